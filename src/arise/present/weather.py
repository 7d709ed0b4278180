"""A run's weather in OpenSCENARIO 1.2 terms, and in one line for the replay.

CARLA describes weather in percentages and sun angles; OpenSCENARIO in oktas, lux, mm/h
and metres of visibility. The conversions below are ours (docs/export.md lists them). The
weather is what the trace recorded: a preset's name, or the full parameter dict a script
set (fog, a low sun; `arise.weather`), so the export carries fog as `Fog visualRange` (the
visibility model of `arise.weather`) and the sun from its altitude and azimuth. The
environment's name is the weather's one-line description, which for a plain preset is its
name, so a CARLA-based player can use it as is.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from arise.vocabulary import DEFAULT_WEATHER
from arise.weather import TimeOfDay, Weather, WeatherValueError, time_of_day

FULL_SUN_LUX = 100_000.0
HEAVY_RAIN_MM_H = 10.0  # CARLA's precipitation 100 %
STRONG_WIND_M_S = 10.0  # CARLA's wind_intensity 100 %


@dataclass(frozen=True)
class WeatherValues:
    """One weather in OpenSCENARIO's units."""

    preset: str  # the closest CARLA preset
    name: str  # one line: the preset and what the run changed (`Weather.describe`)
    cloud_oktas: int  # 0..8
    sun_intensity_lux: float
    sun_azimuth: float  # radians, 0..2pi
    sun_elevation: float  # radians
    fog_visual_range_m: int
    rain_mm_h: float
    wind_m_s: float
    friction_scale: float  # 1 dry, lower when wet
    hour: int  # local time of day it depicts


def run_weather(text: str | None) -> tuple[Weather, list[str]]:
    """The weather a trace recorded (its `params["weather"]` text, untrusted), with a note
    when it is missing or unreadable: then it is the default."""
    if text is None:
        return Weather.preset_only(DEFAULT_WEATHER), [
            f"the trace records no weather; exported as {DEFAULT_WEATHER}"
        ]
    try:
        return Weather.from_param_text(text), []
    except WeatherValueError as error:
        return Weather.preset_only(DEFAULT_WEATHER), [
            f"the trace's weather is unreadable ({error}); exported as {DEFAULT_WEATHER}"
        ]


def describe_run_weather(text: str | None) -> str:
    """One line for a replay's title: the weather as it ran, or that it is not known."""
    if text is None:
        return "weather not recorded"
    try:
        return Weather.from_param_text(text).describe()
    except WeatherValueError:
        return "weather unreadable"


def _hour(time: TimeOfDay, azimuth: float) -> int:
    if time is TimeOfDay.NIGHT:
        return 23
    if time is TimeOfDay.SUNSET:
        # `weather_for` puts a dawn sun on the other side of the sky from CARLA's presets.
        return 6 if 90 <= azimuth % 360 < 270 else 19
    return 12


def values_of(weather: Weather) -> WeatherValues:
    """A weather in OpenSCENARIO's units."""
    fields = weather.parameters()
    cloudiness = max(0.0, fields["cloudiness"])
    altitude = fields["sun_altitude_angle"]
    azimuth = fields["sun_azimuth_angle"]
    wet = max(fields["wetness"], fields["precipitation_deposits"], 0.0)
    intensity = 0.0
    if altitude > 0:
        intensity = FULL_SUN_LUX * math.sin(math.radians(altitude)) * (1 - 0.75 * cloudiness / 100)
    return WeatherValues(
        preset=weather.closest_preset(),
        name=weather.describe(),
        cloud_oktas=min(8, max(0, round(cloudiness / 12.5))),
        sun_intensity_lux=round(intensity, 1),
        sun_azimuth=round(math.radians(azimuth % 360), 4),
        sun_elevation=round(math.radians(altitude), 4),
        fog_visual_range_m=round(weather.visual_range_m),
        rain_mm_h=round(HEAVY_RAIN_MM_H * max(0.0, fields["precipitation"]) / 100, 2),
        wind_m_s=round(STRONG_WIND_M_S * max(0.0, fields["wind_intensity"]) / 100, 2),
        friction_scale=round(1.0 - 0.3 * wet / 100, 3),
        hour=_hour(time_of_day(altitude), azimuth),
    )


def weather_values(text: str | None) -> tuple[WeatherValues, list[str]]:
    """The values of the weather a trace recorded (a preset's name or a parameter dict);
    a missing or unreadable one is the default, with a note."""
    weather, notes = run_weather(text)
    return values_of(weather), notes
