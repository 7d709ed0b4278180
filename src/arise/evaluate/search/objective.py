"""What a search minimises, read from the trace facts of one trial.

The numbers are those of the bench's criticality (`arise.evaluate.criticality`): the
ego against the adversary (our scripts' `AdversaryBehavior`, else the first other mover).
Smaller is more critical for every objective; a collision scores 0. The `score` objective
and expressions over driving metrics read the run's metrics as `arise drive` measures
them (`arise.drive.measure`): SafeBench's overall score is higher for a better drive, so
the search minimises it as it is.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from enum import StrEnum
from typing import Any

from arise.drive.measure import MetricRow, measure
from arise.errors import AriseError
from arise.evaluate.criticality import criticality
from arise.evaluate.search.errors import SearchError
from arise.evaluate.search.expression import (
    DRIVE_METRICS,
    Expression,
    no_value,
)
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
    # SafeBench's overall score of the ego's drive, 0 to 1 (higher is a better drive).
    SCORE = "score"
    CUSTOM = "custom"  # the user's expression over the same facts (`expression.py`)

    @property
    def unit(self) -> str:
        return {Objective.MIN_TTC: "s", Objective.CUSTOM: "", Objective.SCORE: ""}.get(self, "m")

    @property
    def label(self) -> str:
        return {
            Objective.MIN_TTC: "min TTC (s)",
            Objective.MIN_DISTANCE: "min distance (m)",
            Objective.COLLISION: "min distance (m), 0 = collision",
            Objective.SCORE: "overall score (SafeBench, 1 = perfect drive)",
            Objective.CUSTOM: "custom objective",
        }[self]


def needs_metrics(objective: Objective, expression: Expression | None) -> bool:
    """Does the score read the driving metrics (and so the map's road network)?"""
    if objective is Objective.SCORE:
        return True
    return objective is Objective.CUSTOM and expression is not None and expression.needs_metrics


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
    #: The run's driving metrics (`arise drive`'s row), when they were measured.
    metrics: MetricRow | None = None

    @property
    def overall_score(self) -> float | None:
        value = (self.metrics or {}).get("overall_score")
        return None if value is None else float(value)

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
    metrics: MetricRow | None = None,
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
                **drive_values(metrics),
            }
        )
    if objective is Objective.SCORE:
        value = (metrics or {}).get("overall_score")
        if value is None:
            raise SearchError("the score objective needs the run's driving metrics")
        return round(float(value), 4)
    if collision:
        return 0.0
    if objective is Objective.MIN_TTC:
        return round(min(TTC_CAP, min_ttc if min_ttc is not None else TTC_CAP), 3)
    return round(max(0.0, min_distance if min_distance is not None else 0.0), 3)


def drive_values(metrics: MetricRow | None) -> dict[str, float]:
    """Every driving metric as an expression reads it (`no_value` for one without)."""
    row = metrics or {}
    return {
        name: float(value) if (value := row.get(name)) is not None else no_value(name)
        for name in DRIVE_METRICS
    }


def outcome(
    result: CheckResult,
    objective: Objective,
    seconds: float,
    expression: Expression | None = None,
    *,
    metrics_steps: int | None = None,
) -> TrialOutcome:
    """The verdict on one check of a trial's script. With `metrics_steps` (the run's step
    limit, for SafeBench's time-out), the run's driving metrics are measured too; a score
    that needs them and cannot have them makes the trial fail."""
    if not result.ok or result.simulation is None:
        message = result.diagnostic.one_line() if result.diagnostic else "the script did not run"
        return TrialOutcome(ok=False, value=None, message=message, seconds=round(seconds, 3))
    metrics: MetricRow | None = None
    if metrics_steps is not None or needs_metrics(objective, expression):
        steps = metrics_steps or result.simulation.steps
        try:
            metrics = measure(result, steps * result.simulation.timestep)
        except AriseError as error:
            if needs_metrics(objective, expression):
                return TrialOutcome(
                    ok=False,
                    value=None,
                    message=f"cannot measure the drive: {error}",
                    seconds=round(seconds, 3),
                )
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
            metrics=metrics,
            expression=expression,
        ),
        collision=facts.collision,
        min_ttc=facts.min_ttc,
        min_distance=facts.min_distance,
        seconds=round(seconds, 3),
        metrics=metrics,
    )
