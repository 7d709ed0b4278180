"""Our own active sampler: a local search around the best trials so far (`--sampler local`).

Why not only VerifAI's: its cross-entropy sampler learns a distribution over 5 buckets per
parameter, which needs more than 30 trials to move on 4 to 6 parameters; it did not find
the agent's failures sooner than random (issue 31). A failure of the agent usually sits in
a narrow timing window (who reaches the conflict point when), and a trial that came close
(a small TTC) is near it. So this sampler:

1. spreads its first `INITIAL` trials over the space (a Latin hypercube: every parameter's
   range is cut in `INITIAL` strata and each stratum is drawn once);
2. then proposes points around one of the `ELITE` best trials so far (the best most
   often), moved by a Gaussian step of `radius` (a share of each range) per parameter;
   the radius grows after a trial that beat the best and shrinks after one that did not,
   between `MIN_RADIUS` and `MAX_RADIUS`;
3. keeps exploring: a share `EXPLORE` of the proposals, and every proposal while all the
   scores are equal (no trial has closed in yet: nothing to be near), are uniform.

Points live in the unit cube, one coordinate per parameter; the search space maps them to
values. All draws come from one `random.Random(seed)`, and the feedback is the score
alone, so the same seed and the same scores give the same proposals: a resumed search
replays exactly.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field

from arise.evaluate.search.space import DECIMALS, FreeParam, ParamKind, ParamValue

#: Space-filling trials before the search starts to follow the scores.
INITIAL = 5
#: How many of the best trials a proposal may start from (weights ELITE, ..., 1).
ELITE = 3
#: Share of the proposals after the initial ones that are uniform, to leave a bad basin.
EXPLORE = 0.2
#: Step of a proposal, as a share of each parameter's range: at start, and its bounds.
START_RADIUS = 0.2
MIN_RADIUS = 0.04
MAX_RADIUS = 0.35
#: The radius after a trial that beat the best (GROW) and after one that did not (SHRINK).
GROW = 1.3
SHRINK = 0.85
#: Scores closer than this count as equal (scores are rounded to 3 decimals).
TIE = 1e-6


@dataclass
class LocalSearch:
    """The local search over `dimensions` unit coordinates."""

    dimensions: int
    seed: int
    radius: float = START_RADIUS
    told: list[tuple[tuple[float, ...], float]] = field(default_factory=list)
    proposed: int = 0
    _rng: random.Random = field(init=False)
    _initial: list[tuple[float, ...]] = field(init=False)

    def __post_init__(self) -> None:
        self._rng = random.Random(f"local-search:{self.seed}")
        self._initial = self._latin_hypercube(INITIAL)

    def _latin_hypercube(self, count: int) -> list[tuple[float, ...]]:
        columns = []
        for _ in range(self.dimensions):
            strata = list(range(count))
            self._rng.shuffle(strata)
            columns.append([(s + self._rng.random()) / count for s in strata])
        return [tuple(column[i] for column in columns) for i in range(count)]

    def _uniform(self) -> tuple[float, ...]:
        return tuple(self._rng.random() for _ in range(self.dimensions))

    def _informative(self) -> bool:
        """Has any trial scored differently from the others (something to be near)?"""
        scores = [score for _, score in self.told]
        return bool(scores) and max(scores) - min(scores) > TIE

    def _parent(self) -> tuple[float, ...]:
        ranked = sorted(self.told, key=lambda item: item[1])[:ELITE]
        weights = [len(ranked) - i for i in range(len(ranked))]
        return self._rng.choices([point for point, _ in ranked], weights=weights)[0]

    def _step(self, value: float) -> float:
        moved = value + self._rng.gauss(0.0, self.radius)
        # Reflect at the bounds (a clip would pile proposals up on the edges).
        moved = abs(moved) % 2.0
        return 2.0 - moved if moved > 1.0 else moved

    def propose(self) -> tuple[float, ...]:
        index = self.proposed
        self.proposed += 1
        if index < len(self._initial):
            return self._initial[index]
        explore = self._rng.random() < EXPLORE
        if explore or not self._informative():
            return self._uniform()
        return tuple(self._step(value) for value in self._parent())

    def tell(self, point: tuple[float, ...], score: float) -> None:
        best = min((s for _, s in self.told), default=math.inf)
        self.told.append((point, score))
        if len(self.told) <= INITIAL:
            return
        if score < best - TIE:
            self.radius = min(MAX_RADIUS, self.radius * GROW)
        else:
            self.radius = max(MIN_RADIUS, self.radius * SHRINK)


def unit_to_values(params: list[FreeParam], point: tuple[float, ...]) -> dict[str, ParamValue]:
    """The parameter values at a point of the unit cube: a range linearly, an integer
    range and a list of options in equal cells (each integer or option gets its share)."""
    values: dict[str, ParamValue] = {}
    for param, unit in zip(params, point, strict=True):
        unit = min(max(unit, 0.0), 1.0)
        if param.kind is ParamKind.RANGE:
            values[param.name] = round(param.low + unit * (param.high - param.low), DECIMALS)
        elif param.kind is ParamKind.DISCRETE:
            low, high = int(param.low), int(param.high)
            values[param.name] = min(high, low + int(unit * (high - low + 1)))
        else:
            last = len(param.options) - 1
            values[param.name] = param.options[min(last, int(unit * len(param.options)))]
    return values
