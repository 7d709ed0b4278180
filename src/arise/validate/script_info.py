"""What a script says about itself before it runs: its model line and the map it wants.

Read from the text, never by executing it: the validator overrides the model and the map,
which would hide both.
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

_MODEL = re.compile(r"^\s*model\s+([A-Za-z_][\w.]*)\s*$", re.M)
_PARAM = re.compile(r"^\s*param\s+(\w+)\s*=\s*(.+?)\s*$", re.M)
_STRING_ASSIGN = re.compile(r"""^\s*(\w+)\s*=\s*f?['"]([^'"]+)['"]\s*$""", re.M)
_STRING = re.compile(r"""f?['"]([^'"]*)['"]""")
_PLACEHOLDER = re.compile(r"\{(\w+)\}")


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


def _line_of(text: str, position: int) -> int:
    return text.count("\n", 0, position) + 1


def _resolve_string(expression: str, strings: dict[str, str]) -> str | None:
    """The string an expression spells, filling f-string fields from simple assignments."""
    expression = expression.strip()
    if expression in strings:
        return strings[expression]
    literal = _STRING.search(expression)
    if not literal:
        return None
    value = _PLACEHOLDER.sub(lambda m: strings.get(m.group(1), m.group(0)), literal.group(1))
    return None if "{" in value else value


def read_script_info(text: str) -> ScriptInfo:
    model_match = _MODEL.search(text)
    params = {m.group(1): m for m in _PARAM.finditer(text)}
    strings = {m.group(1): m.group(2) for m in _STRING_ASSIGN.finditer(text)}
    map_match = params.get("map")
    carla_map = params.get("carla_map")

    requested: str | None = None
    requested_file: str | None = None
    if map_match:
        value = _resolve_string(map_match.group(2), strings)
        if value and value.endswith(".xodr"):
            requested_file = value
            requested = value.replace("\\", "/").rsplit("/", 1)[-1].removesuffix(".xodr")
    if requested is None and carla_map:
        requested = _resolve_string(carla_map.group(2), strings)
    if requested is None:
        towns = [v for v in strings.values() if re.fullmatch(r"Town\d+\w*", v)]
        requested = towns[0] if towns else None

    ego = re.search(r"^\s*ego\s*=", text, re.M)
    return ScriptInfo(
        model=model_match.group(1) if model_match else None,
        model_line=_line_of(text, model_match.start(1)) if model_match else None,
        map_line=_line_of(text, map_match.start(1)) if map_match else None,
        map_expression=map_match.group(2) if map_match else None,
        requested_map=requested,
        requested_map_file=requested_file,
        ego_line=_line_of(text, ego.start()) if ego else None,
        param_lines={name: _line_of(text, m.start(1)) for name, m in params.items()},
    )
