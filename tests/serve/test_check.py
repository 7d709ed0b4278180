"""Checking a pasted script through the server: only in the confined validator, with the
same verdicts as `arise check`, and a replay for a script that runs."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from arise.llm.settings import Settings
from arise.serve.app import create_app, guarded
from arise.serve.config import ServeConfig
from arise.validate import WorkerPool
from tests.conftest import EXAMPLES

pytestmark = pytest.mark.slow


@pytest.fixture()
def client(tmp_path: Path, validator_pool: WorkerPool) -> Iterator[TestClient]:
    config = ServeConfig(runs_dir=tmp_path / "runs")
    app = create_app(config, pool=validator_pool, settings=Settings())
    with TestClient(guarded(config, app), base_url="http://127.0.0.1:8765") as test_client:
        yield test_client


def test_a_script_that_runs_gets_its_verdict_and_replay(client: TestClient) -> None:
    script = (EXAMPLES / "pedestrian_crossing.scenic").read_text(encoding="utf-8")
    result = client.post("/api/check", json={"script": script, "name": "mine.scenic"}).json()
    assert result["ok"], result
    assert result["summary"].startswith("OK:") and result["name"] == "mine.scenic"
    assert result["sandbox"].startswith("landlock")
    assert result["replay"] == "replay.html"
    page = client.get(f"/checks/{result['id']}/files/replay.html")
    assert page.status_code == 200 and "arise_replay" in page.text
    assert client.get(f"/checks/{result['id']}/files/..%2F..%2Fjob.json").status_code == 404


def test_a_broken_or_hostile_script_gets_its_diagnostic(client: TestClient) -> None:
    broken = client.post("/api/check", json={"script": "ego = new Car at (0, 0\n"}).json()
    assert not broken["ok"] and broken["replay"] is None
    assert broken["diagnostic"]["stage"] in ("parse", "compile")
    hostile = "import os\nos.system('touch /tmp/pwned')\n"
    refused = client.post("/api/check", json={"script": hostile}).json()
    assert not refused["ok"] and refused["diagnostic"]["stage"] == "gate"
    assert "os" in refused["diagnostic"]["message"]
