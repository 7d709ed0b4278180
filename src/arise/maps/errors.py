"""Why a map cannot be used, said so the user can act on it."""

from __future__ import annotations

from arise.errors import AriseError


class MapError(AriseError):
    """A map cannot be found or read; the message says what to do."""
