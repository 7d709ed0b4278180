"""Every adversary behavior meets the ego, whoever drives it and however fast.

Each behavior entry (but those declared to have no conflict with the ego by nature: tagged
`static` or `no_conflict`) is composed with its companions as the KB validator plans it,
and driven by the built-in `blind` and `cautious` agents with the ego's target speed at
0.6 and 1.4 times its geometry's usual one. A run reaches the conflict when the two boxes
come within 6 m or their time-to-collision drops under 3 s (benchmarks/conflict_reach.py
measures the same and prints the table).
"""

from __future__ import annotations

import re
from collections.abc import Iterator

import pytest
from benchmarks.conflict_reach import (
    NO_CONFLICT_TAGS,
    Case,
    Reach,
    adversary_behaviors,
    box_gap,
    cases,
    run_case,
    with_ego_speed,
)

from arise.drive.metrics_track import Track
from arise.kb.loader import load_kb
from arise.kb.schema import Entry
from arise.validate import WorkerPool
from arise.validate.types import AgentTrace, TracePoint

#: The floor agent never brakes: every behavior must reach it at both speeds. The
#: cautious one brakes for what is in front of it; over all runs, this share must reach.
MIN_SHARE = 0.9
#: Each falsification lever at the end where the adversary behaves as before it had one
#: (a fixed start factor of 3, a commit 4 m out, a pause on the anchor).
LEVERS_AT_REACH_END = {
    "OPT_ADV_START_FACTOR": "3",
    "OPT_ADV_COMMIT": "4",
    "OPT_ADV_PAUSE_SHORT": "0",
    "OPT_ADV_RESUME": "0",
}


def at_reach_end(entry: Entry) -> Entry:
    """The entry with its levers fixed at their reach end."""
    snippet = entry.snippet
    for name, value in LEVERS_AT_REACH_END.items():
        snippet = re.sub(rf"^param {name} = .*$", f"param {name} = {value}", snippet, flags=re.M)
    return entry.model_copy(update={"snippet": snippet})


@pytest.fixture(scope="module")
def reaches() -> Iterator[list[Reach]]:
    entries = [at_reach_end(entry) for entry in load_kb(builtin=True)]
    todo, missing = cases(entries, None, ("blind", "cautious"))
    assert not missing, f"no composition for {missing}"
    with WorkerPool(size=2) as pool:
        yield [run_case(case, pool, seed=1) for case in todo]


def _table(found: list[Reach]) -> str:
    return "\n".join(f"{r.case.behavior} {r.case.label}: {r.cell()} {r.error or ''}" for r in found)


@pytest.mark.slow
def test_every_adversary_behavior_meets_the_blind_ego_at_both_speeds(
    reaches: list[Reach],
) -> None:
    errors = [r for r in reaches if r.error]
    assert not errors, _table(errors)
    missed = [r for r in reaches if r.case.agent == "blind" and not r.met]
    assert not missed, _table(missed)


@pytest.mark.slow
def test_the_conflict_happens_in_most_runs_of_either_agent(reaches: list[Reach]) -> None:
    met = sum(r.met for r in reaches) / len(reaches)
    assert met >= MIN_SHARE, f"{met:.2f} of runs met the ego\n" + _table(
        [r for r in reaches if not r.met]
    )


def test_only_declared_exceptions_are_left_out() -> None:
    entries = list(load_kb(builtin=True))
    behaviors = [e for e in entries if e.component.value == "behavior"]
    kept = {e.id for e in adversary_behaviors(entries)}
    left_out = {e.id for e in behaviors} - kept
    assert left_out == {e.id for e in behaviors if set(e.tags) & NO_CONFLICT_TAGS}
    assert len(kept) >= 40  # the exceptions stay few


def test_levers_are_held_at_their_reach_end() -> None:
    kb = load_kb(builtin=True)
    held = at_reach_end(kb.get("behavior.yield_then_go")).snippet
    assert "param OPT_ADV_START_FACTOR = 3\n" in held
    assert "OPT_ADV_START_FACTOR = Range(" in kb.get("behavior.yield_then_go").snippet
    levers = {p for e in kb for p in e.params if p in LEVERS_AT_REACH_END}
    assert levers == set(LEVERS_AT_REACH_END)  # each one is still some entry's


def test_the_ego_speed_is_fixed_in_the_script() -> None:
    script = "param OPT_EGO_SPEED = Range(7, 9)\nparam OPT_EGO_START = 3\n"
    assert with_ego_speed(script, 1.5) == "param OPT_EGO_SPEED = 12.0\nparam OPT_EGO_START = 3\n"
    assert with_ego_speed("param OPT_EGO_SPEED = 10\n", 0.6) == "param OPT_EGO_SPEED = 6.0\n"


def _track(name: str, xs: list[float], heading: float = 0.0) -> Track:
    points = [TracePoint(step=i, x=x, y=0.0, heading=heading, speed=0.0) for i, x in enumerate(xs)]
    trace = AgentTrace(name=name, kind="Car", width=2.0, length=4.0, trajectory=points)
    return Track.of(trace, 0.1)


def test_box_gap_is_the_closest_the_boxes_came() -> None:
    # Heading 0 faces +y: the boxes are 2 m wide along x. Centres 10 m then 3 m apart.
    ego = _track("ego", [0.0, 0.0])
    other = _track("other", [10.0, 3.0])
    assert box_gap(ego, other) == pytest.approx(1.0)
    touching = _track("other", [1.5])
    assert box_gap(ego, touching) == 0.0


def test_a_reach_needs_the_gap_or_the_ttc() -> None:
    case = Case("behavior.x", None, "blind", 0.6)  # type: ignore[arg-type]
    assert Reach(case, 5.9, None).met
    assert Reach(case, 20.0, 2.9).met
    assert not Reach(case, 6.1, 3.1).met
    assert not Reach(case, None, None, error="did not run").met
