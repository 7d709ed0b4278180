"""`arise serve`'s agent pick through the API: a checked script driven by a built-in agent
comes back with its driving metrics beside its replay; the server offers built-ins only."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from arise.drive.report import TABLE
from arise.llm.settings import Settings
from arise.serve.app import create_app, guarded
from arise.serve.checker import CheckStopped, held_request
from arise.serve.config import ServeConfig
from arise.serve.driving import admit_agent
from arise.validate import WorkerPool
from tests.conftest import EXAMPLES

SCRIPT = EXAMPLES / "pedestrian_crossing.scenic"


@pytest.fixture()
def client(tmp_path: Path, validator_pool: WorkerPool) -> Iterator[TestClient]:
    config = ServeConfig(runs_dir=tmp_path / "runs")
    app = create_app(config, pool=validator_pool, settings=Settings())
    with TestClient(guarded(config, app), base_url="http://127.0.0.1:8765") as test_client:
        yield test_client


@pytest.mark.slow
def test_a_script_driven_by_an_agent_comes_with_its_metrics(client: TestClient) -> None:
    agents = [a["name"] for a in client.get("/api/info").json()["agents"]]
    assert agents == ["scripted", "idm", "cautious", "blind"]
    script = SCRIPT.read_text(encoding="utf-8")
    result = client.post("/api/check", json={"script": script, "agent": "idm"}).json()
    assert result["ok"] and result["replay"] == "replay.html", result
    driving = result["driving"]
    assert driving["agent"] == "idm" and driving["error"] is None
    assert [m["label"] for m in driving["metrics"]] == [c.label for c in TABLE]
    values = {m["metric"]: m["value"] for m in driving["metrics"]}
    assert values["collision"] in (0, 1) and driving["collision"] is bool(values["collision"])
    assert 0.0 <= values["route_completion"] <= 1.0 and values["time_spent_s"] > 0
    # Without an agent: the script as it is, and no metrics.
    plain = client.post("/api/check", json={"script": script}).json()
    assert plain["ok"] and plain["driving"] is None


@pytest.mark.slow
def test_the_server_offers_built_in_agents_only(client: TestClient, tmp_path: Path) -> None:
    agent_file = tmp_path / "agent.py"
    agent_file.write_text("raise SystemExit('imported!')\n")
    script = SCRIPT.read_text(encoding="utf-8")
    for name in ("reckless", f"{agent_file}:Agent"):
        answer = client.post("/api/check", json={"script": script, "agent": name})
        assert answer.status_code == 422
        assert answer.json()["error"].startswith(f"unknown agent '{name[:64]}'")
        assert "scripted, idm, cautious, blind" in answer.json()["error"]


def test_the_check_process_cannot_choose_the_agent() -> None:
    """The server holds the check process's run request to the agent it admitted: a
    process that asks for a user's file (or none) runs with the server's choice."""
    asked = {
        "text": "ego = new Car\n",
        "map": {"name": "arise_straight"},
        "options": {"agent": "/tmp/evil.py:Agent", "require_sandbox": False},
    }
    held = held_request(asked, "ego = new Car\n", None, 30.0, "idm")
    assert held["options"]["agent"] == "idm" and held["options"]["seed"] == 0
    assert held_request(asked, "ego = new Car\n", None, 30.0)["options"]["agent"] is None
    with pytest.raises(CheckStopped, match="another script"):
        held_request(asked, "other script\n", None, 30.0, "idm")


@pytest.mark.parametrize(("name", "admitted"), [(None, None), ("", None), (" blind ", "blind")])
def test_admitted_agents(name: str | None, admitted: str | None) -> None:
    assert admit_agent(name) == admitted
