"""A run's weather (a CARLA preset or its parameter dict) in OpenSCENARIO units."""

from __future__ import annotations

import math

import pytest

from arise.present.weather import describe_run_weather, weather_values
from arise.vocabulary import WEATHER_PRESETS
from arise.weather import Light, Visibility, weather_for


def test_clear_noon_is_dry_sunny_and_clear() -> None:
    values, notes = weather_values("ClearNoon")
    assert notes == []
    assert values.rain_mm_h == 0 and values.cloud_oktas == 0
    assert values.sun_intensity_lux > 50_000 and values.hour == 12
    assert values.fog_visual_range_m > 50_000 and values.friction_scale == 1.0


def test_hard_rain_night_is_wet_dark_and_overcast() -> None:
    values, _ = weather_values("HardRainNight")
    assert values.rain_mm_h == 10.0 and values.cloud_oktas == 8
    assert values.sun_intensity_lux == 0 and values.hour == 23
    assert values.friction_scale < 1.0


@pytest.mark.parametrize("preset", WEATHER_PRESETS)
def test_every_preset_converts(preset: str) -> None:
    values, notes = weather_values(preset)
    assert notes == [] and values.preset == preset
    assert 0 <= values.cloud_oktas <= 8 and values.fog_visual_range_m > 0


def test_unknown_preset_falls_back_with_a_note() -> None:
    values, notes = weather_values("SunnyDisco")
    assert values.preset == "ClearNoon" and notes


def test_a_fog_dict_exports_its_visual_range_and_its_closest_preset() -> None:
    fog = weather_for("ClearNoon", Visibility.FOG)
    values, notes = weather_values(fog.param_text())
    assert notes == []
    assert values.preset == "CloudyNoon" and values.name == fog.describe()
    assert 150 <= values.fog_visual_range_m <= 250
    assert values.cloud_oktas == round(60 / 12.5) and values.hour == 12


def test_the_sun_comes_from_the_dicts_altitude_and_azimuth() -> None:
    glare, _ = weather_values(weather_for("ClearNoon", light=Light.GLARE).param_text())
    assert glare.sun_elevation == pytest.approx(math.radians(7), abs=1e-4)
    assert 0 < glare.sun_intensity_lux < 20_000 and glare.hour == 19
    dawn, _ = weather_values(weather_for("ClearNoon", light=Light.DAWN).param_text())
    assert dawn.sun_elevation < 0 and dawn.sun_intensity_lux == 0 and dawn.hour == 6
    assert dawn.sun_azimuth == pytest.approx(math.radians(179), abs=1e-4)


@pytest.mark.parametrize("text", ['{"fog_density": NaN}', '{"fog": 1}', "{", "x" * 5000])
def test_an_unreadable_weather_is_the_default_with_a_note(text: str) -> None:
    values, notes = weather_values(text)
    assert values.preset == "ClearNoon" and len(notes) == 1 and "unreadable" in notes[0]
    assert describe_run_weather(text) == "weather unreadable"


def test_the_replay_title_line_names_the_weather() -> None:
    assert describe_run_weather(None) == "weather not recorded"
    assert describe_run_weather("WetNight") == "WetNight"
    fog = weather_for("ClearNight", Visibility.DENSE_FOG).param_text()
    assert describe_run_weather(fog) == "CloudyNight, visual range about 50 m"
