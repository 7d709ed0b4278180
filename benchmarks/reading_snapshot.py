"""What the fixed readers make of every labeled dev description, without a model.

Writes one JSON line per description: the grounded spec's facts when the model's answer
says nothing useful. Two snapshots, before and after a change to the language layer, show
every reading the change moved (`--diff OLD NEW`). Dev sets only: the held-apart set is
never read here.

    python benchmarks/reading_snapshot.py > /tmp/before.jsonl
    python benchmarks/reading_snapshot.py --diff /tmp/before.jsonl /tmp/after.jsonl
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from arise.evaluate.fidelity import DEVSET_DIR, load_devset
from arise.generate.grounding import ground
from arise.generate.spec import ExtractionAnswer
from arise.language.condense import condense

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
DEV_FILES = ("short.jsonl", "nhtsa.jsonl", "crash_reports.jsonl", "styles.jsonl")


def snapshot() -> list[dict[str, object]]:
    rows = []
    for name in DEV_FILES:
        for item in load_devset(Path(DEVSET_DIR) / name):
            spec = ground(condense(item.text).text, NEUTRAL).spec
            facts = {f.name: f.value for f in spec.grounding if f.name != "participant"}
            facts["actors"] = [a.describe() for a in spec.actors]
            facts["adversary_class"] = spec.scenic_class
            rows.append({"id": item.id, "facts": facts})
    return rows


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
    args = parser.parse_args()
    if args.diff:
        return diff(*args.diff)
    for row in snapshot():
        print(json.dumps(row))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
