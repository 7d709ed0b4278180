"""Module C: the chosen entries become one script in marked sections.

A small model is good at copying and poor at writing Scenic, so entries are copied
verbatim and the model only tunes their `OPT_*` parameters to the description (one short
structured call); every value it proposes is checked and bounded before it is used.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from pydantic import BaseModel, create_model

from arise.generate.retrieve import Retrieval
from arise.kb.compose import compose
from arise.kb.schema import Entry
from arise.llm.base import BaseProvider
from arise.llm.types import Message
from arise.prompts import load
from arise.vocabulary import ActorClass

# The value ends at its line's last non-space (possessive spaces, no lazy value before
# `\s*$`, which backtracked quadratically on a long run of spaces in a KB snippet).
_PARAM_LINE = re.compile(r"^param\s+(OPT_[A-Z0-9_]+)\s*+=\s*+(.*\S)", re.M)
_NUMBER = r"-?\d+(?:\.\d+)?"
_VALUE = re.compile(rf"^\s*(?:({_NUMBER})|Range\(\s*({_NUMBER})\s*,\s*({_NUMBER})\s*\))\s*$")
MAX_STRETCH = 2.0  # a tuned value may be at most this factor outside the default's range


@dataclass
class Draft:
    """One assembled script and what went into it."""

    script: str
    entries: list[Entry]
    map_name: str
    adversary_class: ActorClass | None  # None: the scene has no adversary
    params: dict[str, str] = field(default_factory=dict)  # tuned values actually used
    notes: list[str] = field(default_factory=list)


def declared_params(entries: list[Entry]) -> dict[str, tuple[str, str]]:
    """OPT_* name -> (default value text, id of the entry declaring it)."""
    found: dict[str, tuple[str, str]] = {}
    for entry in entries:
        for name, value in _PARAM_LINE.findall(entry.snippet):
            found.setdefault(name, (value, entry.id))
    return found


def range_bounds(value: str) -> tuple[float, float] | None:
    """(low, high) of a parameter's value text: a number or `Range(a, b)`."""
    match = _VALUE.match(value)
    if not match:
        return None
    if match.group(1) is not None:
        number = float(match.group(1))
        return number, number
    low, high = float(match.group(2)), float(match.group(3))
    return (low, high) if low <= high else None


def checked_value(proposed: Any, default: str) -> str | None:
    """The proposed value as Scenic text, if it is well-formed and near the default."""
    text = str(proposed).strip()
    if isinstance(proposed, (int, float)) and not isinstance(proposed, bool):
        text = f"{proposed:g}"
    wanted, usual = range_bounds(text), range_bounds(default)
    if wanted is None or usual is None:
        return None
    low, high = usual
    span_low = min(low / MAX_STRETCH, low * MAX_STRETCH)
    span_high = max(high * MAX_STRETCH, high / MAX_STRETCH)
    if not (span_low - 1e-9 <= wanted[0] and wanted[1] <= span_high + 1e-9):
        return None
    if (low >= 0) and wanted[0] < 0:
        return None
    return text


def apply_params(script: str, values: Mapping[str, str]) -> str:
    def replace(match: re.Match[str]) -> str:
        name = match.group(1)
        return f"param {name} = {values[name]}" if name in values else match.group(0)

    return _PARAM_LINE.sub(replace, script)


def adapt_messages(description: str, listing: str) -> list[Message]:
    """The tuning call: fixed system prompt, then the description and the parameters."""
    return [
        Message("system", load("adapt_system.md")),
        Message("user", f"Description: {description.strip()}\n\nParameters:\n{listing}"),
    ]


def tune_params(
    description: str,
    entries: list[Entry],
    provider: BaseProvider,
    *,
    temperature: float = 0.0,
    seed: int | None = None,
) -> tuple[dict[str, str], list[str]]:
    """Ask the model for OPT_* values; keep only checked ones. Returns values and notes."""
    declared = declared_params(entries)
    if not declared:
        return {}, []
    fields: dict[str, Any] = {name: (str | float, ...) for name in declared}
    schema: type[BaseModel] = create_model("TunedParams", **fields)
    messages = adapt_messages(description, parameter_listing(entries, declared))
    completion = provider.complete(
        messages, temperature=temperature, max_tokens=300, schema=schema, seed=seed
    )
    proposed = completion.parsed.model_dump() if completion.parsed is not None else {}
    values: dict[str, str] = {}
    notes: list[str] = []
    for name, (default, _) in declared.items():
        value = checked_value(proposed.get(name), default)
        if value is None:
            notes.append(f"{name}: kept default {default} (model proposed {proposed.get(name)!r})")
        elif value.replace(" ", "") != default.replace(" ", ""):
            values[name] = value
    return values, notes


def parameter_listing(entries: list[Entry], declared: dict[str, tuple[str, str]]) -> str:
    """The parameters under the entry that declares them, each entry described once.

    Naming the entry's description once per entry, not once per parameter, shortened the
    tuning prompt from 486 to 404 tokens (median over 15 dev-set runs). Each name keeps
    "(default X)": written "NAME = default", the model replaced every range by a number."""
    by_entry: dict[str, list[str]] = {}
    for name, (default, entry_id) in declared.items():
        by_entry.setdefault(entry_id, []).append(f"- {name} (default {default})")
    described = {entry.id: entry.descriptions[0] for entry in entries}
    return "\n".join(
        f"{described[entry_id]}\n" + "\n".join(lines) for entry_id, lines in by_entry.items()
    )


def assemble(
    retrieval: Retrieval,
    adversary_class: ActorClass | None,
    description: str,
    params: Mapping[str, str] | None = None,
) -> Draft:
    """Compose the chosen entries (ComposeError if they do not fit) and apply tuned params."""
    entries = retrieval.chosen_entries()
    if retrieval.map_name is None:
        from arise.kb.compose import ComposeError

        raise ComposeError(["no available map has every feature the chosen entries need"])
    script = compose(entries, adversary_class, retrieval.map_name, description=description)
    values = dict(params or {})
    return Draft(
        script=apply_params(script, values),
        entries=entries,
        map_name=retrieval.map_name,
        adversary_class=adversary_class,
        params=values,
    )
