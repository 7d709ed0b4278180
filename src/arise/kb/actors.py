"""An entry written for the adversary, copied for another actor of the scene.

Spawn and behavior entries are written for one actor, the adversary: a spawn defines
`adversary` and anchor names such as `advStart` and `advLane`, a behavior defines
`AdversaryBehavior` and reads those anchors. `for_actor` renames a copy so that several
actors compose in one script without their names colliding:

    adversary          -> actor2
    advStart, advLane  -> actor2Start, actor2Lane
    AdversaryBehavior  -> Actor2Behavior
    Steer (any other)  -> Actor2Steer
    OPT_SPAWN_GAP      -> OPT_ACTOR2_SPAWN_GAP

and fills in the actor's class. Names the entry uses but neither defines nor gets from its
partner (`egoStart`, `egoLane`, `conflictManeuver`) are the scene's and stay as they are.
The copy keeps the entry's id and says which actor it places (`Entry.actor`), so the
composer marks it `# kb: <id> as actor2` and a diagnostic leads back to both.
"""

from __future__ import annotations

import re

from arise.errors import AriseError
from arise.kb.schema import Component, Entry
from arise.vocabulary import ActorClass

ADVERSARY_NAME = "adversary"
ADVERSARY_BEHAVIOR = "AdversaryBehavior"
#: Distance parameters of a spawn, shifted for each further copy of a counted actor.
_DISTANCE_PARAM = re.compile(r"(?:AHEAD|GAP|BEHIND|TO_JUNCTION|INTO_EXIT|BEFORE_JUNCTION)$")
_NUMBER = r"(-?\d+(?:\.\d+)?)"
# `param OPT_X = Range(a, b)` (groups 3, 4) or `param OPT_X = a` (group 5).
_PARAM_RANGE = re.compile(
    rf"^(param\s+(OPT_[A-Z0-9_]+)\s*=\s*)(?:Range\(\s*{_NUMBER}\s*,\s*{_NUMBER}\s*\)|{_NUMBER}\s*$)",
    re.M,
)
ACTOR_PATTERN = re.compile(r"^actor[0-9]+$")


class ActorCopyError(AriseError, ValueError):
    """An entry cannot be copied for that actor (a caller's mistake, not the entry's)."""


def actor_name(name: str, actor: str) -> str:
    """What one of the adversary's names becomes for `actor` (e.g. 'actor2')."""
    if name == ADVERSARY_NAME:
        return actor
    if name == ADVERSARY_BEHAVIOR:
        return f"{actor[0].upper()}{actor[1:]}Behavior"
    if name.startswith("adv") and name[3:4].isupper():
        return f"{actor}{name[3:]}"
    return f"{actor[0].upper()}{actor[1:]}{name}"


def actor_param(name: str, actor: str) -> str:
    """OPT_SPAWN_GAP -> OPT_ACTOR2_SPAWN_GAP."""
    return f"OPT_{actor.upper()}_{name.removeprefix('OPT_')}"


def _is_actor_own(name: str) -> bool:
    """A name a spawn or behavior pair shares about its one actor (renamed with it)."""
    return name in (ADVERSARY_NAME, ADVERSARY_BEHAVIOR) or (
        name.startswith("adv") and name[3:4].isupper()
    )


def for_actor(
    entry: Entry, actor: str, scenic_class: ActorClass, *, copy: int = 0, spacing: float = 0.0
) -> Entry:
    """A copy of a spawn or behavior `entry` that places or moves `actor` instead of the
    adversary (see the module's docstring).

    copy, spacing: the `copy`-th of several actors from the same entry; a spawn's distance
    parameters (`OPT_*_AHEAD`, `_GAP`, `_BEHIND`, ...) are moved `copy * spacing` metres
    further out, so that copies stand in a row instead of on top of each other.
    """
    if entry.component not in (Component.SPAWN, Component.BEHAVIOR):
        raise ActorCopyError(f"{entry.id}: only spawn and behavior entries place an actor")
    if not ACTOR_PATTERN.match(actor):
        raise ActorCopyError(f"{actor!r} is not an actor name like 'actor2'")
    cls = ActorClass.of(scenic_class)
    if cls is None or not cls.is_road_user:
        raise ActorCopyError(f"{scenic_class!s} is not a road user's class")
    renames = {name: actor_name(name, actor) for name in entry.defines}
    renames |= {name: actor_name(name, actor) for name in entry.needs if _is_actor_own(name)}
    renames.setdefault(ADVERSARY_BEHAVIOR, actor_name(ADVERSARY_BEHAVIOR, actor))
    renames.setdefault(ADVERSARY_NAME, actor)
    params = {name: actor_param(name, actor) for name in entry.params}
    snippet = entry.snippet
    if copy and spacing and entry.component is Component.SPAWN:
        snippet = _shift_distances(snippet, copy * spacing)
    table = renames | params
    pattern = re.compile(r"\b(" + "|".join(map(re.escape, sorted(table, key=len)[::-1])) + r")\b")
    snippet = pattern.sub(lambda m: table[m.group(1)], snippet)
    snippet = snippet.replace("{{ADVERSARY_CLASS}}", cls.value)
    return entry.model_copy(
        update={
            "snippet": snippet,
            "defines": [renames[name] for name in entry.defines],
            "needs": [renames.get(name, name) for name in entry.needs],
            "params": [params[name] for name in entry.params],
            "placeholders": [p for p in entry.placeholders if p != "ADVERSARY_CLASS"],
            "actor": actor,
            "actor_class": cls,
        }
    )


def _shift_distances(snippet: str, metres: float) -> str:
    """Move every distance parameter's range `metres` further out."""

    def shift(match: re.Match[str]) -> str:
        if not _DISTANCE_PARAM.search(match.group(2)):
            return match.group(0)
        if match.group(5) is not None:
            return f"{match.group(1)}{float(match.group(5)) + metres:g}"
        low, high = float(match.group(3)) + metres, float(match.group(4)) + metres
        return f"{match.group(1)}Range({low:g}, {high:g})"

    return _PARAM_RANGE.sub(shift, snippet)


def spawn_span(entry: Entry) -> float:
    """The widest range of the spawn's distance parameters (0 when fixed): how far apart two
    draws of it may fall."""
    spans = [
        float(match.group(4)) - float(match.group(3)) if match.group(5) is None else 0.0
        for match in _PARAM_RANGE.finditer(entry.snippet)
        if _DISTANCE_PARAM.search(match.group(2))
    ]
    return max(spans, default=0.0)
