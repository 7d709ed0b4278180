"""Where a fitted model of the trials so far says the score is lowest: our active sampler.

A trial's score (TTC, distance) often moves steadily with a lever: a later start, a
faster adversary, a shorter gap. So after the first few trials the search fits, over the
parameters scaled to [-1, 1], a model with a slope and a curvature per parameter (ridge
least squares: a few trials in many parameters still give a usable direction) and tries
the point where the model is lowest, a little shaken so two proposals never coincide. That
point is often a corner of the box, which a uniform draw almost never reaches, or the
bottom of a timing window (too early and the agent sees it coming, too late and the two
miss). A share of the proposals stays uniform, in case the model is wrong.

The uniform draws come from the caller (VerifAI's random sampler, with the search's seed),
so until the model has its first trials this sampler proposes exactly what `random` would.
Parameters with unordered options are not modelled: they take the best trial's option or a
uniform one. Measured against `idm` on the dev scenes (docs/benchmarks.md): it gets closer
to contact than `random` within the same trials, but finds the first failure no sooner.
"""

from __future__ import annotations

import random
from collections.abc import Callable
from dataclasses import dataclass

import numpy

from arise.evaluate.search.space import FreeParam, ParamKind, ParamValue

#: Scored trials before the model is trusted; until then every proposal is uniform.
WARMUP = 3
#: Share of the later proposals that stay uniform.
EXPLORE_SHARE = 0.25
#: Ridge penalty on every coefficient but the mean (in units of the scaled parameters).
RIDGE = 0.3
#: How much a model's proposal is shaken (standard deviation, scaled units).
JITTER = 0.15
#: A proposal closer than this to a point already tried (mean scaled distance per
#: parameter) is shaken again, harder.
TOO_CLOSE = 0.08


@dataclass(frozen=True)
class _Tried:
    point: tuple[float, ...]  # ordered parameters, scaled to [-1, 1]
    options: dict[str, ParamValue]
    score: float


def _ordered(param: FreeParam) -> bool:
    return param.kind is not ParamKind.OPTIONS and param.high > param.low


def _scale(param: FreeParam, value: ParamValue) -> float:
    return 2.0 * (float(value) - param.low) / (param.high - param.low) - 1.0


def _unscale(param: FreeParam, u: float) -> float:
    return param.low + (min(1.0, max(-1.0, u)) + 1.0) / 2.0 * (param.high - param.low)


def fit_minimum(points: numpy.ndarray, scores: numpy.ndarray) -> numpy.ndarray:
    """The point of [-1, 1]^d where a separable quadratic, ridge-fitted to the scores, is
    lowest (per parameter: the vertex when it curves up inside the box, else an end)."""
    count, dims = points.shape
    features = numpy.hstack([numpy.ones((count, 1)), points, points**2])
    penalty = numpy.eye(1 + 2 * dims) * RIDGE
    penalty[0, 0] = 0.0
    coef = numpy.linalg.solve(features.T @ features + penalty, features.T @ scores)
    slope, curve = coef[1 : 1 + dims], coef[1 + dims :]
    best = numpy.empty(dims)
    for i, (a, b) in enumerate(zip(slope, curve, strict=True)):
        ends = [-1.0, 1.0]
        if b > 1e-9:
            ends.append(float(numpy.clip(-a / (2 * b), -1.0, 1.0)))
        best[i] = min((float(a * u + b * u * u), u) for u in ends)[1]
    return best


class SurrogateSampler:
    """Proposes parameter values from a model of the scores so far (see the module)."""

    def __init__(
        self,
        params: list[FreeParam],
        seed: int,
        uniform: Callable[[], dict[str, ParamValue]],
    ):
        self.params = params
        self.ordered = [p for p in params if _ordered(p)]
        self._uniform = uniform
        self._rng = numpy.random.default_rng([seed, 31])
        self._coin = random.Random(seed * 7919 + 31)
        self._tried: list[_Tried] = []
        self._pending: list[tuple[float, ...]] = []

    def propose(self) -> dict[str, ParamValue]:
        if len(self._tried) < WARMUP or not self.ordered or self._coin.random() < EXPLORE_SHARE:
            values = self._uniform()
        else:
            values = self._from_model()
        self._pending.append(self._point(values))
        return values

    def tell(self, values: dict[str, ParamValue], score: float) -> None:
        point = self._point(values)
        if point in self._pending:
            self._pending.remove(point)
        options = {p.name: values[p.name] for p in self.params if not _ordered(p)}
        self._tried.append(_Tried(point, options, score))

    def _point(self, values: dict[str, ParamValue]) -> tuple[float, ...]:
        return tuple(round(_scale(p, values[p.name]), 6) for p in self.ordered)

    def _from_model(self) -> dict[str, ParamValue]:
        points = numpy.array([t.point for t in self._tried])
        scores = numpy.array([t.score for t in self._tried])
        target = fit_minimum(points, scores)
        seen = numpy.array([t.point for t in self._tried] + self._pending)
        spread = JITTER
        for _ in range(6):
            candidate = numpy.clip(target + self._rng.normal(0.0, spread, target.shape), -1, 1)
            if numpy.abs(seen - candidate).mean(axis=1).min() >= TOO_CLOSE:
                break
            spread *= 1.6
        best = min(self._tried, key=lambda t: t.score)
        uniform = self._uniform() if any(not _ordered(p) for p in self.params) else {}
        values: dict[str, ParamValue] = {}
        scaled = dict(zip((p.name for p in self.ordered), candidate, strict=True))
        for param in self.params:
            if _ordered(param):
                values[param.name] = param.value_at(_unscale(param, scaled[param.name]))
            else:
                keep = self._coin.random() < 0.5
                values[param.name] = best.options[param.name] if keep else uniform[param.name]
        return values
