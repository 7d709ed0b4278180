"""Timing words as trigger values: "at the last moment" takes the late end of each trigger's
range, "well ahead" the early end.

Every adversary behavior of the knowledge base starts its move from the ego's state; how
soon is a trigger parameter whose smaller values are later (the ego nearer the conflict
when the adversary goes). A description that says when ("just as the ego passes") narrows
those ranges to the third it names. The model's tuning, when asked, still wins: it reads
stated numbers.
"""

from __future__ import annotations

from collections.abc import Iterable

from arise.generate.assemble import declared_params, range_bounds
from arise.kb.schema import Entry
from arise.vocabulary import Timing

#: Parameters that say how soon the adversary moves, in the ego's terms: the ego's distance
#: or time to the conflict point when it goes, or the gap it cuts into. Smaller is later.
TRIGGER_PARAMS = frozenset({"OPT_ADV_TRIGGER", "OPT_ADV_GAP", "OPT_ADV_CUT_GAP"})
#: The share of a range a timing word keeps, from the end it names.
SHARE = 1 / 3


def timed_params(timing: Timing | None, entries: Iterable[Entry]) -> dict[str, str]:
    """The trigger parameters of these entries narrowed to the end the timing names."""
    if timing is None:
        return {}
    values: dict[str, str] = {}
    for name, (default, _) in declared_params(list(entries)).items():
        bounds = range_bounds(default) if name in TRIGGER_PARAMS else None
        if bounds is None or bounds[0] == bounds[1]:
            continue
        low, high = bounds
        cut = low + (high - low) * SHARE if timing is Timing.LATE else high - (high - low) * SHARE
        low, high = (low, cut) if timing is Timing.LATE else (cut, high)
        values[name] = f"Range({low:g}, {high:g})"
    return values
