"""What a search minimises, read from the trace facts of one trial.

The numbers are those of the bench's criticality (`arise.evaluate.criticality`): the
ego against the adversary (our scripts' `AdversaryBehavior`, else the first other mover).
Smaller is more critical for every objective; a collision scores 0.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from enum import StrEnum
from typing import Any

from arise.evaluate.criticality import criticality
from arise.evaluate.search.errors import SearchError
from arise.evaluate.search.expression import Expression
from arise.validate.types import CheckResult

#: A time-to-collision above this is no conflict at all; also the score of a trial in
#: which the two never close in on each other.
TTC_CAP = 10.0
#: A trial is critical when the two collide or their time-to-collision drops below this.
CRITICAL_TTC = 1.0


class Objective(StrEnum):
    MIN_TTC = "min-ttc"  # smallest time-to-collision (s), capped at TTC_CAP
    MIN_DISTANCE = "min-distance"  # closest approach of the footprints (m)
    # Collision-seeking: the closest approach (m) too, but only a contact counts as found.
    COLLISION = "collision"
    CUSTOM = "custom"  # the user's expression over the same facts (`expression.py`)

    @property
    def unit(self) -> str:
        return {Objective.MIN_TTC: "s", Objective.CUSTOM: ""}.get(self, "m")

    @property
    def label(self) -> str:
        return {
            Objective.MIN_TTC: "min TTC (s)",
            Objective.MIN_DISTANCE: "min distance (m)",
            Objective.COLLISION: "min distance (m), 0 = collision",
            Objective.CUSTOM: "custom objective",
        }[self]


@dataclass(frozen=True)
class TrialOutcome:
    """One trial's verdict: whether it ran, its score and the facts behind it."""

    ok: bool
    value: float | None
    collision: bool = False
    min_ttc: float | None = None
    min_distance: float | None = None
    message: str | None = None
    seconds: float = 0.0

    @property
    def critical(self) -> bool:
        return self.ok and (
            self.collision or (self.min_ttc is not None and self.min_ttc < CRITICAL_TTC)
        )

    def found(self, objective: Objective) -> bool:
        """Did this trial reach what the search looks for?"""
        return self.ok and self.collision if objective is Objective.COLLISION else self.critical

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)


def score(
    objective: Objective,
    collision: bool,
    min_ttc: float | None,
    min_distance: float | None,
    *,
    route_completion: float | None = None,
    expression: Expression | None = None,
) -> float:
    """The number the search minimises."""
    if objective is Objective.CUSTOM:
        if expression is None:
            raise SearchError("--objective custom needs --expression")
        return expression.value(
            {
                "min_ttc": min(TTC_CAP, min_ttc if min_ttc is not None else TTC_CAP),
                "min_distance": max(0.0, min_distance or 0.0),
                "collision": 1.0 if collision else 0.0,
                "route_completion": route_completion if route_completion is not None else 0.0,
            }
        )
    if collision:
        return 0.0
    if objective is Objective.MIN_TTC:
        return round(min(TTC_CAP, min_ttc if min_ttc is not None else TTC_CAP), 3)
    return round(max(0.0, min_distance if min_distance is not None else 0.0), 3)


def outcome(
    result: CheckResult,
    objective: Objective,
    seconds: float,
    expression: Expression | None = None,
) -> TrialOutcome:
    """The verdict on one check of a trial's script."""
    if not result.ok or result.simulation is None:
        message = result.diagnostic.one_line() if result.diagnostic else "the script did not run"
        return TrialOutcome(ok=False, value=None, message=message, seconds=round(seconds, 3))
    facts = criticality(result.simulation)
    if facts is None or facts.min_distance is None:
        return TrialOutcome(
            ok=False,
            value=None,
            message="the scene has no agent besides the ego: nothing to be critical about",
            seconds=round(seconds, 3),
        )
    return TrialOutcome(
        ok=True,
        value=score(
            objective,
            facts.collision,
            facts.min_ttc,
            facts.min_distance,
            route_completion=facts.route_completion,
            expression=expression,
        ),
        collision=facts.collision,
        min_ttc=facts.min_ttc,
        min_distance=facts.min_distance,
        seconds=round(seconds, 3),
    )
