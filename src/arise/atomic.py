"""Whole files or none: every output is written to a temporary name beside it and renamed.

A folder that cannot take the file (read-only, full, not a folder, no permission) is an
`OutputError` that names the folder and the reason, and no temporary file stays behind.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Iterable
from pathlib import Path

from arise.errors import AriseError

#: Outputs are meant to be shared (mkstemp makes 0600).
OUTPUT_MODE = 0o644


class OutputError(AriseError):
    """An output file cannot be written where it was asked for."""


def _reason(error: OSError) -> str:
    return error.strerror or type(error).__name__


def write_chunks_atomic(path: Path, chunks: Iterable[bytes], mode: int = OUTPUT_MODE) -> Path:
    """Write `chunks` to `path` whole, or raise OutputError and leave nothing behind."""
    folder = path.parent
    temporary: str | None = None
    try:
        folder.mkdir(parents=True, exist_ok=True)
        handle, temporary = tempfile.mkstemp(prefix=f".{path.name}.", dir=folder)
        with os.fdopen(handle, "wb") as out:
            for chunk in chunks:
                out.write(chunk)
            out.flush()
            os.fsync(out.fileno())
        os.chmod(temporary, mode)
        os.replace(temporary, path)
        temporary = None
    except OSError as error:
        raise OutputError(f"cannot write {path.name} in {folder}: {_reason(error)}") from None
    finally:
        if temporary is not None:
            with contextlib.suppress(OSError):
                os.unlink(temporary)
    return path


def write_bytes_atomic(path: Path, data: bytes, mode: int = OUTPUT_MODE) -> Path:
    return write_chunks_atomic(path, (data,), mode)


def write_text_atomic(path: Path, text: str, mode: int = OUTPUT_MODE) -> Path:
    return write_bytes_atomic(path, text.encode("utf-8"), mode)


def copy_file_atomic(
    source: Path, target: Path, chunk: int = 1024 * 1024, mode: int = OUTPUT_MODE
) -> Path:
    """Copy a file we chose (e.g. a map from our cache) in chunks, whole or not at all."""

    def chunks() -> Iterable[bytes]:
        with open(source, "rb") as handle:
            while block := handle.read(chunk):
                yield block

    return write_chunks_atomic(target, chunks(), mode)
