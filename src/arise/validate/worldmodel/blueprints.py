"""Blueprint checks: CARLA refuses to spawn an unknown blueprint, so offline we refuse too."""

from __future__ import annotations

import difflib
from functools import cache
from typing import Any

from arise.errors import AriseError

# Which blueprint prefixes each kind of actor may use.
_PREFIX_FOR_CLASS = {"Pedestrian": ("walker.",), "Vehicle": ("vehicle.",), "Prop": ("static.",)}


class UnknownBlueprintError(AriseError):
    """The script asks for a blueprint the installed CARLA version does not have.

    Raised inside Scenic's `simulate()`, which lets it through; the diagnostics and the
    repair rules know it by its class name.
    """


@cache
def known_blueprints() -> frozenset[str]:
    import scenic.simulators.carla.blueprints as table

    names: set[str] = set()
    for attribute in dir(table):
        value = getattr(table, attribute)
        if attribute.endswith("Models") and isinstance(value, (list, tuple)):
            names.update(value)
    names.update(getattr(table, "oldBlueprintNames", {}))
    return frozenset(names)


def _required_prefixes(obj: Any) -> tuple[str, ...] | None:
    for klass in type(obj).__mro__:
        if klass.__name__ in _PREFIX_FOR_CLASS and klass.__module__.startswith("arise"):
            return _PREFIX_FOR_CLASS[klass.__name__]
    return None


def check_blueprint(obj: Any) -> None:
    blueprint = getattr(obj, "blueprint", None)
    if not isinstance(blueprint, str):
        return
    known = known_blueprints()
    if blueprint not in known:
        close = difflib.get_close_matches(blueprint, sorted(known), n=3, cutoff=0.6)
        suggestion = f"; close valid ones: {', '.join(close)}" if close else ""
        raise UnknownBlueprintError(
            f"unknown CARLA blueprint '{blueprint}' for a {type(obj).__name__}{suggestion}"
        )
    prefixes = _required_prefixes(obj)
    if prefixes and not blueprint.startswith(prefixes):
        raise UnknownBlueprintError(
            f"blueprint '{blueprint}' is not a {type(obj).__name__} blueprint "
            f"(expected one starting with {' or '.join(prefixes)})"
        )
