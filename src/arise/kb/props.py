"""A row of props copied for one obstacle of the scene, with its class and its count.

The knowledge base writes props entry by entry (two barrels, a box, a cone taper); a text
may name any prop class in any number ("four drums", "a ladder", "six delineators"). The
entries tagged `prop_row` place a row of three cones; `prop_row` copies one with the
text's class and count and names of its own, so that two rows compose in one script:

    rowRef, rowProps      -> rowRefP2, rowPropsP2
    OPT_MISC_ROW_AHEAD    -> OPT_MISC_ROW_AHEAD_P2
    new Cone ... range(3) -> new Barrel ... range(4)
"""

from __future__ import annotations

import re

from arise.errors import AriseError
from arise.kb.schema import Component, Entry
from arise.vocabulary import ActorClass

PROP_ROW_TAG = "prop_row"
#: The class and the count a row entry is written with.
_ROW_CLASS = re.compile(r"\bnew Cone\b")
_ROW_COUNT = re.compile(r"\brange\(3\)")
#: The longest row copied: more props than this stand in the road as this many.
MAX_ROW = 8


class PropRowError(AriseError, ValueError):
    """An entry cannot be copied as a row of that prop (a caller's mistake)."""


def prop_row(
    entry: Entry, prop: ActorClass, count: int, key: str, settings: dict[str, str] | None = None
) -> Entry:
    """A copy of the row `entry` that places `count` of `prop` (at most `MAX_ROW`), its
    names suffixed with `key` (e.g. 'P2'); `settings` fixes parameters of the copy
    (`{"OPT_MISC_ROW_LATERAL": "-3.5"}`: the lane to the left)."""
    if entry.component is not Component.MISC or PROP_ROW_TAG not in entry.tags:
        raise PropRowError(f"{entry.id}: not a row of props")
    if prop.is_road_user:
        raise PropRowError(f"{prop.value} is a road user, not a prop")
    if not re.fullmatch(r"[A-Z][A-Za-z0-9]*", key):
        raise PropRowError(f"{key!r} is not a name suffix like 'P2'")
    renames = {name: f"{name}{key}" for name in entry.defines}
    params = {name: f"{name}_{key}" for name in entry.params}
    table = renames | params
    pattern = re.compile(r"\b(" + "|".join(map(re.escape, sorted(table, key=len)[::-1])) + r")\b")
    snippet = _ROW_CLASS.sub(f"new {prop.value}", entry.snippet)
    snippet = _ROW_COUNT.sub(f"range({max(1, min(count, MAX_ROW))})", snippet)
    for name, value in (settings or {}).items():
        snippet = re.sub(
            rf"^(param\s+{re.escape(name)}\s*=\s*).*$", rf"\g<1>{value}", snippet, flags=re.M
        )
    snippet = pattern.sub(lambda m: table[m.group(1)], snippet)
    return entry.model_copy(
        update={
            "snippet": snippet,
            "defines": [renames[name] for name in entry.defines],
            "params": [params[name] for name in entry.params],
            "row": key,
        }
    )
