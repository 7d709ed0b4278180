"""Whole files or none: every output is written to a temporary name and renamed
(`arise.atomic`: an unwritable or full folder is one clear OutputError, no leftovers)."""

from __future__ import annotations

from arise.atomic import (
    OutputError,
    copy_file_atomic,
    write_bytes_atomic,
    write_chunks_atomic,
    write_text_atomic,
)

__all__ = [
    "OutputError",
    "copy_file_atomic",
    "write_bytes_atomic",
    "write_chunks_atomic",
    "write_text_atomic",
]
