"""The drive database: whole runs saved one by one, read back validated, keyed so a
resumed drive skips what it has."""

from __future__ import annotations

import sqlite3
from pathlib import Path

import pytest

from arise.drive.records import DriveStatus
from arise.drive.runner import DriveConfig, pending, plan, planned_records
from arise.drive.sources import Scenario
from arise.drive.store import DriveStore, DriveStoreError
from tests.drive.records_cases import DIGEST, driven, failed


def test_runs_are_saved_and_read_back_with_their_metrics(tmp_path: Path) -> None:
    database = tmp_path / "drive.sqlite"
    with DriveStore(database) as store:
        store.save(driven("so-1", "straight_obstacle", collision=1, min_ttc_s=0.0))
        store.save(failed("rt-1", "right_turn", "compile line 3: ScenicSyntaxError: no"))
        store.set_meta(agent="idm", runs=1)
    with DriveStore(database) as store:
        first, second = store.records()
        assert store.meta() == {"agent": "idm", "runs": 1}
        assert store.done_keys() == {("so-1", DIGEST, "idm", 0), ("rt-1", DIGEST, "idm", 0)}
    assert first.status is DriveStatus.DRIVEN and first.collided
    assert first.metrics["collision"] == 1 and isinstance(first.metrics["collision"], int)
    assert first.metrics["min_ttc_s"] == 0.0 and first.timeout_s == 30.0
    assert second.status is DriveStatus.FAILED and not second.metrics
    with sqlite3.connect(database) as db:
        rows = list(db.execute("SELECT scenario, status, collision FROM runs ORDER BY id"))
    assert rows == [("so-1", "driven", 1), ("rt-1", "failed", None)]


def test_a_run_done_again_replaces_its_row(tmp_path: Path) -> None:
    with DriveStore(tmp_path / "drive.sqlite") as store:
        store.save(failed("so-1", "straight_obstacle", "timeout"))
        store.save(driven("so-1", "straight_obstacle"))
        [record] = store.records()
    assert record.driven


def test_pending_skips_what_the_store_holds_for_this_agent_seed_and_script(
    tmp_path: Path,
) -> None:
    scenarios = [
        Scenario("so-1", "straight_obstacle", Path("/scripts/so-1.scenic"), DIGEST),
        Scenario("rt-1", "right_turn", Path("/scripts/rt-1.scenic"), DIGEST),
    ]
    tasks = plan(scenarios, DriveConfig(agent="idm", runs=2))
    assert [(t.scenario, t.run_index, t.seed) for t in tasks] == [
        ("so-1", 0, 0),
        ("rt-1", 0, 0),
        ("so-1", 1, 1),
        ("rt-1", 1, 1),
    ]
    with DriveStore(tmp_path / "drive.sqlite") as store:
        store.save(driven("so-1", "straight_obstacle", run=0))
        store.save(driven("so-1", "straight_obstacle", run=1))
        assert [(t.scenario, t.run_index) for t in pending(tasks, store)] == [
            ("rt-1", 0),
            ("rt-1", 1),
        ]
        # Another agent, or an edited script, is not done yet.
        blind = plan(scenarios, DriveConfig(agent="blind"))
        assert len(pending(blind, store)) == 2
        edited = [Scenario("so-1", "straight_obstacle", Path("/s.scenic"), "cd" * 32)]
        assert len(pending(plan(edited, DriveConfig(agent="idm")), store)) == 1
        # The report takes this plan's runs only, in plan order.
        assert [r.task.run_index for r in planned_records(tasks, store)] == [0, 1]
        assert planned_records(blind, store) == []


def test_a_file_that_is_no_database_is_one_line(tmp_path: Path) -> None:
    garbage = tmp_path / "drive.sqlite"
    garbage.write_text("this is not a database" * 100)
    with pytest.raises(DriveStoreError, match="not a drive database"):
        DriveStore(garbage)


def test_a_row_this_arise_cannot_read_is_one_line(tmp_path: Path) -> None:
    database = tmp_path / "drive.sqlite"
    with DriveStore(database) as store:
        store.save(driven("so-1", "straight_obstacle"))
    with sqlite3.connect(database) as db:
        db.execute("UPDATE runs SET record = ?", ('{"task": {}, "status": "teleported"}',))
    with (
        DriveStore(database) as store,
        pytest.raises(DriveStoreError, match="not one this arise reads"),
    ):
        store.records()
