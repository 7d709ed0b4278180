"""report.md and runs.csv from hand-built runs with known metrics."""

from __future__ import annotations

import csv
from pathlib import Path

from arise.drive.report import OVERALL, TABLE, table_rows, write_report
from tests.drive.records_cases import driven, failed


def _records() -> list:
    return [
        driven(
            "straight_obstacle/so-1",
            "straight_obstacle",
            collision=1,
            time_spent_s=5.0,
            min_ttc_s=0.0,
        ),
        driven("straight_obstacle/so-2", "straight_obstacle", red_lights_run=1, min_ttc_s=2.0),
        driven("right_turn/rt-1", "right_turn", lane_invasions=3, route_completion=0.5),
        failed(
            "right_turn/rt-2", "right_turn", "compile line 3 [GEOMETRY]: ScenicSyntaxError: bad"
        ),
    ]


def test_the_table_averages_each_category_and_overall() -> None:
    rows = {row.group: row for row in table_rows(_records())}
    assert list(rows) == ["right_turn", "straight_obstacle", OVERALL]
    so, rt, overall = rows["straight_obstacle"], rows["right_turn"], rows[OVERALL]
    assert (so.runs, rt.runs, overall.runs) == (2, 1, 3)  # the failed run is not driven
    assert so.values["collision"] == 0.5 and rt.values["collision"] == 0.0
    assert abs(overall.values["collision"] - 1 / 3) < 1e-9
    assert so.values["red_lights_run"] == 0.5 and so.values["time_spent_s"] == 7.5
    assert rt.values["lane_invasions"] == 3 and rt.values["route_completion"] == 0.5
    assert so.values["min_ttc_s"] == 1.0  # the median of 0 and 2
    assert rt.values["min_ttc_s"] is None  # no run of it came near anything
    assert so.values["conflict_reached"] == 1.0
    assert overall.values["overall_score"] is not None


def test_runs_csv_has_a_row_per_run_and_a_column_per_metric(tmp_path: Path) -> None:
    report, table = write_report(_records(), tmp_path, "idm")
    assert table == tmp_path / "runs.csv"
    with table.open(newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert len(rows) == 4
    header = list(rows[0])
    assert header[:7] == ["scenario", "category", "agent", "run_index", "seed", "status", "map"]
    for column in TABLE:
        assert column.metric in header
    assert header[-3:] == ["seconds", "replay", "message"]
    first, second, third, fourth = rows
    assert (first["scenario"], first["collision"], first["status"]) == (
        "straight_obstacle/so-1",
        "1",
        "driven",
    )
    assert first["replay"] == "collisions/straight_obstacle/so-1-idm-r0/replay.gif"
    assert second["collision"] == "0" and second["red_lights_run"] == "1"
    assert first["min_ttc_s"] == "0.0" and third["min_ttc_s"] == ""
    assert float(third["route_completion"]) == 0.5 and third["agent"] == "idm"
    assert fourth["status"] == "failed" and fourth["collision"] == ""
    assert "ScenicSyntaxError" in fourth["message"]


def test_report_md_has_the_papers_table_collisions_and_failures(tmp_path: Path) -> None:
    report = write_report(_records(), tmp_path, "/home/me/my_agent.py:Careful", ["x: a link"])[0]
    text = report.read_text()
    assert text.startswith("# Driving report: agent my\\_agent.py:Careful\n")
    assert "4 runs of 4 scenarios" in text and "3 driven, 1 did not run" in text
    header = "| category | runs | " + " | ".join(c.label for c in TABLE) + " |"
    assert header in text
    assert "| CR | RR | SS | OR | RF | Comp | TS | ACC | YV | LI | OS | min TTC |" in text
    assert "| straight\\_obstacle | 2 | 0.50 | 0.50 | 0.00 | 0.00 | 0.90 | 1.00 | 7.5 |" in text
    assert "| right\\_turn | 1 | 0.00 | 0.00 | 0.00 | 0.00 | 0.90 | 0.50 | 10.0 |" in text
    assert "| **overall** | 3 | 0.33 |" in text
    assert "## Collisions (1)" in text
    assert "[replay](collisions/straight_obstacle/so-1-idm-r0/replay.gif)" in text
    assert "## Runs that did not drive (1)" in text and "ScenicSyntaxError: bad" in text
    assert "## Left out of the source (1)" in text


def test_untrusted_names_cannot_break_the_table(tmp_path: Path) -> None:
    hostile = driven("evil|cat/x", "evil|cat\n# Title", collision=1)
    text = write_report([hostile], tmp_path, "idm")[0].read_text()
    row = next(line for line in text.splitlines() if line.startswith("| evil"))
    assert row.startswith("| evil\\|cat \\# Title | 1 | 1.00 |")
    assert "\n# Title" not in text


def test_no_collision_and_no_run_still_make_a_report(tmp_path: Path) -> None:
    text = write_report([failed("a", "c", "sample: RejectionException")], tmp_path, "blind")[
        0
    ].read_text()
    assert "No run collided." in text
    assert "| **overall** | 0 | - | - |" in text
