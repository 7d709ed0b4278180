"""`arise serve` under a small load on loopback: 20 jobs at once to a replayed model, the
real validator, the server in its own process. None lost, none crashing it, memory flat.
(Times and memory are numbers for benchmarks/serve_load.py and docs/benchmarks.md; the
memory bound here is only there to catch a leak.)"""

from __future__ import annotations

from pathlib import Path

import httpx
import pytest
from benchmarks.serve_load import free_port, run_round, start_server, wait_ready

pytestmark = pytest.mark.slow

JOBS = 20
#: Growth of the server's RSS over the round that would mean something is kept per job.
LEAK_MB = 150


def test_twenty_jobs_at_once_are_all_served(tmp_path: Path) -> None:
    port = free_port()
    url = f"http://127.0.0.1:{port}"
    process = start_server(tmp_path / "runs", port)
    try:
        wait_ready(url, process)
        warm = run_round(url, process.pid, 1)
        assert warm.done == 1, warm.outcomes
        result = run_round(url, process.pid, JOBS)
        assert result.accepted == JOBS, [o.error for o in result.outcomes]
        assert result.lost == 0 and result.done == JOBS, result.outcomes
        ids = {o.job_id for o in result.outcomes}
        assert len(ids) == JOBS
        assert process.poll() is None
        jobs = httpx.get(f"{url}/api/jobs").json()["jobs"]
        assert ids <= {job["id"] for job in jobs}
        assert all(job["state"] == "done" for job in jobs)
        assert len(list((tmp_path / "runs").glob("*/replay.html"))) == JOBS + 1
        assert result.server_mb_after - result.server_mb_before < LEAK_MB
    finally:
        process.terminate()
        process.wait(timeout=30)
