"""Reading a run folder without following a link: every path component under the runs
root is opened with O_NOFOLLOW relative to its parent's descriptor (openat), so a symlink
planted in a run folder, or a run folder that is itself a symlink, is never followed,
and nothing can be swapped for a link between a check and the read.

A run folder may have been handed to the user by someone else: what it holds is untrusted.
Only regular files with one link are read, each up to a size bound; symlinks, FIFOs,
devices, sockets, hard links and oversized files are refused (`Refused`, with why), and
the callers skip them with a note or answer 404.
"""

from __future__ import annotations

import errno
import json
import math
import os
import stat
from collections.abc import Iterator
from enum import StrEnum
from pathlib import Path
from typing import Any, BinaryIO

from arise.serve.errors import NotFound

_CLOEXEC = getattr(os, "O_CLOEXEC", 0)
DIR_FLAGS = os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | _CLOEXEC
# O_NONBLOCK: opening a FIFO must not wait for a writer (it is refused just after).
READ_FLAGS = os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | _CLOEXEC
APPEND_FLAGS = os.O_WRONLY | os.O_APPEND | os.O_CREAT | os.O_NOFOLLOW | _CLOEXEC
#: Errors an open with O_NOFOLLOW gives for a symlink (ELOOP) or a non-directory.
_LINKED = (errno.ELOOP, errno.ENOTDIR, errno.EMLINK)
CHUNK = 64 * 1024


class EntryKind(StrEnum):
    REGULAR = "regular file"
    DIRECTORY = "directory"
    SYMLINK = "symbolic link"
    HARD_LINK = "hard-linked file"
    OTHER = "special file"
    MISSING = "missing"


class Refused(NotFound):
    """An entry the server will not read: a link, a special file, or over its bound."""


def kind_of(mode: int, links: int) -> EntryKind:
    if stat.S_ISLNK(mode):
        return EntryKind.SYMLINK
    if stat.S_ISDIR(mode):
        return EntryKind.DIRECTORY
    if stat.S_ISREG(mode):
        return EntryKind.REGULAR if links == 1 else EntryKind.HARD_LINK
    return EntryKind.OTHER


class Folder:
    """An open directory under the runs root; use as a context manager (closes its fd)."""

    def __init__(self, fd: int, label: str) -> None:
        self.fd = fd
        self.label = label

    @classmethod
    def open(cls, root: Path, *parts: str) -> Folder:
        """`root/parts...`: the root as configured (trusted, links allowed), each part
        below it a real directory, never a link."""
        fd = os.open(root, os.O_RDONLY | os.O_DIRECTORY | _CLOEXEC)
        label = root.name
        try:
            for part in parts:
                inner = _open_dir(fd, part, f"{label}/{part}")
                os.close(fd)
                fd, label = inner, f"{label}/{part}"
        except BaseException:
            os.close(fd)
            raise
        return cls(fd, label)

    def __enter__(self) -> Folder:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        if self.fd >= 0:
            os.close(self.fd)
            self.fd = -1

    def folder(self, name: str) -> Folder:
        """A sub-folder (itself no link)."""
        label = f"{self.label}/{name}"
        return Folder(_open_dir(self.fd, name, label), label)

    def kind(self, name: str) -> EntryKind:
        """What `name` is, without following it."""
        try:
            info = os.stat(name, dir_fd=self.fd, follow_symlinks=False)
        except FileNotFoundError:
            return EntryKind.MISSING
        return kind_of(info.st_mode, info.st_nlink)

    def entries(self) -> Iterator[tuple[str, EntryKind]]:
        """Every entry's name and kind (never followed)."""
        with os.scandir(self.fd) as found:
            for entry in found:
                try:
                    info = entry.stat(follow_symlinks=False)
                except OSError:
                    continue  # gone between the listing and the look
                yield entry.name, kind_of(info.st_mode, info.st_nlink)

    def open_file(self, name: str, max_bytes: int) -> tuple[BinaryIO, int]:
        """`name` opened for reading and its size; `Refused` unless it is a regular,
        singly linked file of at most `max_bytes`."""
        try:
            fd = os.open(name, READ_FLAGS, dir_fd=self.fd)
        except FileNotFoundError:
            raise Refused(f"no file {name!r} in {self.label}") from None
        except OSError as error:
            if error.errno in _LINKED:
                raise Refused(f"{name!r} in {self.label} is a symbolic link") from None
            raise Refused(f"{name!r} in {self.label} cannot be read ({error.strerror})") from None
        try:
            info = os.fstat(fd)
            kind = kind_of(info.st_mode, info.st_nlink)
            if kind is not EntryKind.REGULAR:
                raise Refused(f"{name!r} in {self.label} is a {kind.value}")
            if info.st_size > max_bytes:
                raise Refused(
                    f"{name!r} in {self.label} is {info.st_size} bytes; the limit is {max_bytes}"
                )
            os.set_blocking(fd, True)
            return os.fdopen(fd, "rb"), info.st_size
        except BaseException:
            os.close(fd)
            raise

    def read(self, name: str, max_bytes: int) -> bytes:
        """The whole file (see `open_file`); a file that grew past its bound is refused."""
        handle, _ = self.open_file(name, max_bytes)
        with handle:
            data = handle.read(max_bytes + 1)
        if len(data) > max_bytes:
            raise Refused(f"{name!r} in {self.label} is over {max_bytes} bytes")
        return data

    def read_text(self, name: str, max_bytes: int) -> str | None:
        """The file as UTF-8 text, or None when it is missing, refused or not UTF-8."""
        try:
            return self.read(name, max_bytes).decode("utf-8")
        except (Refused, UnicodeDecodeError):
            return None

    def append_text(self, name: str, text: str) -> None:
        """Append to `name` (created if missing); a link or special file is refused."""
        try:
            fd = os.open(name, APPEND_FLAGS | os.O_NONBLOCK, 0o644, dir_fd=self.fd)
        except OSError as error:
            if error.errno in _LINKED:
                raise Refused(f"{name!r} in {self.label} is a symbolic link") from None
            if error.errno == errno.ENXIO:  # a FIFO nobody reads
                raise Refused(f"{name!r} in {self.label} is a special file") from None
            raise
        with os.fdopen(fd, "ab") as out:
            info = os.fstat(out.fileno())
            if kind_of(info.st_mode, info.st_nlink) is not EntryKind.REGULAR:
                raise Refused(f"{name!r} in {self.label} is not a regular file")
            out.write(text.encode("utf-8"))


def _open_dir(parent: int, name: str, label: str) -> int:
    if not name or name in (".", "..") or "/" in name:
        raise NotFound(f"no folder {label!r}")
    try:
        return os.open(name, DIR_FLAGS, dir_fd=parent)
    except FileNotFoundError:
        raise NotFound(f"no folder {label!r}") from None
    except OSError as error:
        if error.errno in _LINKED:
            raise Refused(f"{label!r} is a symbolic link or not a folder") from None
        raise NotFound(f"folder {label!r} cannot be read ({error.strerror})") from None


def stream(handle: BinaryIO, size: int) -> Iterator[bytes]:
    """The first `size` bytes of an open file, in chunks, then closes it."""
    with handle:
        left = size
        while left > 0:
            chunk = handle.read(min(CHUNK, left))
            if not chunk:
                return
            left -= len(chunk)
            yield chunk


def _finite(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise ValueError(f"{text} is not a finite number")
    return value


def _no_constant(name: str) -> Any:
    raise ValueError(f"{name} is not a number")


def parse_json(text: str) -> Any:
    """JSON from a run folder: NaN, Infinity and numbers too large for a float are
    refused (ValueError), so nothing read back can break a JSON answer or a sum."""
    return json.loads(text, parse_float=_finite, parse_constant=_no_constant)
