"""`arise search --agent`: every trial with an agent in the ego's seat, and the objectives
that read its drive (SafeBench's overall score, expressions over `arise drive`'s metrics).

The scene: a pedestrian steps off the right sidewalk, timed to meet the ego (the knowledge
base's CrossingBehavior); the search moves its walking speed, its trigger distance and
where it waits. `blind` keeps its speed and hits it; `idm` sees it and yields."""

from __future__ import annotations

import csv
import json
import sqlite3
from pathlib import Path

import pytest
from typer.testing import CliRunner

from arise.cli import app
from arise.evaluate.search import Objective, SamplerKind, SearchConfig, SearchStore
from arise.evaluate.search.runner import search_agent, search_folder_name, search_key
from arise.evaluate.search.store import SCHEMA
from arise.validate import CheckOptions
from tests.conftest import DATA

runner = CliRunner()

CROSSING = """\
# A pedestrian steps off the right sidewalk into the ego's lane, timed to meet it.
param map = localPath('maps/arise_straight.xodr')
param carla_map = 'arise_straight'
model scenic.simulators.carla.model
param weather = 'ClearNoon'

param OPT_WALK_SPEED = Range(1.0, 2.0)
param OPT_TRIGGER = Range(12, 30)
param OPT_AHEAD = Range(30, 50)

behavior AdversaryBehavior():
    do CrossingBehavior(ego, globalParameters.OPT_WALK_SPEED, globalParameters.OPT_TRIGGER)

egoLane = Uniform(*network.lanes)
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(30), facing roadDirection
ego = new Car at egoStart, with behavior FollowLaneBehavior(target_speed=9)

spot = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_AHEAD
walker = new Pedestrian right of spot by 4, facing 90 deg relative to spot.heading,
    with regionContainedIn None, with behavior AdversaryBehavior()

terminate when (distance from ego to egoStart) > 90
"""


@pytest.fixture
def crossing(tmp_path: Path) -> Path:
    path = tmp_path / "crossing.scenic"
    path.write_text(CROSSING, encoding="utf-8")
    return path


def _config(script: Path, agent: str | None) -> SearchConfig:
    return SearchConfig(
        script=script,
        objective=Objective.MIN_TTC,
        sampler=SamplerKind.CE,
        check=CheckOptions(agent=search_agent(agent)),
    )


def test_the_agent_is_in_the_key_only_when_one_is_given(crossing: Path) -> None:
    plain = search_key(CROSSING, _config(crossing, None))
    # The key a search had before agents existed: the scripted ego's searches resume.
    assert plain == search_key(CROSSING, _config(crossing, "scripted"))
    assert search_agent("scripted") is None
    keys = {search_key(CROSSING, _config(crossing, name)) for name in ("blind", "idm")}
    assert len(keys | {plain}) == 3


def test_a_file_agent_is_named_by_its_absolute_path() -> None:
    agent = search_agent(str(DATA / "agents" / "user_agent.py") + ":SteadyAgent")
    assert agent is not None and Path(agent.partition(":")[0]).is_absolute()
    assert search_folder_name(agent) == "search-user_agent.py-SteadyAgent"
    assert search_folder_name(None) == "search"


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--agent", "nosuch"], "unknown agent 'nosuch'"),
        (["--agent", "missing.py:Agent"], "missing.py"),
        (["--agent", "agent.py:not-a-class"], "is not a class name"),
    ],
)
def test_a_bad_agent_is_one_line_before_any_file(
    args: list[str], message: str, crossing: Path, tmp_path: Path
) -> None:
    result = runner.invoke(app, ["search", str(crossing), *args, "--out", str(tmp_path / "o")])
    assert result.exit_code == 2, result.output
    assert message in result.output and "Traceback" not in result.output
    assert not (tmp_path / "o").exists()


def test_report_agent_needs_search_trials(tmp_path: Path) -> None:
    database = tmp_path / "bench.sqlite"
    database.write_bytes(b"")
    result = runner.invoke(app, ["report", str(database), "--agent", "idm"])
    assert result.exit_code == 2
    assert "--agent goes with --search-trials" in result.output


def test_an_old_database_gets_the_new_columns(tmp_path: Path) -> None:
    database = tmp_path / "search.sqlite"
    old = SCHEMA.replace(", agent TEXT\n", "\n").replace(" metrics TEXT,", "")
    assert old != SCHEMA
    with sqlite3.connect(database) as db:
        db.executescript(old)
        db.execute(
            "INSERT INTO searches VALUES ('k', 's', 'x', 'ce', 'min-ttc', 0, 1, '[]', 'now')"
        )
        db.execute(
            "INSERT INTO trials VALUES ('k', 0, '{\"A\": 1}', 1, 2.5, 0, 2.5, 3.0, NULL, 1.0, 'now')"
        )
    with SearchStore(database) as store:
        row = store.search("k")
        assert row is not None and row.agent is None
        (trial,) = store.trials("k").values()
        assert trial.outcome.value == 2.5 and trial.outcome.metrics is None


@pytest.mark.slow
def test_blind_collides_within_a_few_trials_and_the_outputs_name_it(
    crossing: Path, tmp_path: Path
) -> None:
    pytest.importorskip("verifai", reason="the verifai extra is not installed")
    out = tmp_path / "out"
    args = ["search", str(crossing), "--agent", "blind", "--objective", "collision"]
    result = runner.invoke(app, [*args, "--trials", "3", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert "with the agent blind" in result.output
    summary = json.loads((out / "search.json").read_text(encoding="utf-8"))
    assert summary["agent"] == "blind"
    (search,) = summary["searches"]
    assert search["agent"] == "blind" and search["first_collision"] is not None
    assert search["first_found"] == search["first_collision"] <= 3
    # The critical instance's replay was driven by blind, and shows its collision.
    metrics = summary["critical_metrics"]
    assert metrics["collision"] == 1 and metrics["overall_score"] < 0.6
    trace = json.loads((out / "critical" / "trace.json").read_text(encoding="utf-8"))
    assert "BlindAgent" in json.dumps(trace)
    header = (out / "critical" / "scenario.scenic").read_text(encoding="utf-8")
    assert "The agent 'blind' drove the ego" in header
    assert "arise drive scenario.scenic --agent blind --seed 0" in header
    assert (out / "critical" / "replay.gif").is_file()
    with (out / "trials.csv").open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert {r["agent"] for r in rows} == {"blind"}
    assert all(0.0 <= float(r["overall_score"]) <= 1.0 for r in rows if r["ok"] == "1")
    with sqlite3.connect(out / "search.sqlite") as db:
        assert db.execute("SELECT agent FROM searches").fetchall() == [("blind",)]


@pytest.mark.slow
def test_score_and_a_drive_metric_expression_are_minimised_end_to_end(
    crossing: Path, tmp_path: Path
) -> None:
    pytest.importorskip("verifai", reason="the verifai extra is not installed")
    out = tmp_path / "out"
    base = ["search", str(crossing), "--trials", "2", "--no-replay", "--out", str(out)]
    scored = runner.invoke(app, [*base, "--agent", "blind", "--objective", "score"])
    assert scored.exit_code == 0, scored.output
    expression = "overall_score + 0.1 * red_lights_run + pet_s / 100"
    custom = runner.invoke(
        app, [*base, "--agent", "idm", "--objective", "custom", "--expression", expression]
    )
    assert custom.exit_code == 0, custom.output
    with sqlite3.connect(out / "search.sqlite") as db:
        searches = dict(db.execute("SELECT key, objective || ':' || agent FROM searches"))
        rows = db.execute("SELECT search, ok, value, metrics FROM trials").fetchall()
    assert sorted(searches.values()) == ["custom:idm", "score:blind"]
    assert len(rows) == 4
    for key, ok, value, metrics_json in rows:
        assert ok, rows
        metrics = json.loads(metrics_json)
        if searches[key] == "score:blind":  # SafeBench's score of blind's drive, as it is
            assert value == pytest.approx(metrics["overall_score"], abs=1e-4)
        else:  # pet_s may be empty: then it reads 10 s
            pet = metrics["pet_s"] if metrics["pet_s"] is not None else 10.0
            wanted = metrics["overall_score"] + 0.1 * metrics["red_lights_run"] + pet / 100
            assert value == pytest.approx(wanted, abs=1e-3)
    # idm yields to the walker: its drive scores better than blind's collision.
    by_agent = {searches[k]: v for k, _, v, _ in rows}
    assert by_agent["custom:idm"] > by_agent["score:blind"]


@pytest.mark.slow
def test_a_users_agent_file_drives_every_trial(crossing: Path, tmp_path: Path) -> None:
    pytest.importorskip("verifai", reason="the verifai extra is not installed")
    agent = f"{DATA / 'agents' / 'user_agent.py'}:SteadyAgent"
    out = tmp_path / "out"
    args = ["search", str(crossing), "--agent", agent, "--trials", "1", "--no-replay"]
    result = runner.invoke(app, [*args, "--out", str(out)])
    assert result.exit_code == 0, result.output
    summary = json.loads((out / "search.json").read_text(encoding="utf-8"))
    assert summary["agent"] == "user_agent.py:SteadyAgent"
    assert summary["searches"][0]["ran"] == 1
    missing = runner.invoke(
        app,
        ["search", str(crossing), "--agent", f"{DATA / 'agents' / 'user_agent.py'}:Nope"]
        + ["--trials", "2", "--no-replay", "--out", str(tmp_path / "nope")],
    )
    assert missing.exit_code == 2 and "Nope" in missing.output
    with sqlite3.connect(tmp_path / "nope" / "search.sqlite") as db:
        assert db.execute("SELECT count(*) FROM trials").fetchone() == (0,)


@pytest.mark.slow
def test_until_found_stops_at_the_first_failure_and_resumes_into_the_full_search(
    crossing: Path, tmp_path: Path
) -> None:
    pytest.importorskip("verifai", reason="the verifai extra is not installed")
    out = tmp_path / "out"
    args = ["search", str(crossing), "--agent", "blind", "--objective", "collision"]
    args += ["--trials", "6", "--out", str(out), "--no-replay"]
    first = runner.invoke(app, [*args, "--until-found"])
    assert first.exit_code == 0, first.output
    (stopped,) = json.loads((out / "search.json").read_text(encoding="utf-8"))["searches"]
    assert stopped["first_found"] is not None
    assert stopped["trials"] == stopped["first_found"] < 6, "no trial after the first failure"
    again = runner.invoke(app, args)  # the same search, every trial: it resumes
    assert again.exit_code == 0, again.output
    (full,) = json.loads((out / "search.json").read_text(encoding="utf-8"))["searches"]
    assert full["trials"] == 6 and full["first_found"] == stopped["first_found"]
    assert full["resumed"] == stopped["trials"]
