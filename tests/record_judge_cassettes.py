"""Record the judge cassettes from the real embedded model (not a test; run by hand).

    .venv/bin/python tests/record_judge_cassettes.py [CASE ...]

Each call takes roughly half a minute to a minute on 2 cores; run it when nothing else
keeps the CPU busy.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from arise.evaluate.judge import consistency  # noqa: E402
from arise.llm.registry import get_provider  # noqa: E402
from tests.judge_cases import CASES  # noqa: E402


def main() -> None:
    names = sys.argv[1:] or list(CASES)
    for name in names:
        case = CASES[name]
        case.cassette.parent.mkdir(parents=True, exist_ok=True)
        if case.cassette.exists():
            case.cassette.unlink()
        started = time.perf_counter()
        with get_provider("local", cache=False, record=case.cassette) as llm:
            result = consistency(
                case.description,
                case.script_text(),
                llm,
                repeat=case.repeat,
                temperature=case.temperature,
                seed=case.seed,
            )
        seconds = time.perf_counter() - started
        for run in result.runs:
            scores = " ".join(f"{k}={v}" for k, v in run.scores.items())
            print(
                f"{name} seed {run.seed}: SCS {100 * run.scs:.1f}% [{scores}] "
                f"{run.seconds:.1f}s {run.usage.prompt_tokens}+{run.usage.completion_tokens} "
                f"tokens, {run.usage.calls} call(s)"
            )
            for criterion, reason in run.reasons.items():
                print(f"    {criterion}: {reason}")
        for line in result.failures:
            print(f"{name} FAILED {line}")
        print(f"{name}: {seconds:.0f}s in all")


if __name__ == "__main__":
    main()
