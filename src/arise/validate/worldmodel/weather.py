"""CARLA 0.9.16 weather checks, so a bad weather param fails offline as it would in CARLA.

The value is a preset name or a dict of `carla.WeatherParameters` fields (what Scenic's
CARLA simulator accepts; `arise.weather.Weather.as_scenic_param()` writes either). The
preset and parameter names themselves live in `arise.vocabulary`.
"""

from __future__ import annotations

import difflib
import math
from typing import Any

from arise.errors import AriseError
from arise.vocabulary import WEATHER_FIELDS, WEATHER_PRESETS

__all__ = ["WEATHER_FIELDS", "WEATHER_PRESETS", "WeatherError", "check_weather"]


class WeatherError(AriseError):
    """The weather param names something CARLA does not have.

    Scenic lets it through `simulate()` (it retries rejections only); the diagnostics and
    the repair rules know it by its class name, the knowledge-base lint catches it by type.
    """


def _suggest(word: str, choices: tuple[str, ...]) -> str:
    close = difflib.get_close_matches(word, choices, n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def check_weather(weather: Any) -> None:
    """Raise WeatherError if CARLA would refuse this weather value."""
    if isinstance(weather, str):
        if weather not in WEATHER_PRESETS:
            raise WeatherError(
                f"unknown CARLA weather preset {weather!r}{_suggest(weather, WEATHER_PRESETS)}"
            )
    elif isinstance(weather, dict):
        for key, value in weather.items():
            if key not in WEATHER_FIELDS:
                raise WeatherError(
                    f"unknown CARLA weather parameter {key!r}{_suggest(str(key), WEATHER_FIELDS)}"
                )
            if not isinstance(value, (int, float)):
                raise WeatherError(f"weather parameter {key!r} must be a number, got {value!r}")
            if not math.isfinite(value):
                # CARLA would hand it to the renderer as it is; the trace could not hold it.
                raise WeatherError(f"weather parameter {key!r} must be finite, got {value!r}")
    elif weather is not None:
        raise WeatherError(f"weather must be a preset name or a dict, got {type(weather).__name__}")
