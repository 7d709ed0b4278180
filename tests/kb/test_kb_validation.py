"""Every entry runs: composed into complete scripts and executed by the real validator."""

from __future__ import annotations

import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from arise.kb.loader import load_kb
from arise.kb.runner import validate_kb
from arise.validate import WorkerPool

BROKEN_BEHAVIOR = """
entries:
  - id: behavior.deliberately_broken
    descriptions: [A behavior that reads a name nobody defines.]
    snippet: |
      behavior AdversaryBehavior():
          do FollowLaneBehavior(target_speed=noSuchSpeed)
    defines: [AdversaryBehavior]
    needs: [advLane]
    adversaries: [Car]
    companions: [spawn.lead_same_lane, geometry.straight_road]
"""


@pytest.fixture(scope="module")
def kb_pool() -> Iterator[WorkerPool]:
    with WorkerPool(size=2) as pool:
        yield pool


@pytest.mark.slow
def test_every_entry_passes_the_validator(kb_pool: WorkerPool) -> None:
    kb = load_kb(builtin=True)
    started = time.monotonic()
    report = validate_kb(kb, pool=kb_pool)
    assert report.ok, report.summary()
    assert report.pass_rate() == 1.0 and len(report.checked) == len(kb) >= 150
    assert time.monotonic() - started < 600


@pytest.mark.slow
def test_a_broken_entry_fails_with_its_id(kb_pool: WorkerPool, tmp_path: Path) -> None:
    (tmp_path / "behavior.yaml").write_text(BROKEN_BEHAVIOR, encoding="utf-8")
    kb = load_kb([tmp_path])
    report = validate_kb(kb, only=["behavior.deliberately_broken"], pool=kb_pool)
    assert not report.ok
    assert "behavior.deliberately_broken" in report.failures()
    summary = report.summary()
    assert "FAILED behavior.deliberately_broken" in summary and "noSuchSpeed" in summary


@pytest.mark.slow
def test_a_lint_failure_is_reported_against_the_entry(kb_pool: WorkerPool, tmp_path: Path) -> None:
    (tmp_path / "misc.yaml").write_text(
        """
entries:
  - id: misc.scenic2_cone
    descriptions: [A cone written the Scenic 2 way.]
    snippet: "oldCone = Cone ahead of ego by 30"
    defines: [oldCone]
""",
        encoding="utf-8",
    )
    report = validate_kb(load_kb([tmp_path]), only=["misc.scenic2_cone"], pool=kb_pool)
    assert not report.ok
    reasons = report.failures()["misc.scenic2_cone"]
    assert any("Scenic 2 object creation" in reason for reason in reasons), reasons


@pytest.mark.slow
@pytest.mark.carla_towns
def test_entries_also_run_on_carla_towns(kb_pool: WorkerPool, carla_maps: Path) -> None:
    """The same plan on CARLA's towns (maps chosen by their known features).

    Not 100%: a few compositions need a two-way road where a town's road is one-way, and the
    offline world model's traffic-light lookup trips on junction-less maneuvers of Town10HD.
    """
    from arise.maps.registry import MapRegistry
    from arise.validate import CheckOptions

    registry = MapRegistry(carla_maps)
    towns = {
        name: entry.features
        for name, entry in registry.entries.items()
        if entry.source == "map-dir" and entry.features
    }
    report = validate_kb(
        load_kb(),
        pool=kb_pool,
        maps=towns,
        options=CheckOptions(seed=1, steps=200, timeout=180, map_dir=str(carla_maps)),
    )
    ran = sum(o.ok for o in report.outcomes) / len(report.outcomes)
    assert ran >= 0.9, report.summary()
    assert {o.composition.map_name for o in report.outcomes} <= set(towns)
