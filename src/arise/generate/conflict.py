"""The conflict of a run: how close the adversary came to the ego, and whether that is what
the description asks for.

A test scenario is worth running only if its conflict happens. Every adversary that moves
must come within reach of the ego (issue 31): its box within 6 m of the ego's, or a
time-to-collision under 3 s. A description that says the two touched or nearly did
("struck", "made contact", "a near miss") asks for more: contact, or a TTC under 1.5 s.

The numbers are recomputed here from the two trajectories, not taken from the worker's
summary: the parent believes nothing a script could have written but the trace itself.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from enum import StrEnum
from typing import Any

from arise.generate.spec import ScenarioSpec
from arise.validate.facts import ego_pair_facts
from arise.validate.types import AgentTrace
from arise.vocabulary import RequirementKind

#: Within reach: the boxes this close (m), or a time-to-collision under REACH_TTC_S.
REACH_GAP_M = 6.0
REACH_TTC_S = 3.0
#: What "struck" or "nearly hit" asks for: contact, or a time-to-collision under this.
CLOSE_TTC_S = 1.5


class ConflictLevel(StrEnum):
    """What a description asks of the adversary's meeting with the ego."""

    NONE = "none"  # no adversary, or one that stays put (a parked or stalled car)
    REACH = "reach"  # its move meets the ego: within 6 m, or TTC under 3 s
    CLOSE = "close"  # the text says they touched or nearly did: contact, or TTC under 1.5 s

    @property
    def wanted(self) -> str:
        return {
            ConflictLevel.NONE: "no conflict asked for",
            ConflictLevel.REACH: f"within {REACH_GAP_M:g} m or TTC under {REACH_TTC_S:g} s",
            ConflictLevel.CLOSE: f"contact or TTC under {CLOSE_TTC_S:g} s",
        }[self]


def conflict_level(spec: ScenarioSpec) -> ConflictLevel:
    if spec.no_adversary or spec.adversary_stationary:
        return ConflictLevel.NONE
    close = spec.contact_stated or any(
        r.kind is RequirementKind.EVENTUALLY_CLOSE for r in spec.requirements
    )
    return ConflictLevel.CLOSE if close else ConflictLevel.REACH


def conflict_met(closest_m: float | None, min_ttc_s: float | None, level: ConflictLevel) -> bool:
    """Whether a closest gap (0: contact) and a smallest TTC (None: never closing) are what
    `level` asks for."""
    if level is ConflictLevel.NONE or closest_m == 0.0:
        return True
    ttc = min_ttc_s if min_ttc_s is not None else float("inf")
    if level is ConflictLevel.CLOSE:
        return ttc < CLOSE_TTC_S
    return ttc < REACH_TTC_S or (closest_m is not None and closest_m < REACH_GAP_M)


@dataclass(frozen=True)
class ConflictFacts:
    """The adversary against the ego over the run, from their trajectories."""

    adversary: str
    closest_m: float | None  # smallest gap between the two boxes (0: they touched)
    min_ttc_s: float | None  # smallest time-to-collision (None: they never closed in)
    contact: bool

    def meets(self, level: ConflictLevel) -> bool:
        return self.contact or conflict_met(self.closest_m, self.min_ttc_s, level)

    def describe(self) -> str:
        if self.contact:
            return "contact"
        gap = "no common step" if self.closest_m is None else f"closest {self.closest_m:.1f} m"
        ttc = "never closing" if self.min_ttc_s is None else f"TTC {self.min_ttc_s:.1f} s"
        return f"{gap}, {ttc}"

    def as_dict(self, level: ConflictLevel) -> dict[str, Any]:
        return {**asdict(self), "asked": level.value, "met": self.meets(level)}


def conflict_facts(ego: AgentTrace, adversary: AgentTrace) -> ConflictFacts:
    pair = ego_pair_facts([ego, adversary])[0]
    return ConflictFacts(
        adversary=adversary.name,
        closest_m=None if pair.min_distance < 0 else pair.min_distance,
        min_ttc_s=pair.min_ttc,
        contact=pair.collided,
    )
