"""Our local-search sampler (`--sampler local`): values inside the declared space, the same
proposals from the same seed and scores (so a resumed search replays), a search that
closes in on a low score, and, slow, the failure of a real scene found within a few
trials."""

from __future__ import annotations

import json
import random
import statistics
from pathlib import Path

import pytest
from typer.testing import CliRunner

from arise.cli import app
from arise.evaluate.search import FreeParam, ParamKind, SamplerKind
from arise.evaluate.search.local import INITIAL, MAX_RADIUS, MIN_RADIUS, LocalSearch
from arise.evaluate.search.sampler import ParamSampler, verifai_available
from tests.evaluate.test_search_agent import CROSSING

PARAMS = [
    FreeParam("SPEED", ParamKind.RANGE, 1, "Range(0, 10)", low=0, high=10),
    FreeParam("GAP", ParamKind.DISCRETE, 2, "DiscreteRange(3, 6)", low=3, high=6),
    FreeParam("CAR", ParamKind.OPTIONS, 3, "Uniform('a', 'b', 'c')", options=("a", "b", "c")),
]


def _score(values: dict[str, object]) -> float:
    """A bowl with its bottom at SPEED 7.3, GAP 4, CAR 'b' (score 0 there)."""
    speed = float(values["SPEED"])  # type: ignore[arg-type]
    gap = int(values["GAP"])  # type: ignore[call-overload]
    return abs(speed - 7.3) + abs(gap - 4) + (0.0 if values["CAR"] == "b" else 2.0)


def _run(seed: int, trials: int) -> list[dict[str, object]]:
    sampler = ParamSampler(PARAMS, SamplerKind.LOCAL, seed=seed, critical_level=1.0)
    seen = []
    for _ in range(trials):
        proposal = sampler.propose()
        seen.append(dict(proposal.values))
        sampler.tell(proposal, _score(proposal.values))
    return seen


def test_values_stay_inside_the_space_and_keep_their_types() -> None:
    for values in _run(seed=5, trials=60):
        assert 0 <= float(values["SPEED"]) <= 10  # type: ignore[arg-type]
        assert values["GAP"] in (3, 4, 5, 6) and isinstance(values["GAP"], int)
        assert values["CAR"] in ("a", "b", "c")


def test_the_first_trials_cover_every_stratum_of_each_range() -> None:
    search = LocalSearch(dimensions=2, seed=0)
    points = [search.propose() for _ in range(INITIAL)]
    for axis in range(2):
        assert sorted(int(p[axis] * INITIAL) for p in points) == list(range(INITIAL))


def test_same_seed_same_proposals_whatever_else_draws_and_another_seed_differs() -> None:
    first = _run(seed=4, trials=20)
    random.seed(99)
    random.random()
    assert _run(seed=4, trials=20) == first
    assert _run(seed=5, trials=20) != first


def test_a_resumed_search_proposes_what_the_uninterrupted_one_did() -> None:
    """What the runner does on resume: a fresh sampler re-proposes the saved trials, is
    told their saved scores, then goes on; its proposals match the uninterrupted search,
    also when the batch proposes several points before any score comes back."""
    whole = _run(seed=2, trials=16)
    saved = whole[:9]
    sampler = ParamSampler(PARAMS, SamplerKind.LOCAL, seed=2, critical_level=1.0)
    replayed = []
    for values in saved:
        proposal = sampler.propose()
        assert proposal.values == values
        sampler.tell(proposal, _score(values))
    for _ in range(7):
        proposal = sampler.propose()
        replayed.append(dict(proposal.values))
        sampler.tell(proposal, _score(proposal.values))
    assert replayed == whole[9:]

    batched = ParamSampler(PARAMS, SamplerKind.LOCAL, seed=2, critical_level=1.0)
    first = [batched.propose() for _ in range(2)]
    again = ParamSampler(PARAMS, SamplerKind.LOCAL, seed=2, critical_level=1.0)
    assert [p.values for p in first] == [again.propose().values for _ in range(2)]


def test_it_closes_in_on_the_low_scores_where_random_does_not() -> None:
    """On the bowl, the local search's late proposals score far lower than uniform ones,
    and its best is near the bottom for most seeds (a local search can miss the right
    option of a list and stay on the wrong one: its uniform share is what leaves it)."""
    late, best = [], []
    for seed in range(5):
        seen = [_score(v) for v in _run(seed=seed, trials=30)]
        late.append(statistics.mean(seen[-10:]))
        best.append(min(seen))
    uniform = random.Random(0)
    blind = [
        _score(
            {
                "SPEED": uniform.uniform(0, 10),
                "GAP": uniform.randint(3, 6),
                "CAR": uniform.choice("abc"),
            }
        )
        for _ in range(200)
    ]
    assert statistics.mean(late) < 0.5 * statistics.mean(blind)
    assert statistics.median(best) < 1.0


def test_the_radius_grows_on_a_better_trial_and_shrinks_otherwise_within_bounds() -> None:
    search = LocalSearch(dimensions=1, seed=0)
    for index in range(INITIAL):
        search.tell(search.propose(), 5.0 + index)
    start = search.radius
    search.tell((0.5,), 1.0)  # a new best
    assert search.radius > start
    for _ in range(40):
        search.tell((0.5,), 9.0)
    assert search.radius == pytest.approx(MIN_RADIUS)
    for score in range(40):
        search.tell((0.5,), -float(score))
    assert search.radius == pytest.approx(MAX_RADIUS)


def test_without_any_difference_in_scores_it_keeps_sampling_the_whole_space() -> None:
    """Every trial capped (no conflict yet): nothing to be near, so proposals stay spread."""
    search = LocalSearch(dimensions=1, seed=3)
    points = []
    for _ in range(40):
        point = search.propose()
        points.append(point[0])
        search.tell(point, 10.0)
    late = points[INITIAL:]
    assert min(late) < 0.2 and max(late) > 0.8


def test_the_local_sampler_needs_no_verifai() -> None:
    """It is ours: it builds without touching VerifAI's modules (only VerifAI's need it)."""
    assert not SamplerKind.LOCAL.verifai and SamplerKind.LOCAL.active
    sampler = ParamSampler(PARAMS[:1], SamplerKind.LOCAL, seed=0, critical_level=1.0)
    assert sampler.propose().info is None


@pytest.mark.slow
def test_it_finds_the_blind_agents_failure_and_resumes_into_the_full_search(
    tmp_path: Path,
) -> None:
    if not verifai_available():
        pytest.skip("the worker loads Scenic's VerifAI support (docs/search.md)")
    script = tmp_path / "crossing.scenic"
    script.write_text(CROSSING, encoding="utf-8")
    out = tmp_path / "out"
    args = ["search", str(script), "--agent", "blind", "--sampler", "local"]
    args += ["--trials", "8", "--out", str(out), "--no-replay"]
    cli = CliRunner()
    first = cli.invoke(app, [*args, "--until-found"])
    assert first.exit_code == 0, first.output
    (stopped,) = json.loads((out / "search.json").read_text(encoding="utf-8"))["searches"]
    assert stopped["sampler"] == "local"
    assert stopped["first_critical"] is not None and stopped["first_critical"] <= 8
    assert stopped["trials"] == stopped["first_found"]
    again = cli.invoke(app, args)  # the same search, all its trials: it replays, then runs
    assert again.exit_code == 0, again.output
    (full,) = json.loads((out / "search.json").read_text(encoding="utf-8"))["searches"]
    assert full["trials"] == 8 and full["resumed"] == stopped["trials"]
    assert full["first_found"] == stopped["first_found"]
