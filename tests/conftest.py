"""Shared fixtures: the repository layout, a warm validator pool, the CARLA towns."""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

import pytest

from arise.validate import CheckOptions, WorkerPool

# The fast tier's guard (tests/slow_guard.py) and pytester, which tests the guard.
pytest_plugins = ["tests.slow_guard", "pytester"]

REPO = Path(__file__).resolve().parents[1]
DATA = REPO / "tests" / "data"
EXAMPLES = REPO / "examples"


def carla_towns_dir() -> Path | None:
    """The CARLA town maps: ARISE_CARLA_MAPS, or ../shared/maps/CARLA beside the clone."""
    candidates = [os.environ.get("ARISE_CARLA_MAPS"), REPO.parent / "shared" / "maps" / "CARLA"]
    for candidate in candidates:
        if candidate and Path(candidate).is_dir() and any(Path(candidate).glob("*.xodr")):
            return Path(candidate)
    return None


@pytest.fixture(scope="session")
def validator_pool() -> Iterator[WorkerPool]:
    with WorkerPool(size=1) as pool:
        yield pool


@pytest.fixture(scope="session")
def carla_maps() -> Path:
    found = carla_towns_dir()
    if found is None:
        pytest.skip(
            "CARLA town maps not found (set ARISE_CARLA_MAPS or put shared/ beside the clone)"
        )
    return found


@pytest.fixture()
def offline_options() -> CheckOptions:
    return CheckOptions(seed=7, timeout=60)
