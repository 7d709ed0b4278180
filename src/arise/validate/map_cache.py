"""Scenic's parsed-map cache (`.snet`), written only by a process that never ran a script.

Scenic parses an OpenDRIVE map in 2-8 s and saves the result, a pickle, beside the map;
later compiles load it in a fraction of a second. A pickle is code, so the file must not
come from a worker that ran an untrusted script: workers are confined without write
access to the map cache, and this module prepares the `.snet` in a fresh, confined
process that only parses the map. The parent moves the finished file into place
atomically, under a lock, so concurrent checks never read half a cache. Only maps in the
cache are prepared (`arise.maps.cache`), and the parent loads a `.snet` only from there.
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from arise.errors import AriseError
from arise.maps.cache import PREPARE_LOCK, maps_root
from arise.paths import cache_dir

PREPARE_TIMEOUT = 300.0  # seconds: CARLA's Town04 takes ~8 s idle, far more on a busy box


class MapPreparationError(AriseError):
    """A map could not be parsed into Scenic's road network."""


def cache_file(xodr: Path) -> Path:
    return xodr.with_suffix(".snet")


def prepare_map(xodr: Path) -> None:
    """Make sure the parsed cache of this (cached copy of a) map exists."""
    if xodr.suffix != ".xodr" or cache_file(xodr).exists():
        return
    folder = xodr.parent
    if xodr.is_symlink() or folder.resolve().parent != maps_root().resolve():
        raise MapPreparationError(
            f"{xodr} is not a map in arise's cache; only copies there are prepared"
        )
    with open(folder / PREPARE_LOCK, "a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if cache_file(xodr).exists():
            return
        workspace = Path(tempfile.mkdtemp(prefix=".prepare-", dir=folder))
        try:
            copy = workspace / xodr.name
            shutil.copyfile(xodr, copy)
            env = {
                key: value
                for key, value in os.environ.items()
                if key in ("PATH", "LANG", "PYTHONPATH", "VIRTUAL_ENV", "ARISE_CACHE_DIR")
            }
            env.update(
                HOME=str(workspace),
                TMPDIR=str(workspace),
                PYTHONDONTWRITEBYTECODE="1",
                ARISE_CACHE_DIR=str(cache_dir()),
            )
            try:
                done = subprocess.run(
                    [sys.executable, "-m", "arise.validate.map_cache", str(copy)],
                    cwd=workspace,
                    env=env,
                    capture_output=True,
                    text=True,
                    timeout=PREPARE_TIMEOUT,
                    start_new_session=True,
                )
            except subprocess.TimeoutExpired:
                raise MapPreparationError(
                    f"parsing map {xodr.stem} took longer than {PREPARE_TIMEOUT:g} s"
                ) from None
            if done.returncode != 0 or not cache_file(copy).exists():
                reason = (done.stderr.strip().splitlines() or ["no output"])[-1]
                raise MapPreparationError(f"map {xodr.stem} could not be parsed: {reason}")
            os.replace(cache_file(copy), cache_file(xodr))
        finally:
            shutil.rmtree(workspace, ignore_errors=True)


def _main(path: str) -> int:
    """Child: parse one map, confined to writing its own workspace, and save the cache."""
    from scenic.domains.driving.roads import Network

    from arise.validate.sandbox import confine, python_policy

    workspace = Path(path).parent
    report = confine(python_policy(workspace, read_also=(workspace,)))
    if report.missing:
        print(f"note: confinement incomplete: {report.label}", file=sys.stderr)
    with contextlib.redirect_stdout(sys.stderr):
        Network.fromFile(path, useCache=False, writeCache=True)
    return 0


if __name__ == "__main__":
    sys.exit(_main(sys.argv[1]))
