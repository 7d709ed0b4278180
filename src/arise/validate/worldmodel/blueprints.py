"""Blueprint checks: CARLA refuses to spawn an unknown blueprint, so offline we refuse too."""

from __future__ import annotations

import difflib
from functools import cache
from typing import Any

from arise.errors import AriseError
from arise.vocabulary import ActorClass, ActorGroup

# Which blueprint prefixes each group of classes may use.
_PREFIX_FOR_GROUP: dict[ActorGroup, tuple[str, ...]] = {
    ActorGroup.VEHICLE: ("vehicle.",),
    ActorGroup.TWO_WHEELER: ("vehicle.",),
    ActorGroup.WALKER: ("walker.",),
    ActorGroup.PROP: ("static.",),
}
# The model's base classes, which a script may also create with a blueprint of its own.
_BASE_GROUPS: dict[str, ActorGroup] = {"Vehicle": ActorGroup.VEHICLE, "Prop": ActorGroup.PROP}


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


def _group(obj: Any) -> ActorGroup | None:
    """The group of the nearest class of our world model the object is an instance of (a
    script's own subclass of Car is a vehicle)."""
    for klass in type(obj).__mro__:
        if not klass.__module__.startswith("arise"):
            continue
        cls = ActorClass.of(klass.__name__)
        if cls is not None:
            return cls.group
        if klass.__name__ in _BASE_GROUPS:
            return _BASE_GROUPS[klass.__name__]
    return None


def _required_prefixes(obj: Any) -> tuple[str, ...] | None:
    group = _group(obj)
    return _PREFIX_FOR_GROUP[group] if group is not None else None


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
