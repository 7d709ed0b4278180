"""The fast tier's guard fails an unmarked test that starts something slow, and lets a
marked one do it (tests/slow_guard.py)."""

from __future__ import annotations

import pytest

from tests.conftest import REPO

INNER = """
import subprocess
import sys

import pytest


def test_unmarked_starts_a_worker():
    from arise.validate import WorkerPool

    with WorkerPool(size=1) as pool:
        pool.warm()


def test_unmarked_loads_the_model(tmp_path):
    from arise.llm import local

    local._load(tmp_path / "no-model.gguf", 512, 1, 0)


def test_unmarked_quick_child():
    subprocess.run([sys.executable, "-c", "pass"], check=True)


@pytest.mark.slow
def test_marked_may_start_one():
    subprocess.run([sys.executable, "-c", "'arise.validate.worker'"], check=True)
"""


def test_guard_fails_unmarked_slow_work(
    pytester: pytest.Pytester, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("PYTHONPATH", str(REPO))
    pytester.makepyfile(test_inner=INNER)
    result = pytester.runpytest_subprocess("-p", "tests.slow_guard", "-p", "no:cacheprovider")
    result.assert_outcomes(passed=2, failed=2)
    result.stdout.fnmatch_lines(
        [
            "*test_unmarked_starts_a_worker is not marked slow but started a validator worker*",
            "*test_unmarked_loads_the_model is not marked slow but started the local language*",
        ]
    )
