"""A disk store of llama.cpp states after a fixed prompt prefix, shared by every process.

Each new ``arise generate`` process used to re-read the same ~1,000 prompt tokens (system
prompts and few-shot examples) before it could read the ~450 that are new. Here the
model's state right after such a prefix is kept on disk, keyed by the model file's sha256,
the exact prefix tokens and the runtime settings that change the numbers, so a later
process loads it in a fraction of a second instead.

An entry is trusted only when its header names the same key and tokens, and the payload's
sha256 matches; anything else is deleted and rebuilt. Entries are written to a temporary
file and renamed, so a reader never sees half an entry. The folder is kept under a size
bound by dropping the entries used least recently.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import struct
import tempfile
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from arise.paths import cache_dir

_MAGIC = b"ARISEKV1"
_SUFFIX = ".kvstate"
DEFAULT_LIMIT_MB = 512


def default_store_dir() -> Path:
    """``$ARISE_CACHE_DIR/prefix-store`` or the user cache folder's."""
    return cache_dir() / "prefix-store"


def entry_key(model_sha256: str, settings: dict[str, object], tokens: Sequence[int]) -> str:
    """The name of the state after ``tokens`` on this model with these settings."""
    digest = hashlib.sha256()
    digest.update(model_sha256.encode())
    digest.update(json.dumps(settings, sort_keys=True).encode())
    digest.update(struct.pack(f"<{len(tokens)}i", *(int(t) for t in tokens)))
    return digest.hexdigest()[:40]


@dataclass(frozen=True)
class StoredPrefix:
    """One entry read back: the tokens it covers and the llama.cpp state bytes."""

    key: str
    tokens: tuple[int, ...]
    state: bytes


class PrefixStore:
    """Entries are files ``<key>.kvstate``: magic, header length, JSON header, payload."""

    def __init__(self, root: Path | None = None, limit_mb: int = DEFAULT_LIMIT_MB) -> None:
        self.root = root or default_store_dir()
        self.limit_bytes = max(0, limit_mb) << 20
        self.discarded: list[str] = []  # why entries were thrown away (corrupt, stale)

    def path(self, key: str) -> Path:
        return self.root / f"{key}{_SUFFIX}"

    def get(self, key: str, tokens: Sequence[int]) -> StoredPrefix | None:
        """The entry, or None when it is absent; a damaged or mismatched one is deleted."""
        path = self.path(key)
        try:
            blob = path.read_bytes()
        except OSError:
            return None
        problem = _check(blob, key, tokens)
        if isinstance(problem, str):
            self.discarded.append(f"{path.name}: {problem}")
            path.unlink(missing_ok=True)
            return None
        with contextlib.suppress(OSError):
            os.utime(path)  # most recently used: the last to be pruned
        return problem

    def put(self, key: str, tokens: Sequence[int], state: bytes) -> Path | None:
        """Write atomically; None when the entry alone exceeds the bound or the disk fails."""
        size = len(state) + 64 + 8 * len(tokens)
        if size > self.limit_bytes:
            return None
        header = json.dumps(
            {
                "key": key,
                "tokens": [int(t) for t in tokens],
                "payload_sha256": hashlib.sha256(state).hexdigest(),
                "payload_bytes": len(state),
                "created": time.time(),
            }
        ).encode()
        try:
            self.root.mkdir(parents=True, exist_ok=True)
            self._prune(self.limit_bytes - size)
            fd, tmp = tempfile.mkstemp(dir=self.root, prefix=".tmp-", suffix=_SUFFIX)
            with os.fdopen(fd, "wb") as fh:
                fh.write(_MAGIC + struct.pack("<Q", len(header)) + header)
                fh.write(state)
                fh.flush()
                os.fsync(fh.fileno())
            os.replace(tmp, self.path(key))
        except OSError:
            return None
        return self.path(key)

    def entries(self) -> list[Path]:
        if not self.root.is_dir():
            return []
        return sorted(self.root.glob(f"*{_SUFFIX}"), key=lambda p: p.stat().st_mtime)

    def size_bytes(self) -> int:
        return sum(p.stat().st_size for p in self.entries())

    def describe(self) -> str:
        """One line for people: how many entries, how big, the bound, where."""
        return (
            f"{len(self.entries())} entries, {self.size_bytes() / 2**20:.0f} of "
            f"{self.limit_bytes >> 20} MiB at {self.root}"
        )

    def clear(self) -> int:
        """Delete every entry; returns how many."""
        found = self.entries()
        for path in found:
            path.unlink(missing_ok=True)
        return len(found)

    def _prune(self, room: int) -> None:
        """Drop the least recently used entries until the rest fit in ``room`` bytes."""
        for stale in self.root.glob(f".tmp-*{_SUFFIX}"):
            if time.time() - stale.stat().st_mtime > 3600:  # a writer that died
                stale.unlink(missing_ok=True)
        entries = self.entries()
        total = sum(p.stat().st_size for p in entries)
        for path in entries:
            if total <= room:
                break
            total -= path.stat().st_size
            path.unlink(missing_ok=True)


def _check(blob: bytes, key: str, tokens: Sequence[int]) -> StoredPrefix | str:
    """The entry in ``blob`` if it is whole and is the one asked for, else why not."""
    if len(blob) < len(_MAGIC) + 8 or not blob.startswith(_MAGIC):
        return "not a prefix-store entry"
    (length,) = struct.unpack_from("<Q", blob, len(_MAGIC))
    start = len(_MAGIC) + 8
    try:
        header = json.loads(blob[start : start + length])
    except ValueError:
        return "unreadable header"
    if not isinstance(header, dict):
        return "unreadable header"
    payload = blob[start + length :]
    if header.get("key") != key or header.get("tokens") != [int(t) for t in tokens]:
        return "written for other tokens or settings"
    if header.get("payload_bytes") != len(payload):
        return "truncated"
    if header.get("payload_sha256") != hashlib.sha256(payload).hexdigest():
        return "checksum mismatch"
    return StoredPrefix(key=key, tokens=tuple(tokens), state=payload)


def file_sha256(path: Path, cache_root: Path | None = None) -> str:
    """sha256 of a (large) model file, remembered per path, size and mtime so a new
    process does not hash 1 GB again."""
    stat = path.stat()
    ident = f"{path.resolve()}|{stat.st_size}|{stat.st_mtime_ns}"
    memo = (cache_root or default_store_dir()) / "model-hashes.json"
    try:
        known = json.loads(memo.read_text("utf-8"))
    except (OSError, ValueError):
        known = {}
    if not isinstance(known, dict):
        known = {}
    if isinstance(known.get(ident), str):
        return str(known[ident])
    digest = hashlib.sha256()
    with path.open("rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            digest.update(chunk)
    value = digest.hexdigest()
    known[ident] = value
    try:
        memo.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=memo.parent, prefix=".tmp-hashes-")
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            json.dump(known, fh)
        os.replace(tmp, memo)
    except OSError:
        pass
    return value
