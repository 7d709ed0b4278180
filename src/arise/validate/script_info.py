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
_TOWN_LITERAL = re.compile(r"""['"]?(Town\d+\w*?)(?:\.xodr)?['"]""")
_ASSIGN_TOWN = re.compile(r"""^\s*(\w+)\s*=\s*['"](Town\d+\w*)['"]\s*$""", re.M)
_XODR = re.compile(r"""['"]([^'"]+\.xodr)['"]""")


@dataclass(frozen=True)
class ScriptInfo:
    model: str | None
    model_line: int | None
    map_line: int | None
    map_expression: str | None
    requested_map: str | None  # a town name like "Town05" or a map file stem
    requested_map_file: str | None  # a literal .xodr path, if the script gives one
    ego_line: int | None


def _line_of(text: str, position: int) -> int:
    return text.count("\n", 0, position) + 1


def read_script_info(text: str) -> ScriptInfo:
    model_match = _MODEL.search(text)
    params = {m.group(1): m for m in _PARAM.finditer(text)}
    map_match = params.get("map")
    carla_map = params.get("carla_map")
    town_vars = {m.group(1): m.group(2) for m in _ASSIGN_TOWN.finditer(text)}

    requested: str | None = None
    requested_file: str | None = None
    if carla_map:
        literal = _TOWN_LITERAL.search(carla_map.group(2))
        if literal:
            requested = literal.group(1)
        elif carla_map.group(2).strip() in town_vars:
            requested = town_vars[carla_map.group(2).strip()]
    if map_match:
        expression = map_match.group(2)
        file_literal = _XODR.search(expression)
        if file_literal and "{" not in file_literal.group(1):
            requested_file = file_literal.group(1)
        if requested is None:
            literal = _TOWN_LITERAL.search(expression)
            if literal:
                requested = literal.group(1)
            else:
                for name, town in town_vars.items():
                    if re.search(rf"\b{name}\b", expression):
                        requested = town
                        break
        if requested is None and requested_file:
            requested = requested_file.rsplit("/", 1)[-1].removesuffix(".xodr")
    if requested is None and town_vars:
        requested = next(iter(town_vars.values()))

    ego = re.search(r"^\s*ego\s*=", text, re.M)
    return ScriptInfo(
        model=model_match.group(1) if model_match else None,
        model_line=_line_of(text, model_match.start(1)) if model_match else None,
        map_line=_line_of(text, map_match.start()) if map_match else None,
        map_expression=map_match.group(2) if map_match else None,
        requested_map=requested,
        requested_map_file=requested_file,
        ego_line=_line_of(text, ego.start()) if ego else None,
    )
