"""The server's API on a scripted runner: jobs, their stream, the queue, cancel, the run
view, downloads, limits, the token and the host check, and a restart."""

from __future__ import annotations

import io
import json
import time
import zipfile
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from arise.generate.run import RunStatus
from arise.serve.config import ServeConfig
from arise.serve.errors import UnsafeBinding
from tests.serve.conftest import DESCRIPTION, MakeClient
from tests.serve.scripted import ScriptedRunner


def wait_state(client: TestClient, job_id: str, *states: str, timeout: float = 10) -> dict:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        job = client.get(f"/api/jobs/{job_id}").json()
        if job["state"] in states:
            return job
        time.sleep(0.02)
    raise AssertionError(f"job {job_id} never reached {states}: {job}")


def submit(client: TestClient, description: str = DESCRIPTION) -> dict:
    response = client.post("/api/jobs", json={"description": description})
    assert response.status_code == 201, response.text
    return response.json()


def stream(client: TestClient, job_id: str) -> list[tuple[str, dict]]:
    """The job's SSE stream, read to its end, as (event name, data) pairs."""
    found: list[tuple[str, dict]] = []
    name = ""
    with client.stream("GET", f"/api/jobs/{job_id}/events") as response:
        assert response.headers["content-type"].startswith("text/event-stream")
        for line in response.iter_lines():
            if line.startswith("event:"):
                name = line.split(":", 1)[1].strip()
            elif line.startswith("data:"):
                found.append((name, json.loads(line.split(":", 1)[1])))
    return found


def test_info_offers_the_cassette_first_and_the_examples(make_client: MakeClient) -> None:
    info = make_client().get("/api/info").json()
    assert info["default"]["provider"] == "replay"
    assert info["models"][0]["label"] == "replayed from first_try.jsonl"
    assert any(not m["ready"] and "OPENAI_API_KEY" in m["note"] for m in info["models"])
    assert len(info["examples"]) >= 8
    assert info["limits"]["description_chars"] == 2000


def test_the_page_and_its_files_are_served_with_a_strict_policy(make_client: MakeClient) -> None:
    client = make_client()
    page = client.get("/")
    assert page.status_code == 200 and "<title>arise" in page.text
    assert "default-src 'self'" in page.headers["content-security-policy"]
    assert page.headers["x-content-type-options"] == "nosniff"
    for name in ("app.js", "app.css"):
        assert client.get(f"/static/{name}").status_code == 200
    assert "http" not in client.get("/static/app.js").text.replace("http://", "")  # no CDN


def test_a_job_streams_every_stage_and_ends_done(
    make_client: MakeClient, runner: ScriptedRunner
) -> None:
    client = make_client()
    job = submit(client)
    assert job["state"] in ("queued", "running") and job["key"] == "replay/first_try.jsonl"
    events = stream(client, job["id"])
    names = [name for name, _ in events]
    stages = [data["stage"] for name, data in events if name == "stage"]
    assert stages == ["extract", "retrieve", "assemble", "validate", "repair"]
    assert names[0] == "state" and names.count("attempt") == 2 and "done" in names
    assert events[-1] == (
        "state",
        {"event": "state", "state": "done", "message": events[-2][1]["summary"]},
    )
    assert runner.descriptions == [DESCRIPTION]
    assert wait_state(client, job["id"], "done")["run_status"] == "executed"


def test_the_run_view_shows_sections_repaired_lines_and_files(make_client: MakeClient) -> None:
    client = make_client()
    job = submit(client)
    wait_state(client, job["id"], "done")
    view = client.get(f"/api/runs/{job['id']}").json()
    assert view["report"]["status"] == "executed"
    assert [s["name"] for s in view["script"]["sections"]] == ["HEADER", "BEHAVIOR", "SPAWN"]
    changed = [line for line in view["script"]["lines"] if line["attempt"] > 0]
    assert [(line["number"], line["section"], line["kind"]) for line in changed] == [
        (6, "BEHAVIOR", "rule")
    ]
    assert [a["kind"] for a in view["attempts"]] == ["initial", "rule"]
    assert "NameError" in view["attempts"][0]["diagnostic"]
    assert "+    do FollowLaneBehavior" in view["attempts"][1]["diff"]
    assert view["files"] == [
        "scenario.scenic",
        "scenario.xosc",
        "report.json",
        "replay.html",
        "arise_straight.xodr",
    ]


def test_the_download_holds_the_run_files_and_nothing_else(make_client: MakeClient) -> None:
    client = make_client()
    job = submit(client)
    wait_state(client, job["id"], "done")
    response = client.get(f"/runs/{job['id']}/download.zip")
    assert response.status_code == 200
    assert response.headers["content-type"] == "application/zip"
    names = zipfile.ZipFile(io.BytesIO(response.content)).namelist()
    assert sorted(Path(n).name for n in names) == sorted(
        ["scenario.scenic", "scenario.xosc", "arise_straight.xodr", "report.json", "replay.html"]
    )
    replay = client.get(f"/runs/{job['id']}/files/replay.html")
    assert replay.status_code == 200 and "sandbox" in replay.headers["content-security-policy"]


@pytest.mark.parametrize(
    "name", ["..%2Fjob.json", ".hidden", "attempts", "..", "%2Fetc%2Fpasswd", "nope.txt"]
)
def test_files_come_only_from_the_runs_own_folder(make_client: MakeClient, name: str) -> None:
    client = make_client()
    job = submit(client)
    wait_state(client, job["id"], "done")
    assert client.get(f"/runs/{job['id']}/files/{name}").status_code == 404


def test_bad_run_ids_and_symlinks_are_not_found(make_client: MakeClient, tmp_path: Path) -> None:
    client = make_client()
    job = submit(client)
    wait_state(client, job["id"], "done")
    secret = tmp_path / "secret.txt"
    secret.write_text("secret", encoding="utf-8")
    (tmp_path / "runs" / job["id"] / "link.txt").symlink_to(secret)
    assert client.get(f"/runs/{job['id']}/files/link.txt").status_code == 404
    for bad in ("..", "20260101-000000-zzzzzz", "x" * 30):
        assert client.get(f"/runs/{bad}/files/report.json").status_code == 404
        assert client.get(f"/api/runs/{bad}").status_code == 404


def test_a_description_over_the_limit_is_413_with_a_clear_message(make_client: MakeClient) -> None:
    client = make_client(max_description_chars=100)
    response = client.post("/api/jobs", json={"description": "The ego car " * 20})
    assert response.status_code == 413
    assert response.json()["error"].startswith("the description is 239 characters long")


@pytest.mark.parametrize(
    ("body", "words"),
    [
        ({"description": "   "}, "the description is empty"),
        ({"description": "Bake a chocolate cake for twelve."}, "does not look like a driving"),
        ({}, "description: Field required"),
        ({"description": DESCRIPTION, "provider": "nobody"}, "unknown provider 'nobody'"),
        ({"description": DESCRIPTION, "provider": "openai"}, "OPENAI_API_KEY"),
        ({"description": DESCRIPTION, "provider": "replay", "model": "x"}, "has one model"),
    ],
)
def test_unusable_requests_are_422_with_one_line_and_no_job(
    make_client: MakeClient, monkeypatch: pytest.MonkeyPatch, body: dict, words: str
) -> None:
    monkeypatch.delenv("OPENAI_API_KEY", raising=False)
    client = make_client()
    response = client.post("/api/jobs", json=body)
    assert response.status_code == 422
    error = response.json()["error"]
    assert words in error and "Traceback" not in error and "\n" not in error
    assert client.get("/api/jobs").json()["jobs"] == []


def running_and_waiting(
    make_client: MakeClient, runner: ScriptedRunner
) -> tuple[TestClient, dict, dict]:
    """Two jobs for one model: the first held at its first stage, the second waiting."""
    runner.hold = True
    client = make_client()
    first, second = submit(client), submit(client)
    assert runner.started.wait(5)
    return client, first, second


def test_jobs_for_one_model_queue_and_run_one_at_a_time(
    make_client: MakeClient, runner: ScriptedRunner
) -> None:
    client, first, second = running_and_waiting(make_client, runner)
    assert wait_state(client, first["id"], "running")["position"] is None
    waiting = client.get(f"/api/jobs/{second['id']}").json()
    assert waiting["state"] == "queued" and waiting["position"] == 1
    assert client.get("/api/jobs").json()["queue"] == [
        {"key": "replay/first_try.jsonl", "running": first["id"], "waiting": 1}
    ]
    runner.release.set()
    wait_state(client, second["id"], "done")
    assert (
        wait_state(client, first["id"], "done")["finished"]
        <= client.get(f"/api/jobs/{second['id']}").json()["started"]
    )


def test_cancel_a_queued_job_and_a_running_one(
    make_client: MakeClient, runner: ScriptedRunner
) -> None:
    client, first, second = running_and_waiting(make_client, runner)
    cancelled = client.post(f"/api/jobs/{second['id']}/cancel").json()
    assert (
        cancelled["state"] == "cancelled" and cancelled["message"] == "cancelled before it started"
    )
    client.post(f"/api/jobs/{first['id']}/cancel")
    runner.release.set()  # the running job stops at its next stage
    job = wait_state(client, first["id"], "cancelled")
    assert job["message"] == "cancelled while running"
    assert runner.descriptions == [DESCRIPTION]  # the queued one never ran
    again = client.post(f"/api/jobs/{first['id']}/cancel")
    assert again.status_code == 409 and "already cancelled" in again.json()["error"]
    assert client.post("/api/jobs/20260101-000000-abcdef/cancel").status_code == 404


def test_a_failed_run_and_a_crashing_runner_are_failed_jobs_with_one_line(
    make_client: MakeClient, runner: ScriptedRunner
) -> None:
    runner.status = RunStatus.FAILED
    client = make_client()
    job = wait_state(client, submit(client)["id"], "failed")
    assert job["message"] == "failed: no script ran" and job["run_status"] == "failed"
    view = client.get(f"/api/runs/{job['id']}").json()
    assert view["script"]["failed"] and view["files"] == ["scenario.scenic", "report.json"]
    runner.crash = RuntimeError("boom\nwith a second line")
    crashed = wait_state(client, submit(client)["id"], "failed")
    assert crashed["message"] == "internal error (RuntimeError); the server's log has the details"
    assert client.get("/api/health").json()["ok"] is True


def test_a_restart_keeps_finished_runs_and_fails_interrupted_ones(
    make_client: MakeClient, tmp_path: Path
) -> None:
    client = make_client()
    done = submit(client)
    wait_state(client, done["id"], "done")
    client.__exit__(None, None, None)
    interrupted = tmp_path / "runs" / "20260101-000000-abcdef"
    interrupted.mkdir()
    (interrupted / "job.json").write_text(
        json.dumps(
            {
                "id": interrupted.name,
                "description": DESCRIPTION,
                "provider": "replay",
                "model": "first_try.jsonl",
                "state": "running",
            }
        ),
        encoding="utf-8",
    )
    (tmp_path / "runs" / "not-a-run").mkdir()
    again = make_client()
    jobs = {job["id"]: job for job in again.get("/api/jobs").json()["jobs"]}
    assert jobs.keys() == {done["id"], interrupted.name}
    assert jobs[done["id"]]["state"] == "done"
    assert jobs[interrupted.name]["state"] == "failed"
    assert "server stopped" in jobs[interrupted.name]["message"]
    events = stream(again, done["id"])  # the stages of a finished run, read from disk
    assert [d["stage"] for n, d in events if n == "stage"][:3] == [
        "extract",
        "retrieve",
        "assemble",
    ]
    assert again.get(f"/runs/{done['id']}/download.zip").status_code == 200


def test_a_full_queue_is_refused(make_client: MakeClient, runner: ScriptedRunner) -> None:
    runner.hold = True
    client = make_client(max_queued=1)
    submit(client)
    assert runner.started.wait(5)
    submit(client)
    response = client.post("/api/jobs", json={"description": DESCRIPTION})
    assert response.status_code == 503 and "already waiting" in response.json()["error"]


def test_another_host_needs_a_token() -> None:
    with pytest.raises(UnsafeBinding, match="access token"):
        ServeConfig(host="0.0.0.0")
    with pytest.raises(UnsafeBinding, match="at least 8"):
        ServeConfig(host="0.0.0.0", token="short")
    with pytest.raises(UnsafeBinding, match="at least 8"):
        ServeConfig(host="0.0.0.0", token="has spaces; and=semicolons")
    assert ServeConfig(host="0.0.0.0", token="a-long-token").token == "a-long-token"
    assert ServeConfig(host="::1").loopback and ServeConfig(host="localhost").loopback


def test_every_request_carries_the_token(make_client: MakeClient) -> None:
    token = "s3cret-token-123"
    client = make_client(host="0.0.0.0", token=token, base_url="http://192.0.2.7:8765")
    for path in ("/", "/api/info", "/api/jobs", "/static/app.js", "/api/health"):
        response = client.get(path)
        assert response.status_code == 401, path
        assert "access token" in response.json()["error"]
    assert (
        client.get("/api/info", headers={"Authorization": "Bearer wrong-token"}).status_code == 401
    )
    assert client.get("/api/info", headers={"Authorization": f"Bearer {token}"}).status_code == 200
    page = client.get(f"/?token={token}")
    assert page.status_code == 200
    assert (
        "HttpOnly" in page.headers["set-cookie"] and "SameSite=Strict" in page.headers["set-cookie"]
    )
    assert client.get("/api/info").status_code == 200  # the cookie from now on
    assert client.post("/api/jobs", json={"description": DESCRIPTION}).status_code == 201


def test_a_loopback_server_answers_only_to_its_own_names(make_client: MakeClient) -> None:
    client = make_client()
    assert client.get("/api/info", headers={"Host": "localhost:8765"}).status_code == 200
    assert client.get("/api/info", headers={"Host": "[::1]:8765"}).status_code == 200
    response = client.get("/api/info", headers={"Host": "attacker.example:8765"})
    assert response.status_code == 421


def test_bodies_over_the_limit_are_413_before_they_are_read(make_client: MakeClient) -> None:
    client = make_client(max_script_bytes=1024)
    big = "x" * (1024 * 6 + 64 * 1024 + 1)
    response = client.post("/api/check", json={"script": big})
    assert response.status_code == 413 and "larger than" in response.json()["error"]
    script = "# a comment\n" * 200  # under the body limit, over the script limit
    response = client.post("/api/check", json={"script": script})
    assert response.status_code == 413 and "the limit is 1 KiB" in response.json()["error"]
    response = client.post("/api/check", json={"script": "  \n"})
    assert response.status_code == 422 and "the script is empty" in response.json()["error"]
    response = client.post(
        "/api/check", content=b"{not json", headers={"content-type": "application/json"}
    )
    assert response.status_code == 422 and "cannot be read" in response.json()["error"]
