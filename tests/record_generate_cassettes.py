"""Record the generator cassettes from the real embedded model (not a test; run by hand).

.venv/bin/python tests/record_generate_cassettes.py [CASE ...]
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from arise.generate.pipeline import Generator  # noqa: E402
from tests.generate_cases import CASES  # noqa: E402


def main() -> None:
    names = sys.argv[1:] or list(CASES)
    for name in names:
        case = CASES[name]
        case.cassette.parent.mkdir(parents=True, exist_ok=True)
        if case.cassette.exists():
            case.cassette.unlink()
        with Generator(case.options(record=str(case.cassette))) as generator:
            run = generator.generate(case.description)
        kinds = [f"{a.kind}:{'ok' if a.ok else 'fail'}" for a in run.attempts]
        print(
            f"{name}: {run.status} {kinds} {run.usage.calls} calls "
            f"{run.seconds:.0f}s -- {run.message or ''}"
        )


if __name__ == "__main__":
    main()
