"""What a script says about itself before it runs: its model line and the map it wants.

Read from the text, never by executing it: the validator overrides the model and the map,
which would hide both.

The text is untrusted and can be as large as the validator accepts, so it is read one line
at a time with string methods, in time linear in its length: the only regular expressions
are anchored single runs (`\\w+`, a dotted name), which cannot backtrack.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

CARLA_MODEL = "scenic.simulators.carla.model"
KNOWN_MODELS = {
    CARLA_MODEL: "CARLA",
    "scenic.domains.driving.model": "generic driving domain",
    "scenic.simulators.newtonian.driving_model": "Newtonian driving",
    "scenic.simulators.metadrive.model": "MetaDrive",
}

_WORD = re.compile(r"\w+")
_DOTTED_NAME = re.compile(r"[A-Za-z_][\w.]*")
_QUOTES = "'\""


@dataclass(frozen=True)
class ScriptInfo:
    model: str | None
    model_line: int | None
    map_line: int | None
    map_expression: str | None
    requested_map: str | None  # a town name like "Town05" or a map file stem
    requested_map_file: str | None  # a literal .xodr path, if the script gives one
    ego_line: int | None
    param_lines: dict[str, int]


def _after_keyword(stripped: str, keyword: str) -> str | None:
    """What follows `keyword` and at least one space at the start of a line, else None."""
    if not stripped.startswith(keyword):
        return None
    rest = stripped[len(keyword) :]
    return rest.lstrip() if rest[:1].isspace() else None


def _assignment(stripped: str) -> tuple[str, str] | None:
    """`name = value` (both stripped; `value` may be empty), or None for any other line."""
    name = _WORD.match(stripped)
    if name is None:
        return None
    rest = stripped[name.end() :].lstrip()
    if not rest.startswith("="):
        return None
    return name.group(), rest[1:].strip()


def _model_of(stripped: str) -> str | None:
    """The world model a `model a.b.c` line names."""
    rest = _after_keyword(stripped, "model")
    return rest if rest and _DOTTED_NAME.fullmatch(rest) else None


def _param_of(stripped: str) -> tuple[str, str] | None:
    """Name and expression of a `param name = expression` line."""
    rest = _after_keyword(stripped, "param")
    found = _assignment(rest) if rest else None
    return found if found and found[1] else None


def _string_assignment_of(stripped: str) -> tuple[str, str] | None:
    """Name and text of `name = 'text'` (or an f-string): one literal, no quotes inside."""
    found = _assignment(stripped)
    if found is None:
        return None
    name, value = found
    value = value.removeprefix("f")
    if len(value) < 3 or value[0] not in _QUOTES or value[-1] not in _QUOTES:
        return None
    body = value[1:-1]
    return None if "'" in body or '"' in body else (name, body)


def _is_ego_assignment(stripped: str) -> bool:
    rest = stripped.removeprefix("ego")
    return rest != stripped and rest.lstrip().startswith("=")


def _first_quote(text: str, start: int = 0) -> int:
    found = [i for i in (text.find("'", start), text.find('"', start)) if i >= 0]
    return min(found) if found else -1


def _filled(value: str, strings: dict[str, str]) -> str | None:
    """`value` with each `{name}` replaced by the string `name` was assigned, or None if a
    field stays unfilled (an unknown name, a stray brace): then it is no literal path."""
    out: list[str] = []
    position = 0
    while (brace := value.find("{", position)) >= 0:
        name = _WORD.match(value, brace + 1)
        if name is None or not value.startswith("}", name.end()):
            return None
        filled = strings.get(name.group())
        if filled is None or "{" in filled:
            return None
        out += [value[position:brace], filled]
        position = name.end() + 1
    out.append(value[position:])
    return "".join(out)


def _resolve_string(expression: str, strings: dict[str, str]) -> str | None:
    """The string an expression spells, filling f-string fields from simple assignments."""
    expression = expression.strip()
    if expression in strings:
        return strings[expression]
    opening = _first_quote(expression)
    closing = _first_quote(expression, opening + 1) if opening >= 0 else -1
    if closing < 0:
        return None
    return _filled(expression[opening + 1 : closing], strings)


def _is_town(value: str) -> bool:
    """`Town` followed by a digit and word characters, e.g. Town05 or Town10HD_Opt."""
    rest = value.removeprefix("Town")
    return rest != value and rest[:1].isdecimal() and rest.replace("_", "a").isalnum()


def read_script_info(text: str) -> ScriptInfo:
    model: tuple[str, int] | None = None
    ego_line: int | None = None
    params: dict[str, tuple[str, int]] = {}  # the last statement of a name wins
    strings: dict[str, str] = {}
    for number, line in enumerate(text.split("\n"), start=1):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        if model is None and (name := _model_of(stripped)) is not None:
            model = (name, number)
        if (param := _param_of(stripped)) is not None:
            params[param[0]] = (param[1], number)
        if (assigned := _string_assignment_of(stripped)) is not None:
            strings[assigned[0]] = assigned[1]
        if ego_line is None and _is_ego_assignment(stripped):
            ego_line = number

    map_param = params.get("map")
    carla_map = params.get("carla_map")
    requested: str | None = None
    requested_file: str | None = None
    if map_param:
        value = _resolve_string(map_param[0], strings)
        if value and value.endswith(".xodr"):
            requested_file = value
            requested = value.replace("\\", "/").rsplit("/", 1)[-1].removesuffix(".xodr")
    if requested is None and carla_map:
        requested = _resolve_string(carla_map[0], strings)
    if requested is None:
        requested = next((v for v in strings.values() if _is_town(v)), None)

    return ScriptInfo(
        model=model[0] if model else None,
        model_line=model[1] if model else None,
        map_line=map_param[1] if map_param else None,
        map_expression=map_param[0] if map_param else None,
        requested_map=requested,
        requested_map_file=requested_file,
        ego_line=ego_line,
        param_lines={name: line for name, (_, line) in params.items()},
    )
