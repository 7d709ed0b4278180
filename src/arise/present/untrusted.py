"""Reading a file of a run folder someone handed over: bounded, and only a regular file.

A run folder may come from anyone, so its files are read like input from the network: a
symbolic link (to a secret, to /dev/zero), a FIFO that never ends, or a file of gigabytes
is refused with one line before anything is read.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from arise.present.errors import PresentError
from arise.regular_files import FileRefused, Refusal, open_regular


class UntrustedFileError(PresentError):
    """A file of a run folder is not one we read (a link, not a file, too large, garbled)."""


def _size(size: int) -> str:
    return f"{size / 2**20:,.1f} MiB" if size >= 2**20 else f"{size / 1024:,.0f} KiB"


def read_regular(path: Path, limit: int) -> bytes:
    """The content of `path`, a regular file (no link, FIFO or device) of at most `limit`
    bytes; UntrustedFileError otherwise. FileNotFoundError when it does not exist."""
    try:
        with open_regular(path, limit) as (fd, _):
            chunks = []
            total = 0
            while chunk := os.read(fd, min(1024 * 1024, limit + 1 - total)):
                chunks.append(chunk)
                total += len(chunk)
                if total > limit:
                    raise UntrustedFileError(f"{path} grew past {_size(limit)} while read")
            return b"".join(chunks)
    except FileRefused as refused:
        reason = {
            Refusal.LINK: "is a symbolic link; it is not read",
            Refusal.UNREADABLE: f"cannot be read: {refused.detail}",
            Refusal.NOT_REGULAR: "is not a regular file; it is not read",
            Refusal.TOO_LARGE: f"is {_size(refused.size)}; the limit is {_size(limit)}",
        }[refused.refusal]
        raise UntrustedFileError(f"{path} {reason}") from None


def read_json(path: Path, limit: int) -> Any:
    """The JSON value in `path` (see `read_regular`); UntrustedFileError if it is none."""
    data = read_regular(path, limit)
    try:
        return json.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError) as error:
        reason = str(error).splitlines()[0][:200] if str(error) else type(error).__name__
        raise UntrustedFileError(f"{path} is not valid JSON ({reason})") from None


def read_text(path: Path, limit: int) -> str:
    """The UTF-8 text in `path` (see `read_regular`)."""
    try:
        return read_regular(path, limit).decode("utf-8")
    except UnicodeDecodeError:
        raise UntrustedFileError(f"{path} is not UTF-8 text") from None
