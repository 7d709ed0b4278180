"""Fixtures of the server's tests: an app on a scripted runner, behind its guard."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

from arise.llm.settings import Settings
from arise.serve.app import create_app, guarded
from arise.serve.config import ServeConfig
from arise.validate import WorkerPool
from tests.generate_cases import CASES
from tests.serve.scripted import ScriptedRunner

CASSETTE = CASES["first_try"].cassette
DESCRIPTION = CASES["first_try"].description

MakeClient = Callable[..., TestClient]


@pytest.fixture()
def runner() -> ScriptedRunner:
    return ScriptedRunner()


@pytest.fixture()
def make_client(tmp_path: Path, runner: ScriptedRunner) -> Iterator[MakeClient]:
    """`make_client(**config)`: a started app (lifespan run) on the scripted runner, with
    the built-in provider presets only (no user config) and a pool that starts no worker
    unless a test checks a script."""
    clients: list[TestClient] = []
    pool = WorkerPool(size=1)

    def make(*, host: str = "127.0.0.1", base_url: str | None = None, **values: Any) -> TestClient:
        values.setdefault("runs_dir", tmp_path / "runs")
        values.setdefault("replay", str(CASSETTE))
        config = ServeConfig(host=host, **values)
        app = create_app(config, pool=pool, make_runner=lambda choice: runner, settings=Settings())
        client = TestClient(
            guarded(config, app),
            base_url=base_url or "http://127.0.0.1:8765",
            raise_server_exceptions=False,
        )
        client.__enter__()
        clients.append(client)
        return client

    yield make
    runner.release.set()
    for client in clients:
        client.__exit__(None, None, None)
    pool.close()
