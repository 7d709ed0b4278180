"""The Scenic internals arise patches (arise.validate.scenic_patches) still look as expected.

A Scenic release that moves them must fail here, loudly, not give traces without
headings or re-parse every map in silence.
"""

from __future__ import annotations

import tomllib
from importlib.metadata import version
from pathlib import Path

import pytest

from arise.validate import CheckOptions, WorkerPool, check, scenic_patches

REPO = Path(__file__).resolve().parents[2]


def test_patched_internals_have_the_expected_shape() -> None:
    assert scenic_patches.check_shapes() == []


def test_the_pin_says_why() -> None:
    """The upper bound on Scenic is what the patches were written for."""
    text = (REPO / "pyproject.toml").read_text(encoding="utf-8")
    dependencies = tomllib.loads(text)["project"]["dependencies"]
    assert any(d.startswith("scenic") and "<3.2" in d for d in dependencies)
    assert version("scenic").startswith("3.1")


@pytest.mark.slow
def test_a_worker_trace_carries_heading_and_speed(validator_pool: WorkerPool) -> None:
    result = check(
        REPO / "examples" / "pedestrian_crossing.scenic",
        CheckOptions(seed=1, steps=20),
        pool=validator_pool,
    )
    assert result.ok and result.simulation is not None
    ego = next(a for a in result.simulation.agents if a.is_ego)
    assert any(point.speed > 0 for point in ego.trajectory)
    assert len({point.heading for point in ego.trajectory}) >= 1
