"""The ego against the other agents: contacts, time-to-collision, post-encroachment time.

Every agent is its oriented box (width x length about its centre, along its heading).
Contact is an overlap of two boxes at the same step (touching counts). Time-to-collision
is exact for the boxes under constant velocity and heading (`contact_times`). The
post-encroachment time is the shortest time between one agent leaving a piece of road and
the other reaching it: over every pair of steps at which the two boxes overlap in space,
the smallest difference of the steps' times (0 for a contact).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
import shapely

from arise.drive.metrics_track import Track, common_steps, contact_times, overlapping
from arise.drive.metrics_types import MetricsError

#: Pairs of overlapping footprints examined for one PET at most: a real run has a few
#: thousand; only a trace in which two agents dwell on one spot for thousands of steps
#: each (a forged one) comes near, and it is refused rather than measured for minutes.
MAX_PET_PAIRS = 2_000_000
_CHUNK = 64  # ego footprints per spatial query


@dataclass(frozen=True)
class Contacts:
    """How many times the ego came into contact with another agent, and the first step."""

    count: int
    first_step: int | None


def contacts(ego: Track, others: Iterable[Track]) -> Contacts:
    """Starts of an overlap between the ego and each other agent (an overlap held over
    consecutive steps is one contact; a gap in the steps ends it)."""
    count = 0
    first: int | None = None
    for other in others:
        ia, ib = common_steps(ego, other)
        touching = overlapping(ego, ia, other, ib)
        if not touching.any():
            continue
        steps = ego.steps[ia]
        continued = np.zeros(len(ia), dtype=bool)
        continued[1:] = touching[:-1] & (np.diff(steps) == 1)
        count += int(np.sum(touching & ~continued))
        start = int(steps[np.argmax(touching)])
        first = start if first is None else min(first, start)
    return Contacts(count=count, first_step=first)


def min_ttc(ego: Track, others: Iterable[Track]) -> float | None:
    """The smallest time-to-collision with any other agent over the common steps (None:
    never on course to touch)."""
    best = math.inf
    for other in others:
        ia, ib = common_steps(ego, other)
        if len(ia):
            best = min(best, float(np.min(contact_times(ego, ia, other, ib))))
    return None if math.isinf(best) else best


def min_gap(ego: Track, others: Iterable[Track]) -> float | None:
    """The smallest distance between the ego's box and any of `others`' boxes at the same
    step, metres (0: contact; None: no common step)."""
    best = math.inf
    for other in others:
        ia, ib = common_steps(ego, other)
        if len(ia):
            mine = shapely.polygons(ego.corners()[ia])
            theirs = shapely.polygons(other.corners()[ib])
            best = min(best, float(np.min(shapely.distance(mine, theirs))))
    return None if math.isinf(best) else best


def post_encroachment(ego: Track, others: Iterable[Track], timestep: float) -> float | None:
    """The smallest post-encroachment time with any of `others`, seconds (None: their
    paths never cross)."""
    best = math.inf
    for other in others:
        ia, ib = common_steps(ego, other)
        if overlapping(ego, ia, other, ib).any():
            return 0.0
        best = min(best, _smallest_gap(ego, other))
    return None if math.isinf(best) else best * timestep


def _smallest_gap(ego: Track, other: Track) -> float:
    """The smallest |step difference| between overlapping footprints (inf: none)."""
    if not len(ego) or not len(other):
        return math.inf
    mine = shapely.polygons(ego.corners())
    theirs = shapely.polygons(other.corners())
    tree = shapely.STRtree(theirs)
    best = math.inf
    examined = 0
    for start in range(0, len(mine), _CHUNK):
        rows, columns = tree.query(mine[start : start + _CHUNK], predicate="intersects")
        examined += len(rows)
        if examined > MAX_PET_PAIRS:
            raise MetricsError(
                f"the ego's and {other.name}'s footprints overlap at more than "
                f"{MAX_PET_PAIRS:,} pairs of steps: too many to measure a PET"
            )
        if len(rows):
            gaps = np.abs(ego.steps[start + rows] - other.steps[columns])
            best = min(best, float(gaps.min()))
    return best
