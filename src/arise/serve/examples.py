"""The example descriptions the page offers (one per scenario category of the paper, and
the demo's), kept as data in `examples.jsonl`."""

from __future__ import annotations

import json
from functools import cache
from importlib import resources


@cache
def examples() -> list[dict[str, str]]:
    text = resources.files(__package__).joinpath("examples.jsonl").read_text(encoding="utf-8")
    return [
        {"title": str(row["title"]), "description": str(row["description"])}
        for row in map(json.loads, filter(str.strip, text.splitlines()))
    ]
