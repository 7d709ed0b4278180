"""CARLA's weather presets in OpenSCENARIO 1.2 terms.

CARLA describes weather in percentages and sun angles; OpenSCENARIO in oktas, lux, mm/h
and metres of visibility. The conversions below are ours (docs/export.md lists them): the
preset's own name travels along as a property, so a CARLA-based player can use it as is.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from arise.vocabulary import DEFAULT_WEATHER, WEATHER_PRESETS

FULL_SUN_LUX = 100_000.0
CLEAR_VISIBILITY_M = 100_000.0
HEAVY_RAIN_MM_H = 10.0  # CARLA's precipitation 100 %
STRONG_WIND_M_S = 10.0  # CARLA's wind_intensity 100 %


@dataclass(frozen=True)
class WeatherValues:
    """One preset in OpenSCENARIO's units."""

    preset: str
    cloud_oktas: int  # 0..8
    sun_intensity_lux: float
    sun_azimuth: float  # radians, 0..2pi
    sun_elevation: float  # radians
    fog_visual_range_m: int
    rain_mm_h: float
    wind_m_s: float
    friction_scale: float  # 1 dry, lower when wet
    hour: int  # local time of day the preset depicts


def _carla_fields(preset: str) -> dict[str, float]:
    try:
        import carla
    except ImportError:  # the client is a dependency; this only guards odd installs
        return {}
    parameters = getattr(carla.WeatherParameters, preset, None)
    if parameters is None:
        return {}
    return {
        name: float(getattr(parameters, name))
        for name in (
            "cloudiness",
            "precipitation",
            "precipitation_deposits",
            "wind_intensity",
            "sun_azimuth_angle",
            "sun_altitude_angle",
            "fog_density",
            "wetness",
        )
    }


def _hour(preset: str) -> int:
    if preset.endswith("Night"):
        return 23
    if preset.endswith("Sunset"):
        return 19
    return 12


def weather_values(preset: str | None) -> tuple[WeatherValues, list[str]]:
    """The values of a preset (an unknown or missing one is the default, with a note)."""
    notes: list[str] = []
    name = preset or DEFAULT_WEATHER
    if name not in WEATHER_PRESETS:
        notes.append(f"weather {preset!r} is no CARLA preset; exported as {DEFAULT_WEATHER}")
        name = DEFAULT_WEATHER
    if preset is None:
        notes.append(f"the trace records no weather preset; exported as {DEFAULT_WEATHER}")
    fields = _carla_fields(name)
    cloudiness = fields.get("cloudiness", 5.0)
    altitude = fields.get("sun_altitude_angle", 45.0)
    azimuth = fields.get("sun_azimuth_angle", 0.0)
    fog = fields.get("fog_density", 0.0)
    wet = max(fields.get("wetness", 0.0), fields.get("precipitation_deposits", 0.0))
    intensity = 0.0
    if altitude > 0:
        intensity = FULL_SUN_LUX * math.sin(math.radians(altitude)) * (1 - 0.75 * cloudiness / 100)
    values = WeatherValues(
        preset=name,
        cloud_oktas=min(8, max(0, round(cloudiness / 12.5))),
        sun_intensity_lux=round(intensity, 1),
        sun_azimuth=round(math.radians(azimuth % 360), 4),
        sun_elevation=round(math.radians(altitude), 4),
        fog_visual_range_m=int(CLEAR_VISIBILITY_M * math.exp(-fog / 15)),
        rain_mm_h=round(HEAVY_RAIN_MM_H * fields.get("precipitation", 0.0) / 100, 2),
        wind_m_s=round(STRONG_WIND_M_S * fields.get("wind_intensity", 0.0) / 100, 2),
        friction_scale=round(1.0 - 0.3 * wet / 100, 3),
        hour=_hour(name),
    )
    return values, notes
