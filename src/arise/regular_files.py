"""Opening a file someone else may have planted: a regular file within a size limit, or a
refusal that says why. Map files beside a script and the files of a run folder are read
this way: a symbolic link (to a secret, to /dev/zero), a FIFO that never ends, or a
sparse file of gigabytes is refused before a byte of it is read."""

from __future__ import annotations

import contextlib
import errno
import os
import stat
from collections.abc import Iterator
from enum import StrEnum
from pathlib import Path

from arise.errors import AriseError


class Refusal(StrEnum):
    """Why a file was not opened."""

    LINK = "link"
    UNREADABLE = "unreadable"
    NOT_REGULAR = "not_regular"
    TOO_LARGE = "too_large"


class FileRefused(AriseError):
    """The file is not one we read; callers turn `refusal` into their own message."""

    def __init__(self, path: Path, refusal: Refusal, detail: str = "", size: int = 0):
        super().__init__(f"{path}: {refusal.value} {detail}".strip())
        self.path = path
        self.refusal = refusal
        self.detail = detail
        self.size = size


@contextlib.contextmanager
def open_regular(path: Path, limit: int) -> Iterator[tuple[int, os.stat_result]]:
    """An open descriptor of `path` and its status, when it is a regular file (the last
    component no link, no FIFO or device) of at most `limit` bytes; FileRefused otherwise.
    FileNotFoundError passes through, for callers to whom absence is no refusal."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC)
    except FileNotFoundError:
        raise
    except OSError as error:
        refusal = Refusal.LINK if error.errno == errno.ELOOP else Refusal.UNREADABLE
        raise FileRefused(path, refusal, error.strerror or "") from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise FileRefused(path, Refusal.NOT_REGULAR)
        if info.st_size > limit:
            raise FileRefused(path, Refusal.TOO_LARGE, size=info.st_size)
        yield fd, info
    finally:
        os.close(fd)
