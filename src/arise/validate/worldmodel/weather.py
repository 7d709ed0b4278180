"""CARLA 0.9.16 weather vocabulary, so a bad weather param fails offline as it would in CARLA."""

from __future__ import annotations

import difflib
from typing import Any

WEATHER_PRESETS: tuple[str, ...] = (
    "ClearNoon", "CloudyNoon", "WetNoon", "WetCloudyNoon", "SoftRainNoon", "MidRainyNoon",
    "HardRainNoon", "ClearSunset", "CloudySunset", "WetSunset", "WetCloudySunset",
    "SoftRainSunset", "MidRainSunset", "HardRainSunset", "ClearNight", "CloudyNight",
    "WetNight", "WetCloudyNight", "SoftRainNight", "MidRainyNight", "HardRainNight",
    "DustStorm", "Default",
)

WEATHER_FIELDS: tuple[str, ...] = (
    "cloudiness", "precipitation", "precipitation_deposits", "wind_intensity",
    "sun_azimuth_angle", "sun_altitude_angle", "fog_density", "fog_distance", "fog_falloff",
    "wetness", "scattering_intensity", "mie_scattering_scale", "rayleigh_scattering_scale",
    "dust_storm",
)


class WeatherError(ValueError):
    """The weather param names something CARLA does not have."""


def _suggest(word: str, choices: tuple[str, ...]) -> str:
    close = difflib.get_close_matches(word, choices, n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def check_weather(weather: Any) -> None:
    """Raise WeatherError if CARLA would refuse this weather value."""
    if isinstance(weather, str):
        if weather not in WEATHER_PRESETS:
            raise WeatherError(f"unknown CARLA weather preset {weather!r}"
                               f"{_suggest(weather, WEATHER_PRESETS)}")
    elif isinstance(weather, dict):
        for key, value in weather.items():
            if key not in WEATHER_FIELDS:
                raise WeatherError(f"unknown CARLA weather parameter {key!r}"
                                   f"{_suggest(str(key), WEATHER_FIELDS)}")
            if not isinstance(value, (int, float)):
                raise WeatherError(f"weather parameter {key!r} must be a number, got {value!r}")
    elif weather is not None:
        raise WeatherError(f"weather must be a preset name or a dict, got {type(weather).__name__}")
