"""Free parameters are read from the script's own `param` lines, and fixing them changes
those lines only."""

from __future__ import annotations

from arise.evaluate.search import ParamKind, find_free_params, fix_params
from tests.conftest import DATA

SCRIPT = """param map = localPath('maps/arise_straight.xodr')
model scenic.simulators.carla.model
param weather = Uniform('ClearNoon', 'WetNoon')
GAP = [10, 20]
LOW = 2
param OPT_ADV_SPEED = Range(LOW, 2 * LOW + 1)  # m/s
param OPT_MODE = Uniform('a', 'b')
param LANES = Uniform(1, 2, 3)
param EGO_SPEED = VerifaiRange(7, 10)
param GAP_M = VerifaiDiscreteRange(*GAP)
param CAR = VerifaiOptions({'vehicle.audi.tt': 2, 'vehicle.tesla.model3': 1})
param PRIOR = VerifaiParameter.withPrior(Normal(7, 1.5))
param NOISE = Normal(0, 1)
param FIXED = 3
param LATER = Range(0, 1)
param LATER = 0.5
param SPREAD = Range(ego_speed, 4)
ego = new Car
"""


def test_every_kind_of_free_parameter_is_found() -> None:
    params = {p.name: p for p in find_free_params(SCRIPT)}
    assert list(params) == [
        "OPT_ADV_SPEED",
        "OPT_MODE",
        "LANES",
        "EGO_SPEED",
        "GAP_M",
        "CAR",
        "PRIOR",
        "NOISE",
    ]
    speed = params["OPT_ADV_SPEED"]
    assert (speed.kind, speed.low, speed.high, speed.line) == (ParamKind.RANGE, 2, 5, 6)
    assert params["OPT_MODE"].options == ("a", "b")  # an OPT_ choice counts, even of words
    assert params["LANES"].options == (1, 2, 3)
    assert params["EGO_SPEED"].verifai and params["EGO_SPEED"].kind is ParamKind.RANGE
    assert (params["GAP_M"].kind, params["GAP_M"].low, params["GAP_M"].high) == (
        ParamKind.DISCRETE,
        10,
        20,
    )
    assert params["CAR"].options == ("vehicle.audi.tt", "vehicle.tesla.model3")
    assert (params["PRIOR"].low, params["PRIOR"].high) == (4.0, 10.0)
    assert (params["NOISE"].low, params["NOISE"].high) == (-2.0, 2.0)


def test_weather_words_fixed_values_overrides_and_unknown_bounds_are_not_free() -> None:
    names = {p.name for p in find_free_params(SCRIPT)}
    assert not names & {"weather", "FIXED", "LATER", "SPREAD", "map"}


def test_fixing_changes_only_the_param_lines_and_says_what_was_searched() -> None:
    params = find_free_params(SCRIPT)
    values = {"OPT_ADV_SPEED": 3.123456, "GAP_M": 12, "CAR": "vehicle.tesla.model3"}
    fixed = fix_params(SCRIPT, params, values)
    before, after = SCRIPT.splitlines(), fixed.splitlines()
    assert len(before) == len(after)
    changed = [i for i, (a, b) in enumerate(zip(before, after, strict=True)) if a != b]
    assert [after[i] for i in changed] == [
        "param OPT_ADV_SPEED = 3.1235  # searched in Range(LOW, 2 * LOW + 1)",
        "param GAP_M = 12  # searched in VerifaiDiscreteRange(*GAP)",
        "param CAR = 'vehicle.tesla.model3'  # searched in "
        "VerifaiOptions({'vehicle.audi.tt': 2, 'vehicle.tesla.model3': 1})",
    ]
    left = {p.name for p in find_free_params(fixed)}
    assert not left & set(values)


def test_a_generated_script_has_its_opt_ranges_free() -> None:
    text = (DATA / "base_crossing.scenic").read_text(encoding="utf-8")
    assert [p.name for p in find_free_params(text)] == [
        "OPT_ADV_SPEED",
        "OPT_TRIGGER",
        "OPT_GEO_Y_DISTANCE",
    ]
