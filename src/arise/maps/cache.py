"""The map cache: a copy of every map a check ran on, keyed by the digest of its content.

`cache_dir()/maps/<digest>/NAME.xodr`, with Scenic's parsed `NAME.snet` beside it, written
only by the confined preparer (`arise.validate.map_cache`). Scenic's `.snet` is a pickle,
so the parent loads one only from a folder this module vouches for (`trusted_entry`): a
path inside the cache, no symbolic link on the way, and content whose digest is the
folder's name. A map file handed to us (beside a script, in --map-dir) is copied in
chunks while it is hashed, never read whole, and only when it is a regular file below
`MAX_MAP_BYTES`. The cache is trimmed to `MAP_CACHE_BUDGET_BYTES`, least recently used
folders first; a folder used in the last `MAP_CACHE_IN_USE_SECONDS` or holding one of our
own maps is never evicted, so no run loses the map it is using.
"""

from __future__ import annotations

import contextlib
import fcntl
import hashlib
import os
import re
import shutil
import stat
import tempfile
import time
from collections.abc import Iterator
from functools import cache
from importlib import resources
from pathlib import Path

from arise.limits import MAP_CACHE_BUDGET_BYTES, MAP_CACHE_IN_USE_SECONDS, MAX_MAP_BYTES
from arise.maps.choice import is_safe_map_name
from arise.maps.errors import MapError
from arise.paths import cache_dir
from arise.regular_files import FileRefused, Refusal, open_regular

DIGEST_LENGTH = 16  # hex digits of sha256 that name a cache folder
CHUNK = 1024 * 1024
PREPARE_LOCK = ".prepare.lock"  # held by arise.validate.map_cache while it parses a map
_DIGEST = re.compile(rf"^[0-9a-f]{{{DIGEST_LENGTH}}}$")
_INCOMING = ".incoming-"
_EVICTED = ".evicted-"
# (device, inode, size, mtime) of a file already hashed in this process -> its digest.
_known: dict[tuple[int, int, int, int], str] = {}


def maps_root() -> Path:
    """The cache's map folder, as a real path (so its entries compare equal to their own
    resolved paths in `trusted_entry`)."""
    root = cache_dir() / "maps"
    root.mkdir(parents=True, exist_ok=True)
    return root.resolve()


def _mib(size: int) -> str:
    return f"{size / 2**20:,.0f} MiB" if size < 2**30 else f"{size / 2**30:,.1f} GiB"


@contextlib.contextmanager
def open_map_file(path: Path) -> Iterator[tuple[int, os.stat_result]]:
    """An open map file that is a regular file (no symbolic link, device or FIFO) within
    the size limit; raises MapError otherwise."""
    try:
        with open_regular(path, MAX_MAP_BYTES) as opened:
            yield opened
    except FileNotFoundError as error:
        raise MapError(f"map file {path} cannot be read: {error.strerror}") from None
    except FileRefused as refused:
        reason = {
            Refusal.LINK: "is a symbolic link; give the file itself",
            Refusal.UNREADABLE: f"cannot be read: {refused.detail}",
            Refusal.NOT_REGULAR: "is not a regular file",
            Refusal.TOO_LARGE: f"is {_mib(refused.size)}; the limit is "
            f"{_mib(MAX_MAP_BYTES)} (no road map is that large)",
        }[refused.refusal]
        raise MapError(f"map file {path} {reason}") from None


def _chunks(fd: int, path: Path) -> Iterator[bytes]:
    """The file's content in chunks, from its start, never more than the size limit."""
    os.lseek(fd, 0, os.SEEK_SET)
    total = 0
    while chunk := os.read(fd, CHUNK):
        total += len(chunk)
        if total > MAX_MAP_BYTES:
            raise MapError(f"map file {path} grew past {_mib(MAX_MAP_BYTES)} while read")
        yield chunk


def _digest_of(fd: int, path: Path) -> str:
    digest = hashlib.sha256()
    for chunk in _chunks(fd, path):
        digest.update(chunk)
    return digest.hexdigest()[:DIGEST_LENGTH]


def file_digest(path: Path) -> str:
    """The cache key of a map file (MapError for what is no map file we accept)."""
    with open_map_file(path) as (fd, _):
        return _digest_of(fd, path)


def _touch(folder: Path) -> None:
    """Mark a cache folder used now (a read-only cache is used as it is)."""
    with contextlib.suppress(OSError):
        os.utime(folder)


def _is_regular(path: Path) -> bool:
    try:
        return stat.S_ISREG(path.lstat().st_mode)
    except OSError:
        return False


def cached_copy(path: Path, name: str | None = None) -> Path:
    """The cache's copy of a map file, made now if needed (see the module's docstring).
    `name` is the map's name (default: the file's stem)."""
    name = path.stem if name is None else name
    if not is_safe_map_name(name):
        raise MapError(
            f"map file {path.name!r} has no plain name: use letters, digits, '_', '.' and "
            "'-' (at most 64, not starting with a dot)"
        )
    root = maps_root()
    with open_map_file(path) as (fd, info):
        key = (info.st_dev, info.st_ino, info.st_size, info.st_mtime_ns)
        digest = _known.get(key) or _digest_of(fd, path)
        folder = root / digest
        target = folder / f"{name}.xodr"
        _touch(folder)  # before the look: an evictor that moved it meanwhile puts it back
        if _is_regular(target):
            _known[key] = digest
            return target
        _copy_in(fd, path, root, target)
        _known[key] = digest
    evict(keep=folder)
    return target


def _copy_in(fd: int, path: Path, root: Path, target: Path) -> None:
    """Stream the open file into `target`, hashing as it goes; whole or not at all."""
    handle, temporary = tempfile.mkstemp(prefix=_INCOMING, suffix=".xodr", dir=root)
    try:
        digest = hashlib.sha256()
        with os.fdopen(handle, "wb") as out:
            for chunk in _chunks(fd, path):
                digest.update(chunk)
                out.write(chunk)
        if digest.hexdigest()[:DIGEST_LENGTH] != target.parent.name:
            raise MapError(f"map file {path} changed while it was copied; try again")
        os.chmod(temporary, 0o644)
        target.parent.mkdir(exist_ok=True)
        os.replace(temporary, target)
    except OSError as error:
        raise MapError(f"cannot copy map {path} into the cache {root}: {error}") from None
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(temporary)


def trusted_entry(path: str | os.PathLike[str]) -> Path | None:
    """`path` itself when it is a map in our cache whose content matches its folder's
    digest, reached without symbolic links; else None. Only such a map's `.snet` may be
    loaded (Scenic unpickles it)."""
    given = Path(os.path.abspath(path))
    root = maps_root()
    try:
        real = given.resolve(strict=True)
    except (OSError, RuntimeError):
        return None
    if real != given or real.parent.parent != root or real.suffix != ".xodr":
        return None
    if not _DIGEST.fullmatch(real.parent.name) or not is_safe_map_name(real.stem):
        return None
    try:
        with open_map_file(real) as (fd, _):
            if _digest_of(fd, real) != real.parent.name:
                return None
    except MapError:
        return None
    snet = real.with_suffix(".snet")
    if os.path.lexists(snet) and not _is_regular(snet):
        return None
    return real


@cache
def builtin_digests() -> frozenset[str]:
    """Cache folders of the maps we ship: never evicted (they are small and always used)."""
    folder = Path(str(resources.files("arise.maps").joinpath("data")))
    found = set()
    for path in folder.glob("*.xodr"):
        with contextlib.suppress(MapError):
            found.add(file_digest(path))
    return frozenset(found)


def _size(folder: Path) -> int:
    total = 0
    for parent, _, files in os.walk(folder):
        for file in files:
            with contextlib.suppress(OSError):
                total += os.lstat(os.path.join(parent, file)).st_size
    return total


def evict(
    keep: Path | None = None,
    budget: int = MAP_CACHE_BUDGET_BYTES,
    in_use: float = MAP_CACHE_IN_USE_SECONDS,
) -> list[str]:
    """Trim the map cache to `budget` bytes, least recently used folders first; returns
    the digests evicted. Never evicts `keep`, a folder used within `in_use` seconds, one
    of our own maps or a folder whose map is being parsed."""
    root = maps_root()
    now = time.time()
    folders: list[tuple[int, int, Path]] = []
    total = 0
    for entry in root.iterdir():
        try:
            info = entry.lstat()
        except OSError:
            continue
        if entry.name.startswith((_INCOMING, _EVICTED)):  # left by a killed process
            if now - info.st_mtime > in_use:
                _remove(entry)
            continue
        if not stat.S_ISDIR(info.st_mode) or not _DIGEST.fullmatch(entry.name):
            continue
        size = _size(entry)
        total += size
        folders.append((info.st_mtime_ns, size, entry))
    evicted: list[str] = []
    protected = builtin_digests()
    for used_ns, size, folder in sorted(folders):
        if total <= budget:
            break
        if folder == keep or now - used_ns / 1e9 < in_use or folder.name in protected:
            continue
        if _evict_one(root, folder, used_ns):
            total -= size
            evicted.append(folder.name)
    return evicted


def _evict_one(root: Path, folder: Path, used_ns: int) -> bool:
    """Move the folder aside atomically (a reader sees it whole or not at all), unless its
    map is being parsed or it was used after we looked; then delete it."""
    try:  # the lock exists once a map was parsed here; opening it changes nothing
        lock = open(folder / PREPARE_LOCK)  # noqa: SIM115  (held across the rename)
    except FileNotFoundError:
        lock = None
    except OSError:
        return False
    aside = root / f"{_EVICTED}{folder.name}-{os.getpid()}"
    try:
        if lock is not None:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        os.rename(folder, aside)
        if aside.stat().st_mtime_ns != used_ns:  # used between our look and the move
            os.rename(aside, folder)
            return False
    except OSError:
        return False
    finally:
        if lock is not None:
            lock.close()
    _remove(aside)
    return True


def _remove(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        with contextlib.suppress(OSError):
            path.unlink()
