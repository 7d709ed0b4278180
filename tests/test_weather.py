"""arise.weather: the typed weather value, its CARLA form, its visibility model and the
conditions the language rules name. CARLA's own numbers come from the installed client."""

from __future__ import annotations

import itertools
import json
import math

import carla
import pytest
from pydantic import ValidationError

from arise.vocabulary import WEATHER_FIELDS, WEATHER_PRESETS
from arise.weather import (
    BOUNDS,
    CONSTRUCTOR_DEFAULTS,
    MAX_PARAM_TEXT,
    PRESET_PARAMETERS,
    Light,
    TimeOfDay,
    Visibility,
    Weather,
    WeatherValueError,
    fog_density_for,
    time_of_day,
    visual_range_m,
    weather_for,
)

FLOAT32 = 1e-5


def _carla(parameters: carla.WeatherParameters) -> dict[str, float]:
    return {name: float(getattr(parameters, name)) for name in WEATHER_FIELDS}


# -- CARLA's numbers ------------------------------------------------------------------------


@pytest.mark.parametrize("preset", WEATHER_PRESETS)
def test_the_preset_table_is_carlas_own(preset: str) -> None:
    theirs = _carla(getattr(carla.WeatherParameters, preset))
    assert PRESET_PARAMETERS[preset] == pytest.approx(theirs, abs=FLOAT32)


def test_the_constructor_defaults_are_carlas() -> None:
    defaults = dict(CONSTRUCTOR_DEFAULTS)
    assert defaults == pytest.approx(_carla(carla.WeatherParameters()), abs=FLOAT32)


def test_the_full_dict_builds_in_carla_exactly_the_preset_with_its_overrides() -> None:
    weather = weather_for("WetNoon", Visibility.FOG, Light.DUSK)
    value = weather.as_scenic_param()
    assert isinstance(value, dict) and list(value) == list(WEATHER_FIELDS)
    built = carla.WeatherParameters(**value)  # what Scenic's CARLA simulator does with it
    expected = getattr(carla.WeatherParameters, weather.preset)
    for name, number in weather.overrides.items():
        setattr(expected, name, number)
    assert _carla(built) == pytest.approx(_carla(expected), abs=FLOAT32)


def test_a_partial_dict_reads_as_carla_runs_it() -> None:
    partial = {"cloudiness": 10.0, "sun_altitude_angle": -5.0}
    weather = Weather.from_parameters(partial)
    assert weather.parameters() == pytest.approx(
        _carla(carla.WeatherParameters(**partial)), abs=FLOAT32
    )
    assert weather.parameters()["scattering_intensity"] == 0.0  # not the preset's 1.0


# -- the value ------------------------------------------------------------------------------


def test_a_preset_alone_is_its_name_in_the_script() -> None:
    weather = Weather.preset_only("CloudySunset")
    assert weather.overrides == {}
    assert weather.as_scenic_param() == "CloudySunset"
    assert weather.scenic_source() == "'CloudySunset'"
    assert weather.param_text() == "CloudySunset"
    assert weather.closest_preset() == "CloudySunset" and weather.describe() == "CloudySunset"


def test_overrides_make_the_full_dict_and_keep_the_rest_of_the_preset() -> None:
    weather = Weather(preset="CloudyNoon", fog_density=80.0, fog_distance=5.0)
    value = weather.as_scenic_param()
    assert isinstance(value, dict)
    assert value["fog_density"] == 80.0 and value["fog_distance"] == 5.0
    assert value["cloudiness"] == 60.0 and value["scattering_intensity"] == 1.0
    assert weather.scenic_source().startswith("{'cloudiness': 60.0,")


@pytest.mark.parametrize("name", WEATHER_FIELDS)
def test_every_override_is_bounded(name: str) -> None:
    low, high = BOUNDS[name]
    assert Weather(**{name: float(low)}).overrides == {name: low}
    assert Weather(**{name: float(high)}).overrides == {name: high}
    for outside in (low - 1, high + 1, math.nan, math.inf):
        with pytest.raises(ValidationError):
            Weather(**{name: outside})
        with pytest.raises(WeatherValueError):
            Weather.from_parameters({**PRESET_PARAMETERS["ClearNoon"], name: outside})


@pytest.mark.parametrize(
    "bad",
    [
        {"preset": "SunnyDisco"},
        {"fog_density": True},  # strict: a bool is no number
        {"fog_density": "50"},
        {"fogginess": 3.0},
    ],
)
def test_a_bad_value_is_refused(bad: dict[str, object]) -> None:
    with pytest.raises(ValidationError):
        Weather(**bad)  # type: ignore[arg-type]


def test_a_weather_is_frozen() -> None:
    weather = Weather.preset_only("ClearNoon")
    with pytest.raises(ValidationError):
        weather.fog_density = 50.0  # type: ignore[misc]


def test_an_unknown_preset_is_one_arise_error() -> None:
    with pytest.raises(WeatherValueError, match="SunnyNoon"):
        Weather.preset_only("SunnyNoon")


# -- the trace's text, which is untrusted ---------------------------------------------------

CONDITIONS = list(itertools.product(Visibility, [None, *Light]))


@pytest.mark.parametrize(("visibility", "light"), CONDITIONS)
def test_every_condition_survives_the_trace_text(
    visibility: Visibility, light: Light | None
) -> None:
    weather = weather_for("ClearNoon", visibility, light)
    text = weather.param_text()
    assert len(text) < MAX_PARAM_TEXT
    back = Weather.from_param_text(text)
    assert back.same_as(weather)
    assert back.closest_preset() == weather.closest_preset()


@pytest.mark.parametrize("preset", WEATHER_PRESETS)
def test_a_presets_full_dict_reads_back_as_the_preset(preset: str) -> None:
    back = Weather.from_param_text(json.dumps(dict(PRESET_PARAMETERS[preset])))
    assert back.preset == preset and back.overrides == {}


@pytest.mark.parametrize(
    "text",
    [
        '{"fog_density": NaN}',
        '{"fog_density": Infinity}',
        '{"fog_density": true}',
        '{"fog_density": "a lot"}',
        '{"fog_density": {"nested": 1}}',
        '{"fogginess": 3}',
        '{"fog_density": 500}',
        "[1, 2]",
        "{not json",
        "ClearNoon; rm -rf /",
        "{" + " " * MAX_PARAM_TEXT + "}",
        "[" * 100_000,
    ],
)
def test_unreadable_trace_text_is_one_arise_error(text: str) -> None:
    with pytest.raises(WeatherValueError):
        Weather.from_param_text(text)


# -- the visibility model -------------------------------------------------------------------


@pytest.mark.parametrize(
    ("visibility", "range_m"),
    [
        (Visibility.MIST, 1_500),
        (Visibility.HAZE, 3_000),
        (Visibility.SMOKE, 500),
        (Visibility.FOG, 200),
        (Visibility.DENSE_FOG, 50),
    ],
)
def test_each_condition_leaves_its_visual_range(visibility: Visibility, range_m: float) -> None:
    weather = weather_for("ClearNoon", visibility)
    assert weather.visual_range_m == pytest.approx(range_m, rel=0.02)
    assert weather.parameters()["fog_distance"] == 0.0
    assert "visual range about" in weather.describe()


def test_the_model_runs_both_ways_and_is_monotonic() -> None:
    ranges = [visual_range_m(density) for density in range(0, 101, 5)]
    assert ranges == sorted(ranges, reverse=True)
    assert visual_range_m(100) == pytest.approx(30, rel=0.01)
    for range_m in (40, 150, 900, 5_000, 40_000):
        assert visual_range_m(fog_density_for(range_m)) == pytest.approx(range_m, rel=0.01)
    assert visual_range_m(0, fog_distance=25) == pytest.approx(100_025)


def test_carlas_clear_presets_are_clear_and_fog_is_thicker_than_its_night() -> None:
    assert Weather.preset_only("ClearNoon").visual_range_m > 50_000
    night = Weather.preset_only("ClearNight").visual_range_m
    assert 700 < night < 1_000  # CARLA's night presets hold fog of density 60
    assert weather_for("ClearNight", Visibility.FOG).visual_range_m < night / 3


# -- conditions to parameters ---------------------------------------------------------------


def test_clear_air_and_no_light_is_the_preset_itself() -> None:
    assert weather_for("SoftRainSunset") == Weather.preset_only("SoftRainSunset")


def test_night_is_the_night_variant_and_day_the_noon_one() -> None:
    assert weather_for("WetCloudyNoon", light=Light.NIGHT) == Weather.preset_only("WetCloudyNight")
    assert weather_for("MidRainyNight", light=Light.DAY).preset == "MidRainyNoon"
    assert weather_for("HardRainNoon", light=Light.NIGHT).parameters()["sun_altitude_angle"] == -90


def test_dusk_and_dawn_are_twilight_on_opposite_sides_of_the_sky() -> None:
    dusk = weather_for("ClearNoon", light=Light.DUSK)
    dawn = weather_for("ClearNoon", light=Light.DAWN)
    assert dusk.preset == dawn.preset == "ClearSunset"
    assert -6 <= dusk.parameters()["sun_altitude_angle"] < 0
    assert dusk.parameters()["sun_altitude_angle"] == dawn.parameters()["sun_altitude_angle"]
    gap = abs(dusk.parameters()["sun_azimuth_angle"] - dawn.parameters()["sun_azimuth_angle"])
    assert gap == pytest.approx(180)


def test_glare_is_a_low_sun_in_a_clear_sky() -> None:
    glare = weather_for("CloudyNoon", light=Light.GLARE)
    values = glare.parameters()
    assert glare.preset == "ClearSunset"
    assert 0 < values["sun_altitude_angle"] <= 15 and values["cloudiness"] <= 10
    assert "sun 7 degrees above the horizon" in glare.describe()
    assert weather_for("WetCloudyNoon", light=Light.GLARE).preset == "WetSunset"


def test_fog_hides_the_sky_but_rain_keeps_its_own() -> None:
    assert weather_for("ClearNoon", Visibility.FOG).preset == "CloudyNoon"
    assert weather_for("WetNoon", Visibility.FOG).preset == "WetCloudyNoon"
    assert weather_for("HardRainNight", Visibility.DENSE_FOG).preset == "HardRainNight"


def test_haze_and_smoke_start_from_the_dust_storm() -> None:
    haze = weather_for("ClearNoon", Visibility.HAZE)
    smoke = weather_for("CloudyNoon", Visibility.SMOKE, Light.NIGHT)
    assert haze.preset == smoke.preset == "DustStorm"
    assert haze.parameters()["dust_storm"] == 50
    assert (
        haze.parameters()["mie_scattering_scale"]
        > PRESET_PARAMETERS["ClearNoon"]["mie_scattering_scale"]
    )
    assert smoke.parameters()["sun_altitude_angle"] == -90  # DustStorm has no night preset


def test_the_map_default_becomes_clear_noon_once_changed() -> None:
    assert weather_for("Default") == Weather.preset_only("Default")
    assert weather_for("Default", Visibility.FOG).preset == "CloudyNoon"


def test_an_unknown_base_is_one_arise_error() -> None:
    with pytest.raises(WeatherValueError):
        weather_for("Foggy", Visibility.FOG)


# -- the closest preset ---------------------------------------------------------------------


@pytest.mark.parametrize(
    ("base", "visibility", "light", "closest"),
    [
        # the labelling rules of the dev sets and the held-apart set
        ("ClearNoon", Visibility.FOG, None, "CloudyNoon"),
        ("ClearNoon", Visibility.DENSE_FOG, None, "CloudyNoon"),
        ("ClearNoon", Visibility.MIST, None, "CloudyNoon"),
        ("ClearNight", Visibility.FOG, Light.NIGHT, "CloudyNight"),
        ("ClearNoon", Visibility.HAZE, None, "DustStorm"),
        ("ClearNoon", Visibility.SMOKE, None, "DustStorm"),
        ("ClearNoon", Visibility.HAZE, Light.NIGHT, "DustStorm"),
        ("ClearNoon", Visibility.CLEAR, Light.DUSK, "ClearSunset"),
        ("ClearNoon", Visibility.CLEAR, Light.DAWN, "ClearSunset"),
        ("ClearNoon", Visibility.CLEAR, Light.GLARE, "ClearSunset"),
        ("WetNoon", Visibility.FOG, Light.DUSK, "WetCloudySunset"),
        ("SoftRainNoon", Visibility.MIST, Light.NIGHT, "SoftRainNight"),
    ],
)
def test_the_closest_preset_follows_sky_and_light(
    base: str, visibility: Visibility, light: Light | None, closest: str
) -> None:
    assert weather_for(base, visibility, light).closest_preset() == closest


def test_fog_and_scattering_alone_do_not_move_the_closest_preset() -> None:
    weather = Weather(
        preset="ClearNoon", fog_density=100.0, mie_scattering_scale=5.0, sun_azimuth_angle=90.0
    )
    assert weather.closest_preset() == "ClearNoon"


def test_the_time_of_day_follows_the_suns_height() -> None:
    assert time_of_day(45) is TimeOfDay.NOON and time_of_day(31) is TimeOfDay.NOON
    assert time_of_day(29) is TimeOfDay.SUNSET and time_of_day(-30) is TimeOfDay.SUNSET
    assert time_of_day(-40) is TimeOfDay.NIGHT


def test_describe_is_one_line() -> None:
    for visibility, light in CONDITIONS:
        line = weather_for("MidRainyNoon", visibility, light).describe()
        assert "\n" not in line and line.startswith(("MidRain", "Dust"))
