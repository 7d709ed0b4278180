"""Isolation: warm workers are reused, recycled, and a bad script never harms the caller."""

from __future__ import annotations

import os

import pytest

from arise.validate import CheckOptions, WorkerPool, check, check_text
from tests.conftest import DATA, EXAMPLES


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
