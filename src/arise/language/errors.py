"""Errors of the language layer: a rule file that cannot be read is a bug in our data."""

from __future__ import annotations

from arise.errors import AriseError


class RuleError(AriseError):
    """A reading rule or the lexicon is malformed (an unknown class, a bad pattern, an
    example that does not give its facts)."""

    exit_code = 1
