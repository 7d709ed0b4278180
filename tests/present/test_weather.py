"""CARLA presets in OpenSCENARIO units."""

from __future__ import annotations

import pytest

from arise.present.weather import weather_values
from arise.vocabulary import WEATHER_PRESETS


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
