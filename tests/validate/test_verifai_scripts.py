"""Scripts in the style of Scenic's VerifAI examples (NHTSA pre-crash typologies with
`VerifaiRange`, `VerifaiDiscreteRange`, `VerifaiOptions`, `VerifaiParameter.withPrior`
and `param verifaiSamplerType`) pass offline, sampled by VerifAI's own samplers.

The scripts in tests/data/verifai are ours, written in that style."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from arise.validate import CheckOptions, CheckResult, Stage, WorkerPool, check
from arise.validate.diagnostics import hint_for
from tests.conftest import DATA

pytest.importorskip("verifai", reason="the verifai extra is not installed (docs/search.md)")

VERIFAI = DATA / "verifai"
SCRIPTS = ["lead_vehicle_brakes", "pedestrian_crossing", "oncoming_left_turn", "cut_in"]


def _param(result: CheckResult, name: str) -> str:
    assert result.simulation is not None
    return result.simulation.params[name]


@pytest.mark.slow
@pytest.mark.parametrize("name", SCRIPTS)
def test_verifai_style_script_runs_offline(name: str, validator_pool: WorkerPool) -> None:
    result = check(VERIFAI / f"{name}.scenic", CheckOptions(seed=5), pool=validator_pool)
    assert result.ok, result.diagnostic
    assert result.simulation is not None and result.simulation.steps > 0
    assert result.sandbox is not None and result.sandbox.active


@pytest.mark.slow
def test_values_come_from_verifai_halton_sequence(validator_pool: WorkerPool) -> None:
    """The first VerifAI parameter takes base-2 Halton points: (x - low) / width is a
    fraction with a power-of-two denominator, which uniform random draws never are."""
    result = check(
        VERIFAI / "lead_vehicle_brakes.scenic", CheckOptions(seed=5), pool=validator_pool
    )
    assert result.ok, result.diagnostic
    fraction = (float(_param(result, "EGO_SPEED")) - 7) / 3
    assert 0 < fraction < 1
    scaled = fraction * 2**12
    assert math.isclose(scaled, round(scaled), abs_tol=1e-6)
    gap = int(_param(result, "LEAD_GAP"))
    assert 12 <= gap <= 20
    assert _param(result, "LEAD_MODEL") in (
        "vehicle.audi.a2",
        "vehicle.nissan.micra",
        "vehicle.toyota.prius",
    )
    assert _param(result, "verifaiSamplerType") == "halton"


@pytest.mark.slow
def test_cross_entropy_with_weights_and_priors_compiles(validator_pool: WorkerPool) -> None:
    """Weights, buckets and priors under the cross-entropy sampler fail in Scenic 3.1.1
    with numpy 2 (scenic_patches, patch 5); with the patch they sample within bounds."""
    walk = check(VERIFAI / "pedestrian_crossing.scenic", CheckOptions(seed=2), pool=validator_pool)
    assert walk.ok, walk.diagnostic
    assert 1.0 <= float(_param(walk, "WALK_SPEED")) <= 2.0
    assert 20 <= int(_param(walk, "PED_AHEAD")) <= 35
    turn = check(VERIFAI / "oncoming_left_turn.scenic", CheckOptions(seed=2), pool=validator_pool)
    assert turn.ok, turn.diagnostic
    assert _param(turn, "ADV_MODEL") in ("vehicle.tesla.model3", "vehicle.audi.tt")
    assert float(_param(turn, "ADV_SPEED")) > 0


@pytest.mark.slow
@pytest.mark.parametrize(
    ("sampler", "wanted"),
    [("sa", "one of 'random', 'halton'"), ("bo", "GPyOpt")],
)
def test_sampler_problems_name_the_param_line(
    sampler: str, wanted: str, validator_pool: WorkerPool, tmp_path: Path
) -> None:
    if sampler == "bo":
        try:
            import GPyOpt  # noqa: F401

            pytest.skip("GPyOpt is installed: 'bo' runs")
        except ImportError:
            pass
    text = (VERIFAI / "cut_in.scenic").read_text(encoding="utf-8")
    script = tmp_path / "cut_in.scenic"
    script.write_text(text.replace("'halton'", f"'{sampler}'"), encoding="utf-8")
    result = check(script, CheckOptions(seed=5), pool=validator_pool)
    assert result.diagnostic is not None
    assert result.diagnostic.stage is Stage.COMPILE
    assert result.diagnostic.line == 7
    assert wanted in (result.diagnostic.hint or "")


def test_missing_verifai_says_how_to_install_it() -> None:
    hint = hint_for("ModuleNotFoundError", "No module named 'verifai'")
    assert hint is not None and "--no-deps verifai" in hint


@pytest.mark.slow
@pytest.mark.carla_towns
@pytest.mark.parametrize("name", ["lead_vehicle_brakes", "cut_in"])
def test_verifai_style_script_runs_on_carla_towns(
    name: str, validator_pool: WorkerPool, carla_maps: Path
) -> None:
    result = check(
        VERIFAI / f"{name}.scenic",
        CheckOptions(seed=5, map_dir=str(carla_maps)),
        pool=validator_pool,
    )
    assert result.ok, result.diagnostic
    assert result.map is not None and result.map.name.startswith("Town")
