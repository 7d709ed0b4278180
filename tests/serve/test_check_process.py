"""Script checks run beside the pages, not in their way: while a check is stuck in the
real validator, /api/health and the page still answer; too many checks at once are
refused with 503; a check process that does not answer in time is killed and replaced."""

from __future__ import annotations

import os
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import anyio
import pytest
from fastapi.testclient import TestClient

from arise.generate.options import GenerateOptions
from arise.llm.settings import Settings
from arise.serve.app import create_app, guarded
from arise.serve.checker import CheckStopped, ScriptChecker
from arise.serve.config import ServeConfig
from arise.validate import WorkerPool
from tests.conftest import EXAMPLES

pytestmark = pytest.mark.slow

#: A script that loops at the top level until the validator's time-out kills it.
LOOPING = (EXAMPLES / "pedestrian_crossing.scenic").read_text(encoding="utf-8") + (
    "\nwhile True:\n    pass\n"
)
BROKEN = "ego = new Car at (0, 0\n"


@pytest.fixture()
def client(tmp_path: Path, validator_pool: WorkerPool) -> Iterator[TestClient]:
    config = ServeConfig(
        runs_dir=tmp_path / "runs",
        options=GenerateOptions(check_timeout=4),
        max_queued_checks=0,  # one check at a time, none waiting
    )
    app = create_app(config, pool=validator_pool, settings=Settings())
    with TestClient(guarded(config, app), base_url="http://127.0.0.1:8765") as test_client:
        yield test_client


def test_health_and_the_page_answer_while_a_check_is_stuck(client: TestClient) -> None:
    outcome: dict[str, Any] = {}

    def post() -> None:
        outcome["response"] = client.post("/api/check", json={"script": LOOPING})

    checking = threading.Thread(target=post)
    checking.start()
    deadline = time.monotonic() + 60
    health = client.get("/api/health").json()
    while health["checks"]["running"] == 0 and checking.is_alive():
        assert time.monotonic() < deadline, "the check never started"
        time.sleep(0.05)
        health = client.get("/api/health").json()
    # The check is in flight: the server answers around it.
    assert health["ok"] is True and health["checks"] == {"running": 1, "waiting": 0}
    assert client.get("/").status_code == 200
    assert client.get("/api/info").status_code == 200
    busy = client.post("/api/check", json={"script": BROKEN})
    assert busy.status_code == 503 and "running or waiting already" in busy.json()["error"]
    assert checking.is_alive(), "the check ended before the server was asked"
    checking.join(120)
    response = outcome["response"]
    assert response.status_code == 200, response.text
    result = response.json()
    assert not result["ok"] and result["diagnostic"]["error_type"] in ("Timeout", "CheckTimeout")
    assert client.get("/api/health").json()["checks"] == {"running": 0, "waiting": 0}
    broken = client.post("/api/check", json={"script": BROKEN}).json()  # the next one runs
    assert not broken["ok"] and broken["diagnostic"]["stage"] in ("parse", "compile")


def test_a_check_process_that_does_not_answer_is_killed_and_replaced(
    tmp_path: Path, validator_pool: WorkerPool
) -> None:
    checker = ScriptChecker(validator_pool, budget=0)  # no process answers in 0 s
    folder = tmp_path / "check"
    folder.mkdir()

    async def scenario() -> None:
        checker.warm()
        (stuck,) = checker.pids()
        with pytest.raises(CheckStopped, match="did not read the script"):
            await checker.check(BROKEN, folder, None, 10)
        assert checker.pids() == [] and checker.counts() == {"running": 0, "waiting": 0}
        with pytest.raises(ProcessLookupError):
            os.kill(stuck, 0)  # killed (and reaped), not left running
        checker.budget = 60
        result = await checker.check(BROKEN, folder, None, 10)
        assert not result["ok"] and result["diagnostic"]["stage"] in ("parse", "compile")
        (fresh,) = checker.pids()
        assert fresh != stuck

    try:
        anyio.run(scenario)
    finally:
        checker.close()
