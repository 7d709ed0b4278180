"""What the server does with run folders it did not write, and with requests from other
sites: a planted link or special file is never followed or served, records read back are
validated, and a cross-site request that would change something is refused."""

from __future__ import annotations

import io
import json
import os
import zipfile
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from tests.serve.conftest import DESCRIPTION, MakeClient
from tests.serve.scripted import ScriptedRunner
from tests.serve.test_app import stream, submit, wait_state

SECRET = "TOP-SECRET-7f3a9c"
ORIGIN = "http://127.0.0.1:8765"


def plant_secret(folder: Path) -> Path:
    """A folder outside the runs folder with files a link could lead to."""
    folder.mkdir()
    secret = folder / "secret.txt"
    secret.write_text(f"password = {SECRET}\n", encoding="utf-8")
    return secret


def texts_of(responses: list) -> list[str]:
    """Every response body, zips unpacked, as text."""
    found = []
    for response in responses:
        body = response.content
        if body.startswith(b"PK"):
            with zipfile.ZipFile(io.BytesIO(body)) as archive:
                found += [
                    archive.read(name).decode("utf-8", "replace") for name in archive.namelist()
                ]
        found.append(body.decode("utf-8", "replace"))
    return found


def test_a_run_folder_that_is_a_link_is_neither_listed_nor_served(
    make_client: MakeClient, tmp_path: Path
) -> None:
    outside = tmp_path / "outside"
    plant_secret(outside)
    run_id = "20260101-000000-abcdef"
    record = {
        "id": run_id,
        "description": SECRET,
        "provider": "replay",
        "model": "first_try.jsonl",
        "state": "done",
    }
    (outside / "job.json").write_text(json.dumps(record), encoding="utf-8")
    (outside / "events.jsonl").write_text(json.dumps({"event": "state", "x": SECRET}) + "\n")
    for name in ("scenario.scenic", "report.json", "replay.html", "town.xodr"):
        (outside / name).write_text(SECRET, encoding="utf-8")
    runs = tmp_path / "runs"
    runs.mkdir()
    (runs / run_id).symlink_to(outside, target_is_directory=True)

    client = make_client()  # reads the runs folder at start
    responses = [
        client.get("/api/jobs"),
        client.get(f"/api/jobs/{run_id}"),
        client.get(f"/api/runs/{run_id}"),
        client.get(f"/api/jobs/{run_id}/events"),
        client.get(f"/runs/{run_id}/download.zip"),
        *(
            client.get(f"/runs/{run_id}/files/{name}")
            for name in ("scenario.scenic", "report.json", "replay.html", "town.xodr")
        ),
    ]
    assert responses[0].status_code == 200 and responses[0].json()["jobs"] == []
    assert [r.status_code for r in responses[1:]] == [404] * (len(responses) - 1)
    assert not [text for text in texts_of(responses) if SECRET in text]


def test_links_and_special_files_in_a_run_are_skipped(
    make_client: MakeClient, tmp_path: Path
) -> None:
    client = make_client()
    job = submit(client)
    wait_state(client, job["id"], "done")
    folder = tmp_path / "runs" / job["id"]
    secret = plant_secret(tmp_path / "outside")
    (folder / "scenario.xosc").unlink()
    (folder / "scenario.xosc").symlink_to(secret)  # a link where a bundle file belongs
    (folder / "leak.xodr").symlink_to(secret)
    os.link(secret, folder / "hard.xodr")  # a hard link is a regular file with two names
    os.mkfifo(folder / "fifo.xodr")  # opening it for reading must not wait for a writer
    (folder / "scenario.scenic").unlink()
    (folder / "scenario.scenic").symlink_to(secret)
    attempts = folder / "attempts"
    for path in attempts.iterdir():
        path.unlink()
    attempts.rmdir()
    attempts.symlink_to(secret.parent, target_is_directory=True)
    (secret.parent / "attempt-01.scenic").write_text(SECRET, encoding="utf-8")

    view = client.get(f"/api/runs/{job['id']}")
    assert view.status_code == 200
    assert view.json()["files"] == ["report.json", "replay.html", "arise_straight.xodr"]
    assert sorted(line.split(":")[0] for line in view.json()["skipped"]) == [
        "fifo.xodr",
        "hard.xodr",
        "leak.xodr",
        "scenario.scenic",
        "scenario.xosc",
    ]
    assert view.json()["script"]["lines"] == []
    files = [
        client.get(f"/runs/{job['id']}/files/{name}")
        for name in ("scenario.xosc", "leak.xodr", "hard.xodr", "fifo.xodr", "scenario.scenic")
    ]
    assert [r.status_code for r in files] == [404] * 5
    download = client.get(f"/runs/{job['id']}/download.zip")
    assert download.status_code == 200
    archive = zipfile.ZipFile(io.BytesIO(download.content))
    assert sorted(Path(n).name for n in archive.namelist()) == [
        "SKIPPED.txt",
        "arise_straight.xodr",
        "replay.html",
        "report.json",
    ]
    note = archive.read(f"{job['id']}/SKIPPED.txt").decode()
    assert "scenario.xosc: a symbolic link" in note and "fifo.xodr: a special file" in note
    responses = [
        view,
        download,
        *files,
        client.get("/api/jobs"),
        client.get(f"/api/jobs/{job['id']}"),
    ]
    assert not [text for text in texts_of(responses) if SECRET in text]


def test_a_linked_events_file_is_not_written_through(
    make_client: MakeClient, runner: ScriptedRunner, tmp_path: Path
) -> None:
    runner.hold = True
    client = make_client()
    job = submit(client)
    assert runner.started.wait(5)
    target = plant_secret(tmp_path / "outside")
    events = tmp_path / "runs" / job["id"] / "events.jsonl"
    events.unlink()
    events.symlink_to(target)
    runner.release.set()
    assert wait_state(client, job["id"], "done")["state"] == "done"
    assert target.read_text(encoding="utf-8") == f"password = {SECRET}\n"
    assert [name for name, _ in stream(client, job["id"])][-1] == "state"  # kept in memory


@pytest.mark.parametrize(
    "change",
    [
        {"created": float("nan")},
        {"started": float("inf")},
        {"state": "exploded"},
        {"run_status": "pwned"},
        {"message": "x" * 20_000},
        {"description": ["not", "text"]},
    ],
)
def test_a_job_record_that_is_not_ours_is_left_out(
    make_client: MakeClient, tmp_path: Path, change: dict
) -> None:
    run_id = "20260101-000000-abcdef"
    record = {
        "id": run_id,
        "description": DESCRIPTION,
        "provider": "replay",
        "model": "first_try.jsonl",
        "state": "done",
        **change,
    }
    folder = tmp_path / "runs" / run_id
    folder.mkdir(parents=True)
    (folder / "job.json").write_text(json.dumps(record), encoding="utf-8")
    client = make_client()
    response = client.get("/api/jobs")
    assert response.status_code == 200 and response.json()["jobs"] == []


def test_a_crafted_report_cannot_break_or_stall_the_run_view(
    make_client: MakeClient, tmp_path: Path
) -> None:
    client = make_client()
    job = submit(client)
    wait_state(client, job["id"], "done")
    report = tmp_path / "runs" / job["id"] / "report.json"
    crafted = {
        "status": "executed",
        "final_attempt": 10**9,  # must not drive a loop
        "attempts": [{"index": 0, "check_seconds": "soon", "repair_seconds": [1]}],
    }
    report.write_text(json.dumps(crafted), encoding="utf-8")
    view = client.get(f"/api/runs/{job['id']}").json()
    assert view["attempts"][0]["seconds"] == 0.0
    assert all(line["attempt"] == 0 for line in view["script"]["lines"])
    report.write_text('{"status": "executed", "seconds": NaN}', encoding="utf-8")
    response = client.get(f"/api/runs/{job['id']}")
    assert response.status_code == 200 and response.json()["report"] is None


def post_job(client: TestClient, **headers: str):
    return client.post("/api/jobs", json={"description": DESCRIPTION}, headers=headers)


@pytest.mark.parametrize(
    "headers",
    [
        {"Origin": "https://evil.example"},
        {"Sec-Fetch-Site": "cross-site"},
        {"Sec-Fetch-Site": "same-site", "Origin": "http://127.0.0.1:3000"},
        {"Origin": "null"},
        {"Origin": ORIGIN, "Sec-Fetch-Site": "cross-site"},
        {"Origin": "http://localhost:8765"},  # another name is another origin
    ],
)
def test_a_cross_site_request_that_changes_something_is_refused(
    make_client: MakeClient, headers: dict[str, str]
) -> None:
    client = make_client()
    response = post_job(client, **headers)
    assert response.status_code == 403
    assert response.json()["error"].startswith("cross-site request refused:")
    assert client.get("/api/jobs").json()["jobs"] == []
    assert client.post("/api/check", json={"script": "x"}, headers=headers).status_code == 403


def test_a_cross_site_cancel_is_refused_and_same_origin_is_allowed(
    make_client: MakeClient, runner: ScriptedRunner
) -> None:
    runner.hold = True
    client = make_client()
    same = {"Origin": ORIGIN, "Sec-Fetch-Site": "same-origin"}
    job = post_job(client, **same)
    assert job.status_code == 201
    assert post_job(client, **{"Sec-Fetch-Site": "none"}).status_code == 201  # typed address
    assert post_job(client).status_code == 201  # no browser: curl, scripts
    cancel = f"/api/jobs/{job.json()['id']}/cancel"
    refused = client.post(cancel, headers={"Origin": "https://evil.example"})
    assert refused.status_code == 403
    assert client.get(f"/api/jobs/{job.json()['id']}").json()["state"] != "cancelled"
    assert client.post(cancel, headers=same).status_code == 200
    runner.release.set()
    assert wait_state(client, job.json()["id"], "cancelled")["state"] == "cancelled"
    # a GET from another site changes nothing and is answered as before
    assert client.get("/api/jobs", headers={"Sec-Fetch-Site": "cross-site"}).status_code == 200


def test_a_token_server_refuses_cross_site_requests_even_with_the_token(
    make_client: MakeClient,
) -> None:
    token = "s3cret-token-123"
    client = make_client(host="0.0.0.0", token=token, base_url="http://192.0.2.7:8765")
    auth = {"Authorization": f"Bearer {token}"}
    assert post_job(client, **auth, Origin="https://evil.example").status_code == 403
    assert post_job(client, **auth, Origin="http://192.0.2.7:8765").status_code == 201


def test_a_loopback_server_answers_to_loopback_addresses_only(make_client: MakeClient) -> None:
    client = make_client()
    assert client.get("/api/health", headers={"Host": "127.0.0.2:8765"}).status_code == 200
    for host in ("rebind.attacker.example:8765", "192.0.2.1:8765", ""):
        assert client.get("/api/health", headers={"Host": host}).status_code == 421
