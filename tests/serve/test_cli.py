"""`arise serve` on the command line: what it refuses before binding, and what it serves."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import uvicorn
from typer.testing import CliRunner

from arise.cli import app
from arise.serve.guard import Guard
from tests.serve.conftest import CASSETTE


def test_another_address_without_a_token_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("ARISE_SERVE_TOKEN", raising=False)
    result = CliRunner().invoke(app, ["serve", "--host", "0.0.0.0"])
    assert result.exit_code == 2
    assert "--host 0.0.0.0 lets other machines reach the server" in result.output


def test_a_missing_cassette_is_a_usage_error(tmp_path: Path) -> None:
    result = CliRunner().invoke(app, ["serve", "--replay", str(tmp_path / "none.jsonl")])
    assert result.exit_code == 2 and "no such cassette" in result.output


def test_it_serves_the_guarded_app_with_the_token(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    served: dict[str, Any] = {}
    monkeypatch.setattr(uvicorn, "run", lambda app, **kw: served.update(app=app, **kw))
    result = CliRunner().invoke(
        app,
        ["serve", "--host", "0.0.0.0", "--port", "9123", "--runs-dir", str(tmp_path)]
        + ["--replay", str(CASSETTE)],
        env={"ARISE_SERVE_TOKEN": "token-from-env"},
    )
    assert result.exit_code == 0, result.output
    assert "open http://0.0.0.0:9123/?token=token-from-env" in result.output
    assert served["host"] == "0.0.0.0" and served["port"] == 9123
    guard = served["app"]
    assert isinstance(guard, Guard) and guard.token == "token-from-env" and not guard.loopback
