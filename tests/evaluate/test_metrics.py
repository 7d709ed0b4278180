"""The paper's metrics against cases computed by hand."""

from __future__ import annotations

import pytest

from arise.evaluate.metrics import (
    by_category,
    calls_per_executable,
    esr_single,
    esr_total,
    rcr,
    tokens_per_executable,
)
from arise.evaluate.records import BenchTask, RunRecord


def run(
    category: str,
    status: str,
    first: bool,
    repairs: int,
    calls: int = 2,
    tokens: int = 100,
    index: int = 0,
) -> RunRecord:
    task = BenchTask(f"{category}-{index}", category, "d", "arise", 0.3, 0)
    return RunRecord(
        task=task,
        status=status,
        first_pass_ok=first,
        repairs=repairs,
        llm_calls=calls,
        prompt_tokens=tokens,
        completion_tokens=0,
    )


def test_esr_single_and_total() -> None:
    runs = [
        run("a", "executed", True, 0),
        run("a", "executed", False, 3),
        run("a", "failed", False, 10),
        run("a", "executed", False, 1),
    ]
    assert esr_single(runs) == pytest.approx(1 / 4)
    assert esr_total(runs) == pytest.approx(3 / 4)
    assert esr_single([]) is None and esr_total([]) is None


def test_rcr_counts_only_runs_repaired_into_success() -> None:
    runs = [
        run("a", "executed", True, 0),  # first try: left out
        run("a", "failed", False, 10),  # budget spent: left out
        run("a", "executed", False, 3),
        run("a", "executed", False, 1),
    ]
    # A_i includes the successful repair: (3 + 1) / 2.
    assert rcr(runs) == pytest.approx(2.0)


@pytest.mark.parametrize(
    "runs",
    [
        [run("a", "executed", True, 0), run("a", "executed", True, 0)],  # all first try
        [run("a", "failed", False, 10)],  # all failed
        [run("a", "refused", False, 0)],  # refused: nothing to repair
        [],
    ],
)
def test_rcr_is_not_applicable_without_a_repaired_success(runs: list[RunRecord]) -> None:
    assert rcr(runs) is None


def test_average_is_the_mean_of_category_values_and_skips_not_applicable() -> None:
    runs = [
        run("a", "executed", False, 2),
        run("a", "executed", False, 4, index=1),
        run("b", "executed", True, 0),
        run("c", "executed", False, 6),
    ]
    values, average = by_category(runs, rcr, ["a", "b", "c"])
    assert values == {"a": 3.0, "b": None, "c": 6.0}
    assert average == pytest.approx(4.5)  # (3 + 6) / 2, not the pooled 4.0
    values, average = by_category(runs, esr_total, ["a", "b", "c"])
    assert average == pytest.approx(1.0)


def test_paper_table_average_is_reproduced() -> None:
    # ARISE, T=0.3, total ESR per category from the paper's Table I -> its average 0.780.
    paper = [0.964, 0.872, 0.424, 0.632, 0.892, 0.848, 0.876, 0.728]
    runs = []
    for index, value in enumerate(paper):
        ok = round(value * 1000)
        runs += [
            run(f"c{index}", "executed" if k < ok else "failed", False, 1, index=k)
            for k in range(1000)
        ]
    _, average = by_category(runs, esr_total, [f"c{i}" for i in range(8)])
    assert average == pytest.approx(0.7795, abs=1e-4)


def test_cost_is_spent_over_executable_scripts() -> None:
    runs = [
        run("a", "executed", True, 0, calls=2, tokens=1000),
        run("a", "failed", False, 10, calls=12, tokens=9000),
    ]
    assert calls_per_executable(runs) == pytest.approx(14.0)
    assert tokens_per_executable(runs) == pytest.approx(10000.0)
    assert calls_per_executable([run("a", "failed", False, 1)]) is None
