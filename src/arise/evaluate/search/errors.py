"""What can stop a search before or while it runs, said in one line."""

from __future__ import annotations

from arise.errors import AriseError


class SearchError(AriseError):
    """A search cannot run: a bad script, option or database."""


class NoFreeParameters(SearchError):
    """The script declares nothing to search over."""


class SamplerUnavailable(SearchError):
    """VerifAI (or what one of its samplers needs, e.g. GPyOpt for 'bo') is missing."""


class StoreMismatch(SearchError):
    """The database holds trials that this search would not have proposed."""
