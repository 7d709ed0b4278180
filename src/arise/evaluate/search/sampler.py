"""VerifAI's samplers proposing values for a script's free parameters.

The proposals are VerifAI's (`verifai.server.choose_sampler` over a `FeatureSpace` of the
free parameters); this module only translates between parameters and VerifAI's points,
and turns a trial's score into the feedback VerifAI's active samplers learn from:

- cross-entropy (`ce`) moves its bucket distributions toward samples whose feedback is
  below 0, so the feedback is the score minus the elite level: the better of the best
  `ELITE_SHARE` of the scores so far and the critical level (TTC 1 s, contact);
- Bayesian optimisation (`bo`, needs GPyOpt) models the score itself and minimises it;
- our own `surrogate` (`surrogate.py`) fits a Gaussian process to the scores and tries
  where it expects the most gain; its uniform draws are VerifAI's random sampler's, so it
  starts exactly where `random` does.

VerifAI draws from Python's and numpy's global random generators; each sampler keeps its
own states and swaps them in around every call, so a search is reproducible from its
seed, whatever else runs in the process, and replays exactly when it resumes.
"""

from __future__ import annotations

import importlib.util
import random
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

from arise.evaluate.search.errors import SamplerUnavailable
from arise.evaluate.search.space import FreeParam, ParamKind, ParamValue
from arise.evaluate.search.surrogate import SurrogateSampler

#: Share of the scores so far that counts as elite for the cross-entropy update.
ELITE_SHARE = 0.3
#: Scores needed before the cross-entropy sampler starts to learn (before: uniform).
CE_WARMUP = 4
#: VerifAI's cross-entropy smoothing (its default 0.9 learns too slowly for 30 trials).
CE_ALPHA = 0.8
#: Buckets per continuous parameter for the cross-entropy sampler (VerifAI's default 5).
CE_BUCKETS = 5
#: Random trials before Bayesian optimisation fits its model (VerifAI's default 5).
BO_INITIAL = 5


class SamplerKind(StrEnum):
    RANDOM = "random"  # uniform, VerifAI's RandomSampler
    HALTON = "halton"  # low-discrepancy Halton sequence (passive)
    CE = "ce"  # cross-entropy (active)
    BO = "bo"  # Bayesian optimisation through GPyOpt (active)
    SURROGATE = "surrogate"  # ours: a Gaussian process's expected improvement (active)

    @property
    def active(self) -> bool:
        return self in (SamplerKind.CE, SamplerKind.BO, SamplerKind.SURROGATE)

    @property
    def verifai_kind(self) -> str:
        """The VerifAI sampler behind this one (ours draws VerifAI's uniform points)."""
        return "random" if self is SamplerKind.SURROGATE else self.value


@dataclass
class Proposal:
    """One point VerifAI proposed, as parameter values, with what VerifAI needs back."""

    values: dict[str, ParamValue]
    point: Any = None
    info: Any = None


def verifai_available() -> bool:
    return importlib.util.find_spec("verifai") is not None


def _require(kind: SamplerKind) -> None:
    if not verifai_available():
        raise SamplerUnavailable(
            "`arise search` needs VerifAI: pip install --no-deps verifai==2.2.0 dill "
            "(or `make setup-dev`; see docs/search.md)"
        )
    if kind is SamplerKind.BO and importlib.util.find_spec("GPyOpt") is None:
        raise SamplerUnavailable(
            "the 'bo' sampler needs GPyOpt and GPy (pip install GPyOpt GPy); "
            "or use --sampler ce, VerifAI's cross-entropy sampler"
        )


def _domain(param: FreeParam) -> Any:
    from verifai.features import Box, DiscreteBox

    if param.kind is ParamKind.RANGE:
        return Box([param.low, param.high])
    if param.kind is ParamKind.DISCRETE:
        return DiscreteBox([int(param.low), int(param.high)])
    return DiscreteBox([0, len(param.options) - 1])  # options by index


def _sampler_params(kind: SamplerKind) -> Any:
    from dotmap import DotMap

    if kind is SamplerKind.CE:
        return DotMap(alpha=CE_ALPHA, cont=DotMap(buckets=CE_BUCKETS))
    if kind is SamplerKind.BO:
        return DotMap(init_num=BO_INITIAL)
    return None


class ParamSampler:
    """A VerifAI sampler over the free parameters of one script."""

    def __init__(
        self, params: list[FreeParam], kind: SamplerKind, seed: int, critical_level: float
    ):
        _require(kind)
        from verifai.features import Feature, FeatureSpace
        from verifai.server import choose_sampler

        self.params = params
        self.kind = kind
        self.critical_level = critical_level
        self.scores: list[float] = []
        generator = random.Random(seed)
        self._py_state = generator.getstate()
        import numpy

        self._np_state = numpy.random.RandomState(seed % 2**32).get_state()
        space = FeatureSpace({p.name: Feature(_domain(p)) for p in params})
        with self._own_random():
            _, self._sampler = choose_sampler(space, kind.verifai_kind, _sampler_params(kind))
        self._surrogate = (
            SurrogateSampler(params, seed, lambda: self._draw().values)
            if kind is SamplerKind.SURROGATE
            else None
        )

    @contextmanager
    def _own_random(self) -> Iterator[None]:
        import numpy

        saved_py, saved_np = random.getstate(), numpy.random.get_state()
        random.setstate(self._py_state)
        numpy.random.set_state(self._np_state)
        try:
            yield
        finally:
            self._py_state, self._np_state = random.getstate(), numpy.random.get_state()
            random.setstate(saved_py)
            numpy.random.set_state(saved_np)

    def propose(self) -> Proposal:
        if self._surrogate is not None:
            return Proposal(values=self._surrogate.propose())
        return self._draw()

    def _draw(self) -> Proposal:
        """VerifAI's sampler's next point, as parameter values."""
        with self._own_random():
            point, info = self._sampler.getSample()
        values: dict[str, ParamValue] = {}
        for param in self.params:
            raw = getattr(point, param.name)
            values[param.name] = param.value_at(raw[0] if isinstance(raw, tuple | list) else raw)
        return Proposal(values=values, point=point, info=info)

    def feedback(self, score: float) -> float:
        """The value VerifAI is told for a trial that scored `score` (lower is better)."""
        self.scores.append(score)
        if self.kind is not SamplerKind.CE:
            return score
        if len(self.scores) < CE_WARMUP:
            return 1.0  # not yet an elite to learn from: no update
        ordered = sorted(self.scores)
        elite = ordered[max(0, int(len(ordered) * ELITE_SHARE) - 1)]
        level = max(elite, self.critical_level)
        return score - level - 1e-9  # below 0 (VerifAI's threshold) for the elite

    def tell(self, proposal: Proposal, score: float) -> None:
        """Report a trial's score (a failed trial: the worst score) to the sampler."""
        if self._surrogate is not None:
            self._surrogate.tell(proposal.values, score)
            return
        rho = self.feedback(score)
        with self._own_random():
            self._sampler.update(proposal.point, proposal.info, rho)
