"""Judge cases shared by the cassette recorder and the tests that replay them.

The cassettes in tests/cassettes/judge/ were recorded from the real embedded model
(Qwen2.5-Coder-1.5B-Instruct Q4_K_M through llama-cpp-python, 2 threads) with
`.venv/bin/python tests/record_judge_cassettes.py`. A change to the judge prompt, the schema,
the examples or a script in tests/data/judge changes the request, so the replay misses and
names it: re-record then.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent
DATA = ROOT / "data" / "judge"
CASSETTES = ROOT / "cassettes" / "judge"

#: Says clear noon and a pedestrian from the right sidewalk, so the car-in-rain script
#: contradicts it on adversary type, weather, behavior and spawn.
PEDESTRIAN = (
    "On a clear day at noon, the ego car drives along a straight two-lane road. "
    "A pedestrian suddenly steps off the right sidewalk, walks into the ego's lane "
    "and stops right in front of it."
)
CHILD_DIR = DATA / "child_behind_van"  # a generation folder: scenario.scenic + report.json


@dataclass(frozen=True)
class Case:
    name: str
    description: str
    script: Path
    repeat: int = 1
    temperature: float = 0.0
    seed: int = 0

    @property
    def cassette(self) -> Path:
        return CASSETTES / f"{self.name}.jsonl"

    def script_text(self) -> str:
        path = self.script / "scenario.scenic" if self.script.is_dir() else self.script
        return path.read_text(encoding="utf-8")


def child_description() -> str:
    import json

    return str(json.loads((CHILD_DIR / "report.json").read_text())["description"])


CASES = {
    case.name: case
    for case in [
        # a real generator output that follows the description
        Case("good", PEDESTRIAN, DATA / "pedestrian_stops.scenic"),
        # the same description against a car braking ahead in hard rain
        Case("mismatch", PEDESTRIAN, DATA / "car_brakes_in_rain.scenic"),
        # a real generator output with real flaws: the child never freezes, rain unasked for
        Case("child", child_description(), CHILD_DIR),
        # the consistency study: the good pair three times, sampled
        Case("repeat", PEDESTRIAN, DATA / "pedestrian_stops.scenic", repeat=3, temperature=0.7),
    ]
}
