"""Isolation: warm workers are reused, recycled, and a bad script never harms the caller."""

from __future__ import annotations

import os

import psutil
import pytest

from arise.validate import CheckOptions, WorkerPool, check, check_text
from tests.conftest import DATA, EXAMPLES, REPO


@pytest.mark.slow
def test_warm_worker_is_reused_then_recycled() -> None:
    script = EXAMPLES / "pedestrian_crossing.scenic"

    def idle_pids(pool: WorkerPool) -> list[int]:
        return [worker.process.pid for worker in pool._idle.queue]

    with WorkerPool(size=1, recycle_after=2) as pool:
        assert check(script, CheckOptions(seed=2), pool=pool).ok
        first = idle_pids(pool)
        assert len(first) == 1
        assert check(script, CheckOptions(seed=2), pool=pool).ok
        assert idle_pids(pool) == [], "a worker that reached its quota is retired"
        assert check(script, CheckOptions(seed=2), pool=pool).ok
        second = idle_pids(pool)
        assert len(second) == 1 and second != first


@pytest.mark.slow
def test_memory_bomb_does_not_touch_the_caller(validator_pool: WorkerPool) -> None:
    before = os.getpid()
    result = check(
        DATA / "broken" / "memory_bomb.scenic",
        CheckOptions(seed=1, memory_mb=512),
        pool=validator_pool,
    )
    assert result.diagnostic is not None and result.diagnostic.error_type == "MemoryError"
    assert os.getpid() == before
    again = check(
        EXAMPLES / "pedestrian_crossing.scenic", CheckOptions(seed=1), pool=validator_pool
    )
    assert again.ok


@pytest.mark.slow
def test_check_text_uses_a_private_file_and_cleans_up(tmp_path) -> None:
    text = (EXAMPLES / "pedestrian_crossing.scenic").read_text()
    result = check_text(text, CheckOptions(seed=4))
    assert result.ok, result.diagnostic
    assert not os.path.exists(result.script)


@pytest.mark.slow
def test_a_worker_started_in_the_background_serves_the_first_check() -> None:
    script = EXAMPLES / "pedestrian_crossing.scenic"
    with WorkerPool(size=1) as pool:
        pool.warm_in_background(nice=10)
        result = check(script, CheckOptions(seed=2), pool=pool)  # waits for that worker
        assert result.ok, result.diagnostic
        assert result.sandbox is not None
        (worker,) = list(pool._idle.queue)
        assert os.getpriority(os.PRIO_PROCESS, worker.process.pid) >= 10
        assert pool._started == 1, "the check took the warmed worker, not a second one"


@pytest.mark.slow
def test_closing_while_a_worker_starts_leaves_no_process() -> None:
    def workers() -> list[psutil.Process]:
        children = psutil.Process().children()
        return [c for c in children if "arise.validate.worker" in " ".join(c.cmdline())]

    before = workers()
    pool = WorkerPool(size=1)
    pool.warm_in_background()
    pool.close()  # ends the start it no longer needs instead of waiting for it
    assert pool._warming is not None and not pool._warming.is_alive()
    assert pool._idle.empty()
    assert pool._started == 0, "the start was ended, not waited for and then killed"
    psutil.wait_procs([p for p in workers() if p not in before], timeout=10)
    assert [p for p in workers() if p not in before and p.is_running()] == []


# A script (past the static gate, which would refuse it) that writes the pool's own words
# on every pipe it inherited, then ends its process before any result: the fork server's
# word of a `ready`, a `child_died` or a stage with a field of its own.
FORGER = """param map = localPath('{map}')
model scenic.simulators.carla.model
import typing
osmodule = typing.sys.modules['os']
lines = [
    '{{"event": "ready", "pid": 1, "sandbox": {{}}}}',
    '{{"event": "child_died", "code": 0, "flooded": false, "garbled": false}}',
    '{{"event": "stage", "stage": "simulate", "note": "forged"}}',
]
for fd in range(1, 64):
    try:
        if osmodule.fstat(fd).st_mode & 0o170000 == 0o010000:
            osmodule.write(fd, ('\\n'.join(lines) + '\\n').encode())
    except OSError:
        pass
osmodule._exit(0)
ego = new Car
"""


@pytest.mark.slow
def test_a_child_that_forges_the_pools_messages_is_a_protocol_violation(
    validator_pool: WorkerPool,
) -> None:
    text = FORGER.format(map=REPO / "src/arise/maps/data/arise_straight.xodr")
    result = check_text(text, CheckOptions(seed=1, static_gate=False), pool=validator_pool)
    assert result.diagnostic is not None
    assert result.diagnostic.error_type == "ProtocolViolation", result.diagnostic
    assert "wrote its own lines" in result.diagnostic.message
    again = check(
        EXAMPLES / "pedestrian_crossing.scenic", CheckOptions(seed=1), pool=validator_pool
    )
    assert again.ok, again.diagnostic
