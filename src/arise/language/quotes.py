"""Quotes: is a stretch of words really in the description, and where.

Grounding keeps a model's answer only with a quote that passes `quote_in`; case, spacing
and punctuation do not matter, whole words do.
"""

from __future__ import annotations

import re


def _normal(text: str) -> str:
    text = text.lower().replace("’", "'").replace("`", "'")
    text = re.sub(r"[^a-z0-9' ]+", " ", text)
    return re.sub(r"\s+", " ", text).strip()


def quote_in(description: str, quote: str | None) -> bool:
    """True when `quote` is words of `description` (case, spacing and punctuation aside)."""
    if not quote or not _normal(quote):
        return False
    return f" {_normal(quote)} " in f" {_normal(description)} "


def find_quote(description: str, quote: str) -> tuple[int, int] | None:
    """Where the quote is in the description (character span), or None."""
    words = _normal(quote).split()
    if not words:
        return None
    pattern = r"\W+".join(re.escape(word) for word in words)
    match = re.search(rf"(?<![\w']){pattern}(?![\w'])", description, re.I)
    return match.span() if match else None
