"""Prompt templates live here as files, so they can be read, diffed and tuned without code."""

from __future__ import annotations

import json
from functools import cache
from importlib import resources
from typing import Any


@cache
def load(name: str) -> str:
    """The text of a prompt file in this folder."""
    return resources.files(__name__).joinpath(name).read_text(encoding="utf-8")


def load_jsonl(name: str) -> list[dict[str, Any]]:
    return [json.loads(line) for line in load(name).splitlines() if line.strip()]
