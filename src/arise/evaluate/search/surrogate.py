"""Where a model of the trials so far expects the most gain: our active sampler.

A trial's score (TTC, distance) moves with the levers, often smoothly and often with one
or two levers that matter: a later start, a faster adversary, a shorter gap. So after the
first few trials the search fits a Gaussian process to the scores over the parameters
scaled to [-1, 1], one length scale per parameter (picked by the fit's marginal
likelihood, so a lever the score ignores gets a long one), and tries the candidate with
the largest expected improvement over the best score so far. The candidates are uniform
points and points close around the best trials: a near miss is often one small step from
contact. Unlike a fitted quadratic, whose lowest point may sit in a corner the trials have
already ruled out, the process knows where it has looked. A share of the proposals stays
uniform, in case the model is wrong.

The uniform draws come from the caller (VerifAI's random sampler, with the search's seed),
so until the model has its first trials this sampler proposes exactly what `random` would.
Parameters with unordered options are not modelled: they take the best trial's option or a
uniform one. Measured against `random` on the dev scenes: docs/benchmarks.md.
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable
from dataclasses import dataclass

import numpy

from arise.evaluate.search.space import FreeParam, ParamKind, ParamValue

#: Scored trials before the model is trusted; until then every proposal is uniform.
WARMUP = 3
#: Share of the later proposals that stay uniform.
EXPLORE_SHARE = 0.2
#: Length scales a parameter may get (scaled units; the box is 2 wide).
LENGTH_SCALES = (0.25, 0.5, 1.0, 2.0, 4.0)
#: Noise variance of the normalized scores: a changed value may move the scene a little.
NOISE = 0.01
#: Uniform candidates for the expected improvement, and candidates around each best trial.
UNIFORM_CANDIDATES = 1500
LOCAL_CANDIDATES = 300
#: Best trials the local candidates gather around, and how far they stray (scaled units).
LOCAL_AROUND = 3
LOCAL_SPREADS = (0.05, 0.15, 0.35)


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


def _finite(scores: numpy.ndarray) -> numpy.ndarray:
    """Scores a Gaussian process can take: a custom expression may give an infinite or
    undefined one, counted as the worst (or, for minus infinity, the best) finite one."""
    finite = numpy.isfinite(scores)
    if finite.all():
        return scores
    low, high = (scores[finite].min(), scores[finite].max()) if finite.any() else (0.0, 0.0)
    return numpy.where(finite, scores, numpy.where(scores == -numpy.inf, low, high))


class ScoreModel:
    """A Gaussian process over scaled points, one length scale per dimension (see module)."""

    def __init__(self, points: numpy.ndarray, scores: numpy.ndarray):
        self.points = points
        self.mean = float(scores.mean())
        self.scale = float(scores.std()) or 1.0
        self.targets = (scores - self.mean) / self.scale
        dims = points.shape[1]
        self.lengths = numpy.full(dims, 1.0)
        best = self._evidence(self.lengths)
        for _ in range(2):  # coordinate ascent over the grid
            for i in range(dims):
                for length in LENGTH_SCALES:
                    trial = self.lengths.copy()
                    trial[i] = length
                    evidence = self._evidence(trial)
                    if evidence > best + 1e-9:
                        best, self.lengths = evidence, trial
        self._factor, self._alpha = self._solve(self.lengths)

    def _kernel(self, a: numpy.ndarray, b: numpy.ndarray, lengths: numpy.ndarray) -> numpy.ndarray:
        diff = (a[:, None, :] - b[None, :, :]) / lengths
        return numpy.exp(-0.5 * (diff**2).sum(axis=2))

    def _solve(self, lengths: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
        gram = self._kernel(self.points, self.points, lengths)
        factor = numpy.linalg.cholesky(gram + NOISE * numpy.eye(len(self.points)))
        alpha = numpy.linalg.solve(factor.T, numpy.linalg.solve(factor, self.targets))
        return factor, alpha

    def _evidence(self, lengths: numpy.ndarray) -> float:
        """Log marginal likelihood of the scores under these length scales (up to a constant)."""
        factor, alpha = self._solve(lengths)
        return float(-0.5 * self.targets @ alpha - numpy.log(numpy.diag(factor)).sum())

    def predict(self, candidates: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
        """Mean and standard deviation of the normalized score at each candidate."""
        cross = self._kernel(candidates, self.points, self.lengths)
        mean = cross @ self._alpha
        solved = numpy.linalg.solve(self._factor, cross.T)
        variance = numpy.clip(1.0 - (solved**2).sum(axis=0), 1e-12, None)
        return mean, numpy.sqrt(variance)

    def expected_improvement(self, candidates: numpy.ndarray) -> numpy.ndarray:
        """How far below the best score so far each candidate is expected to go."""
        mean, sd = self.predict(candidates)
        gain = self.targets.min() - mean
        z = gain / sd
        cdf = 0.5 * (1.0 + numpy.vectorize(math.erf)(z / math.sqrt(2.0)))
        pdf = numpy.exp(-0.5 * z * z) / math.sqrt(2.0 * math.pi)
        return numpy.asarray(gain * cdf + sd * pdf)


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

    def _candidates(self, points: numpy.ndarray, scores: numpy.ndarray) -> numpy.ndarray:
        dims = points.shape[1]
        spread = [self._rng.uniform(-1.0, 1.0, (UNIFORM_CANDIDATES, dims))]
        for index in numpy.argsort(scores)[:LOCAL_AROUND]:
            sizes = self._rng.choice(LOCAL_SPREADS, (LOCAL_CANDIDATES, 1))
            near = points[index] + self._rng.normal(0.0, 1.0, (LOCAL_CANDIDATES, dims)) * sizes
            spread.append(numpy.clip(near, -1.0, 1.0))
        return numpy.vstack(spread)

    def _from_model(self) -> dict[str, ParamValue]:
        points = numpy.array([t.point for t in self._tried])
        scores = _finite(numpy.array([t.score for t in self._tried]))
        candidates = self._candidates(points, scores)
        model = ScoreModel(points, scores)
        if self._pending:
            # Proposed in this batch but not scored yet: believe the model's guess for
            # them, so the next proposal goes elsewhere instead of beside them.
            pending = numpy.array(self._pending)
            guessed = model.mean + model.scale * model.predict(pending)[0]
            model = ScoreModel(
                numpy.vstack([points, pending]), numpy.concatenate([scores, guessed])
            )
        gains = model.expected_improvement(candidates)
        candidate = candidates[int(numpy.argmax(gains))]
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
