"""VerifAI's samplers, driven through `ParamSampler`: reproducible from the seed whatever
else draws random numbers, values inside the declared space, and the cross-entropy
sampler learns from the feedback it is given."""

from __future__ import annotations

import importlib.util
import random
import statistics

import numpy
import pytest

from arise.evaluate.search import FreeParam, ParamKind, SamplerKind, SamplerUnavailable
from arise.evaluate.search.sampler import ParamSampler
from arise.evaluate.search.surrogate import WARMUP, ScoreModel, _finite

pytest.importorskip("verifai", reason="the verifai extra is not installed (docs/search.md)")

PARAMS = [
    FreeParam("SPEED", ParamKind.RANGE, 1, "Range(0, 10)", low=0, high=10),
    FreeParam("GAP", ParamKind.DISCRETE, 2, "DiscreteRange(3, 6)", low=3, high=6),
    FreeParam("CAR", ParamKind.OPTIONS, 3, "Uniform('a', 'b')", options=("a", "b")),
]


@pytest.mark.parametrize(
    "kind", [SamplerKind.RANDOM, SamplerKind.HALTON, SamplerKind.CE, SamplerKind.SURROGATE]
)
def test_same_seed_same_proposals_whatever_else_draws(kind: SamplerKind) -> None:
    first = ParamSampler(PARAMS, kind, seed=4, critical_level=1.0)
    second = ParamSampler(PARAMS, kind, seed=4, critical_level=1.0)
    a = []
    for _ in range(6):
        proposal = first.propose()
        a.append(proposal.values)
        first.tell(proposal, float(proposal.values["SPEED"]))
    b = []
    for _ in range(6):
        random.random()
        numpy.random.rand(3)
        proposal = second.propose()
        b.append(proposal.values)
        second.tell(proposal, float(proposal.values["SPEED"]))
    assert a == b
    for values in a:
        assert 0 <= float(values["SPEED"]) <= 10
        assert values["GAP"] in (3, 4, 5, 6) and isinstance(values["GAP"], int)
        assert values["CAR"] in ("a", "b")


def test_halton_proposes_the_halton_sequence() -> None:
    sampler = ParamSampler(PARAMS[:1], SamplerKind.HALTON, seed=0, critical_level=1.0)
    assert [sampler.propose().values["SPEED"] for _ in range(3)] == [5.0, 2.5, 7.5]


def test_cross_entropy_moves_toward_low_scores_and_random_does_not() -> None:
    """Score = SPEED: VerifAI's cross-entropy sampler, fed the elite feedback, ends up
    proposing small speeds; the random sampler keeps its mean near 5."""

    def late_mean(kind: SamplerKind) -> float:
        sampler = ParamSampler(PARAMS[:1], kind, seed=1, critical_level=0.0)
        seen = []
        for _ in range(60):
            proposal = sampler.propose()
            speed = float(proposal.values["SPEED"])
            seen.append(speed)
            sampler.tell(proposal, speed)
        return statistics.mean(seen[-20:])

    assert late_mean(SamplerKind.CE) < 3.0
    assert late_mean(SamplerKind.RANDOM) > 3.5


def test_elite_feedback_is_negative_only_below_the_level() -> None:
    sampler = ParamSampler(PARAMS[:1], SamplerKind.CE, seed=0, critical_level=1.0)
    for score in (9.0, 8.0, 7.0, 6.0):
        sampler.feedback(score)
    assert sampler.feedback(0.5) < 0  # critical: always elite
    assert sampler.feedback(9.5) > 0


@pytest.mark.skipif(importlib.util.find_spec("GPyOpt") is not None, reason="GPyOpt installed")
def test_bayesian_optimisation_without_gpyopt_says_what_to_install() -> None:
    with pytest.raises(SamplerUnavailable, match="GPyOpt"):
        ParamSampler(PARAMS, SamplerKind.BO, seed=0, critical_level=1.0)


def test_surrogate_starts_with_the_random_samplers_points() -> None:
    """Until it has scores to fit, ours proposes exactly what `random` does (same seed)."""
    ours = ParamSampler(PARAMS, SamplerKind.SURROGATE, seed=3, critical_level=1.0)
    plain = ParamSampler(PARAMS, SamplerKind.RANDOM, seed=3, critical_level=1.0)
    for _ in range(WARMUP):
        mine, theirs = ours.propose(), plain.propose()
        assert mine.values == theirs.values
        ours.tell(mine, 5.0)
        plain.tell(theirs, 5.0)


def test_surrogate_proposes_plain_python_values_inside_the_space() -> None:
    """The values are written into the script as they are: a numpy scalar would read
    `np.float64(4.2)` there and fail to compile."""
    sampler = ParamSampler(PARAMS, SamplerKind.SURROGATE, seed=0, critical_level=1.0)
    for _ in range(12):
        proposal = sampler.propose()
        values = proposal.values
        assert type(values["SPEED"]) is float and 0 <= values["SPEED"] <= 10
        assert type(values["GAP"]) is int and values["GAP"] in (3, 4, 5, 6)
        assert values["CAR"] in ("a", "b")
        sampler.tell(proposal, float(values["SPEED"]) / 2 + values["GAP"])


def test_score_model_finds_the_lever_that_matters_and_where_the_score_is_low() -> None:
    """A score that moves with one parameter and ignores the other: the fit gives the
    ignored one a long length scale, and expects the most gain where the score falls."""
    rng = numpy.random.default_rng(0)
    points = rng.uniform(-1, 1, size=(14, 2))
    scores = 3.0 + 2.0 * (points[:, 0] - 0.4) ** 2
    model = ScoreModel(points, scores)
    assert model.lengths[1] > model.lengths[0]
    grid = numpy.array([[-0.9, 0.0], [0.4, 0.0], [0.9, 0.0]])
    assert int(numpy.argmax(model.expected_improvement(grid))) == 1
    mean, sd = model.predict(points[:1])
    assert abs(model.mean + model.scale * mean[0] - scores[0]) < 0.2 and sd[0] < 0.2


def test_surrogate_finds_a_corner_failure_sooner_than_random() -> None:
    """A score that falls under the critical level only near one corner of six
    parameters: ours finds it in far fewer trials than uniform draws (40 seeds)."""
    params = [
        FreeParam(f"P{i}", ParamKind.RANGE, i, "Range(0, 10)", low=0, high=10) for i in range(6)
    ]

    def ttc(values: dict[str, object]) -> float:
        u = [float(values[p.name]) / 5 - 1 for p in params]  # type: ignore[arg-type]
        return 2.6 - 1.2 * u[0] - 1.0 * u[2] + 0.8 * u[4] ** 2

    def mean_first(kind: SamplerKind) -> float:
        firsts = []
        for seed in range(40):
            sampler = ParamSampler(params, kind, seed=seed, critical_level=1.0)
            first = 31
            for trial in range(30):
                proposal = sampler.propose()
                score = ttc(proposal.values)
                sampler.tell(proposal, score)
                if score < 1.0:
                    first = trial + 1
                    break
            firsts.append(first)
        return statistics.mean(firsts)

    assert mean_first(SamplerKind.SURROGATE) < 0.5 * mean_first(SamplerKind.RANDOM)


def test_surrogate_takes_infinite_and_undefined_scores() -> None:
    """A custom expression may score a trial inf or nan: the model still proposes values
    inside the space."""
    raw = numpy.array([float("inf"), 3.0, float("nan"), 2.0, float("-inf")])
    assert _finite(raw).tolist() == [3.0, 3.0, 3.0, 2.0, 2.0]
    model = ScoreModel(numpy.array([[-0.5], [0.0], [0.5], [0.9], [-0.9]]), _finite(raw))
    assert numpy.isfinite(model.expected_improvement(numpy.array([[0.2]]))).all()
    sampler = ParamSampler(PARAMS, SamplerKind.SURROGATE, seed=1, critical_level=1.0)
    scores = [float("inf"), 3.0, float("nan"), 2.0, float("-inf"), 4.0, 1.5, 2.5]
    for score in scores:
        proposal = sampler.propose()
        assert 0 <= float(proposal.values["SPEED"]) <= 10
        sampler.tell(proposal, score)
