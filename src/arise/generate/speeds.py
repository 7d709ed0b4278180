"""Stated speeds as parameter values: "the AV was travelling at 17 mph" sets the ego's speed
parameter, "V2 ... at about 30 mph" the adversary's, without asking the model.

A stated speed becomes a narrow range around it (a tenth either way), so a search still has
room; a value far from the entry's own range (a motorway speed in a town-street entry) is
refused as the model's would be, and the default stands.
"""

from __future__ import annotations

from collections.abc import Iterable

from arise.generate.assemble import checked_value, declared_params
from arise.generate.spec import ScenarioSpec
from arise.kb.schema import Entry

EGO_SPEED = "OPT_EGO_SPEED"
ADVERSARY_SPEED = "OPT_ADV_SPEED"
#: The share either way of a stated speed its range keeps.
SPREAD = 0.1


def stated_speeds(spec: ScenarioSpec, entries: Iterable[Entry]) -> dict[str, str]:
    """The speed parameters of these entries that the description states."""
    declared = declared_params(list(entries))
    values: dict[str, str] = {}
    for name, speed in ((EGO_SPEED, spec.ego_speed), (ADVERSARY_SPEED, spec.adversary_speed)):
        if speed is None or speed <= 0 or name not in declared:
            continue
        wanted = f"Range({speed * (1 - SPREAD):.1f}, {speed * (1 + SPREAD):.1f})"
        checked = checked_value(wanted, declared[name][0])
        if checked is not None:
            values[name] = checked
    return values
