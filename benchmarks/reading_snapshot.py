"""What the fixed readers make of every labeled dev description, without a model.

Writes one JSON line per description: the grounded spec's facts when the model's answer
says nothing useful. Two snapshots, before and after a change to the language layer, show
every reading the change moved (`--diff OLD NEW`). Dev sets only: the held-apart set is
never read here.

    python benchmarks/reading_snapshot.py > /tmp/before.jsonl
    python benchmarks/reading_snapshot.py --diff /tmp/before.jsonl /tmp/after.jsonl
    python benchmarks/reading_snapshot.py --score   # rules-only start and direction, per set

`--score` compares, per labeled actor with a start or a direction, what the rules alone
read (facts from the text; a neutral default counts as not read) with the truth: the
adversary's `spawn_position` and `start_detail`, the other actors' `start`. "side" is the
coarse side (left, right, ahead, behind, oncoming); "start" also the end (front/rear) when
both say it.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from arise.evaluate.fidelity import (
    DEVSET_DIR,
    DEVSET_FILES,
    Direction,
    LabeledActor,
    LabeledDescription,
    Start,
    load_devset,
)
from arise.generate.grounding import ground
from arise.generate.spec import Actor, ExtractionAnswer, ScenarioSpec
from arise.language.condense import condense
from arise.language.facts import FactSource
from arise.vocabulary import AdversaryManeuver, RelativePosition, StartDetail

NEUTRAL = ExtractionAnswer.model_validate(
    {
        "adversary": "",
        "adversary_type": "car",
        "behavior": "",
        "road_type": "straight_road",
        "ego_maneuver": "go_straight",
        "geometry": "",
        "spawn_position": "ahead_same_lane",
        "spawn": "",
        "participants": [],
        "requirements": [],
    }
)
DEV_FILES = tuple(DEVSET_FILES.values())


def snapshot() -> list[dict[str, object]]:
    rows: list[dict[str, object]] = []
    for name in DEV_FILES:
        for item in load_devset(Path(DEVSET_DIR) / name):
            spec = ground(condense(item.text).text, NEUTRAL).spec
            facts: dict[str, object] = {
                f.name: f.value for f in spec.grounding if f.name != "participant"
            }
            facts["actors"] = [
                a.describe() + (f" [{a.start_detail.value}]" if a.start_detail else "")
                for a in spec.actors
            ]
            facts["adversary_class"] = spec.scenic_class
            rows.append({"id": item.id, "facts": facts})
    return rows


# -- scoring the rules' reading against the truth ---------------------------------------------

P = RelativePosition
_SIDE = {
    Start.AHEAD: "ahead",
    Start.BEHIND: "behind",
    Start.LEFT: "left",
    Start.LEFT_FRONT: "left",
    Start.LEFT_REAR: "left",
    Start.OPPOSITE_SIDEWALK: "left",
    Start.RIGHT: "right",
    Start.RIGHT_FRONT: "right",
    Start.RIGHT_REAR: "right",
    Start.ONCOMING: "oncoming",
}
_READ_SIDE = {
    P.AHEAD_SAME_LANE: "ahead",
    P.BEHIND_SAME_LANE: "behind",
    P.ONCOMING: "oncoming",
    P.ADJACENT_LANE_LEFT: "left",
    P.ROADSIDE_LEFT: "left",
    P.CROSSING_FROM_LEFT: "left",
    P.ADJACENT_LANE_RIGHT: "right",
    P.ROADSIDE_RIGHT: "right",
    P.CROSSING_FROM_RIGHT: "right",
}
#: The ends (front/rear) a read start allows; a lane beside the ego is either unless the
#: start detail says which.
_ENDS: dict[RelativePosition, frozenset[str]] = {
    P.ROADSIDE_LEFT: frozenset({"front", ""}),
    P.ROADSIDE_RIGHT: frozenset({"front", ""}),
    P.CROSSING_FROM_LEFT: frozenset({"front", ""}),
    P.CROSSING_FROM_RIGHT: frozenset({"front", ""}),
}
_DETAIL_ENDS = {
    StartDetail.FROM_BEHIND: frozenset({"rear", ""}),
    StartDetail.AHEAD: frozenset({"front", ""}),
}


def _end(start: Start) -> str:
    return start.value.split("_")[1] if start.value.endswith(("_front", "_rear")) else ""


def _start_matches(truth: Start, read: RelativePosition, detail: StartDetail | None) -> bool:
    if _SIDE[truth] != _READ_SIDE[read]:
        return False
    if truth is Start.OPPOSITE_SIDEWALK:
        return read is P.ROADSIDE_LEFT
    ends = _DETAIL_ENDS.get(detail) if detail else None
    return _end(truth) in (ends or _ENDS.get(read, frozenset({"front", "rear", ""})))


def _adversary_direction(spec: ScenarioSpec) -> Direction | None:
    """The adversary's direction as the rules read it, None when they read none."""
    facts = {f.name: f for f in spec.grounding if f.source is FactSource.TEXT}
    if "adversary_stationary" in facts and spec.adversary_stationary:
        return Direction.STATIONARY
    if "adversary_maneuver" in facts:
        turn = {
            AdversaryManeuver.TURN_LEFT: Direction.TURNING_LEFT,
            AdversaryManeuver.TURN_RIGHT: Direction.TURNING_RIGHT,
        }.get(spec.adversary_maneuver)
        if turn:
            return turn
    if "spawn_position" not in facts:
        return None
    return _DIRECTION_OF_START.get(spec.spawn_position)


#: The way a road user starting there goes, when nothing else is read (a roadside start
#: says nothing of it).
_DIRECTION_OF_START = {
    P.CROSSING_FROM_LEFT: Direction.CROSSING_LEFT_TO_RIGHT,
    P.CROSSING_FROM_RIGHT: Direction.CROSSING_RIGHT_TO_LEFT,
    P.ONCOMING: Direction.OPPOSITE,
    P.AHEAD_SAME_LANE: Direction.SAME,
    P.BEHIND_SAME_LANE: Direction.SAME,
    P.ADJACENT_LANE_LEFT: Direction.SAME,
    P.ADJACENT_LANE_RIGHT: Direction.SAME,
}


def _pair(
    item: LabeledDescription, spec: ScenarioSpec
) -> list[tuple[LabeledActor, ScenarioSpec | Actor | None]]:
    """Each labeled actor with what the rules read of it, matched by class (the labeled
    adversary first): the read adversary (the spec), an actor of `spec.actors`, or None (not
    read). A labeled adversary of no read class is held against the read adversary."""
    labeled = sorted(item.truth.actors, key=lambda a: a.role != "adversary")
    read: list[ScenarioSpec | Actor] = [] if spec.no_adversary else [spec]
    read += spec.actors
    found: dict[int, ScenarioSpec | Actor] = {}
    for index, actor in enumerate(labeled):
        cls = [r.scenic_class for r in read]
        if actor.cls in cls:
            found[index] = read.pop(cls.index(actor.cls))
    for index, actor in enumerate(labeled):
        if index not in found and actor.role == "adversary" and spec in read:
            found[index] = read.pop(read.index(spec))
    return [(actor, found.get(index)) for index, actor in enumerate(labeled)]


def score_item(item: LabeledDescription, spec: ScenarioSpec) -> dict[str, list[bool | None]]:
    """Per fact (side, start, direction): True right, False wrong, None not read."""
    text = {f.name for f in spec.grounding if f.source is FactSource.TEXT}
    out: dict[str, list[bool | None]] = {"side": [], "start": [], "direction": []}
    for actor, read in _pair(item, spec):
        position: RelativePosition | None = None
        detail: StartDetail | None = None
        direction: Direction | None = None
        if isinstance(read, ScenarioSpec):
            position = read.spawn_position if "spawn_position" in text else None
            detail = read.start_detail if "start_detail" in text else None
            direction = _adversary_direction(read)
        elif read is not None:
            position = read.start
            if read.stationary:
                direction = Direction.STATIONARY
            elif read.start is not None:
                direction = _DIRECTION_OF_START.get(read.start)
        if actor.start is not None:
            if position is None:
                out["side"].append(None)
                out["start"].append(None)
            else:
                out["side"].append(_SIDE[actor.start] == _READ_SIDE[position])
                out["start"].append(_start_matches(actor.start, position, detail))
        if actor.direction is not None:
            out["direction"].append(None if direction is None else direction == actor.direction)
    return out


def score(verbose: bool = False) -> int:
    """Print, per set, the rules-only start side, start and direction against the truth."""
    print(f"{'set':<14}{'side':>14}{'start':>14}{'direction':>14}   (right/scored, not read)")
    for name in DEV_FILES:
        totals: dict[str, list[bool | None]] = {"side": [], "start": [], "direction": []}
        for item in load_devset(Path(DEVSET_DIR) / name):
            spec = ground(condense(item.text).text, NEUTRAL).spec
            got = score_item(item, spec)
            for key, values in got.items():
                totals[key] += values
            if verbose and any(v is not True for vs in got.values() for v in vs):
                print(f"  {item.id}: {got}  | {item.text[:90]}")
        cells = []
        for key in ("side", "start", "direction"):
            values = totals[key]
            right = sum(v is True for v in values)
            unread = sum(v is None for v in values)
            cells.append(f"{right}/{len(values)} ({unread})")
        print(f"{name.removesuffix('.jsonl'):<14}" + "".join(f"{c:>14}" for c in cells))
    return 0


def diff(old: Path, new: Path) -> int:
    before = {r["id"]: r["facts"] for r in map(json.loads, old.read_text().splitlines())}
    after = {r["id"]: r["facts"] for r in map(json.loads, new.read_text().splitlines())}
    moved = 0
    for key, facts in after.items():
        was = before.get(key, {})
        changes = {k: (was.get(k), v) for k, v in facts.items() if was.get(k) != v}
        changes.update({k: (v, None) for k, v in was.items() if k not in facts})
        if changes:
            moved += 1
            print(key)
            for name, (a, b) in changes.items():
                print(f"   {name}: {a} -> {b}")
    print(f"{moved} of {len(after)} readings moved", file=sys.stderr)
    return 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--diff", nargs=2, type=Path)
    parser.add_argument("--score", action="store_true", help="start and direction vs truth")
    parser.add_argument("-v", "--verbose", action="store_true", help="with --score: misses")
    args = parser.parse_args()
    if args.score:
        return score(args.verbose)
    if args.diff:
        return diff(*args.diff)
    for row in snapshot():
        print(json.dumps(row))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
