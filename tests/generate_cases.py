"""Generator cases shared by the cassette recorder and the tests that replay them.

Cassettes were recorded from the real embedded model (Qwen2.5-Coder-1.5B-Instruct Q4_K_M,
llama.cpp, temperature 0, seed 0) with `python tests/record_generate_cassettes.py`. A change
to a prompt, the knowledge base or the retrieval changes the requests, so the replay misses
and names the request: re-record then.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from arise.generate.options import GenerateOptions, Mode

ROOT = Path(__file__).resolve().parent
CASSETTES = ROOT / "cassettes" / "generate"
FAULTY_KB = ROOT / "data" / "kb_faulty"


@dataclass(frozen=True)
class Case:
    name: str
    description: str
    mode: Mode = Mode.ARISE
    max_repairs: int = 10
    kb_dirs: tuple[str, ...] = ()
    extra: dict[str, object] = field(default_factory=dict)

    def options(self, **overrides: object) -> GenerateOptions:
        values: dict[str, object] = dict(
            mode=self.mode,
            max_repairs=self.max_repairs,
            kb_dirs=list(self.kb_dirs),
            seed=0,
            temperature=0.0,
            retrieval="bm25",
            cache=False,
            # recorded when the model read every description; they test what follows
            model_extraction="always",
        )
        values.update(self.extra)
        values.update(overrides)
        return GenerateOptions.model_validate(values)

    @property
    def cassette(self) -> Path:
        return CASSETTES / f"{self.name}.jsonl"


# The repair cases test how a script that does not run is fixed; the semantic gate (on by
# default, tested in test_semantic_gate*.py) would add swaps for facts of the description.
NO_GATE: dict[str, object] = {"semantic_gate": False}

CASES = {
    case.name: case
    for case in [
        Case(
            "first_try", "A cyclist riding ahead in the ego's lane suddenly brakes to a full stop."
        ),
        Case(
            "rule_fix",
            "A pedestrian on a unicycle wobbles along the gutter ahead of the "
            "ego and tips into its lane.",
            kb_dirs=(str(FAULTY_KB),),
            extra=NO_GATE,
        ),
        Case(
            "llm_repair",
            "A jogger zigzags across the boulevard in front of the ego car.",
            kb_dirs=(str(FAULTY_KB),),
            extra=NO_GATE,
        ),
        Case(
            "give_up",
            "A pedestrian street mime hops across the avenue in front of the ego "
            "car and pirouettes.",
            kb_dirs=(str(FAULTY_KB),),
            max_repairs=1,
            extra=NO_GATE,
        ),
        # A description of the dev set fresh6 (f6-dt-1) on which the model's extraction ran
        # into the token limit inside a string (2026-11-30): the rules' reading stands in.
        Case(
            "runaway_reply",
            "Picture yourself halfway down a tight residential road with houses on both "
            "sides, doing about 20 mph. Three cars are parked nose to tail along the kerb on "
            "your nearside. A football bounces out from between the second and third of "
            "them, and a boy of about eight runs out after it into your path. Could you "
            "stop in time? Cover the brake whenever you pass parked cars near homes, and "
            "leave at least a door's width between you and them. Where there's a ball, "
            "there's usually a child.",
        ),
        Case(
            "single_pass",
            "The ego turns left at an intersection while an oncoming car goes straight through.",
            mode=Mode.SINGLE_PASS,
        ),
        Case(
            "chatscene",
            "The ego turns left at an intersection while an oncoming car goes straight through.",
            mode=Mode.CHATSCENE,
        ),
    ]
}
