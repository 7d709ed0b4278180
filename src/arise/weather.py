"""Weather as a typed value: a CARLA preset, plus the CARLA weather parameters it changes.

CARLA 0.9.16 has 22 named presets but no fog, haze, smoke, dawn, dusk or glare among them;
its `WeatherParameters` carry all of those as numbers. A `Weather` is the preset a scene
starts from and the parameters it overrides. `as_scenic_param()` is what the script's
`param weather = ...` line holds: the preset's name when nothing is overridden, else the
*complete* dict of the 14 parameters. Scenic's CARLA simulator builds
`carla.WeatherParameters(**dict)` from a dict, and that constructor gives every missing
field 0 (not the preset's value), so a partial dict would quietly turn off the preset's
scattering and fog start; the full dict is the preset with the overrides applied.

Where the extraction reads conditions from words (the lead's language rules), it calls
`weather_for(base, visibility, light)`. The numbers it sets, and why:

**Visibility** is one model both ways (`visual_range_m`, `fog_density_for`): the visual
range is the clear stretch before the fog starts plus an exponential in the density,
``fog_distance + 100 km * exp(-fog_density / 12.33)``; the scale makes density 100 a 30 m
range. CARLA's own presets come out at 57-85 km by day (density 2-7), 770-850 m at night
(60: CARLA darkens its nights with fog) and 31 m in HardRainNight (100). `fog_falloff` only shapes the fog's height, so the model,
which looks along the road, ignores it. Each condition targets a range from the usual
definitions and gets the density the model gives for it, with the fog starting at the
camera (`fog_distance` 0):

| condition | range | fog_density | fog_falloff | also | base sky |
|---|---|---|---|---|---|
| mist | 1,500 m (WMO: mist is 1 km or more) | 51.8 | 0.5 | | clear -> cloudy |
| haze | 3,000 m | 43.2 | 0.1 | mie 0.3, dust 50 | clear/cloudy -> DustStorm |
| smoke | 500 m | 65.3 | 0.2 | mie 0.6 | clear/cloudy -> DustStorm |
| fog | 200 m (fog is under 1 km) | 76.6 | 1.0 | | clear -> cloudy |
| dense fog | 50 m (the Met Office's "dense") | 93.7 | 2.0 | | clear -> cloudy |

Fog hides the sun, so a clear base becomes its cloudy variant (a wet one its wet-cloudy
one); rain presets keep their own sky. Haze and smoke are airborne particles: CARLA's only
such weather is DustStorm, whose dust a haze halves; Mie scattering (large particles)
gives their halo. A higher `fog_falloff` keeps the fog low and heavy (CARLA's docs), hence
more for thicker fog. These are our choices, checked against the offline world model and
the export, not against CARLA's renderer.

**Light** picks the preset's time of day and, where CARLA has no preset for it, the sun:

- day: the Noon variant (sun 45 degrees up);
- dusk, dawn: the Sunset variant with the sun 3 degrees *below* the horizon, as in civil
  twilight (0 to -6 degrees), which is what reports call dusk and dawn; CARLA's Sunset sun
  stands 15 degrees up. Dawn puts the sun on the other side of the sky (azimuth + 180);
- glare: the Sunset variant with the sun 7 degrees up and a clear sky (a cloudy base
  becomes clear when the air is clear), since low-sun glare comes from a visible sun
  within about 15 degrees of the horizon;
- night: the Night variant (sun at -90 degrees, as CARLA's night presets have it).

A sun *ahead of the ego* is not set: CARLA's azimuth is in world coordinates, the ego's
heading is known only once Scenic samples the scene, and a `param` dict cannot depend on
it (Scenic samples only tuples and lists inside a param's value). DustStorm and Default
have no time-of-day variants: the sun's altitude is set instead, and Default (CARLA's
"keep the map's weather", -1 everywhere) is read as ClearNoon once anything changes.

`closest_preset()` names the preset a weather looks most like, by sky and light alone: the
time of day from the sun's height (noon above 30 degrees, a sunset down to -37.5, then
night), then the preset of that time (or DustStorm) nearest in cloud, rain, road water and
dust. So fog over CloudyNoon is CloudyNoon, dusk and glare are a Sunset, smoke is
DustStorm. It is how a report names a weather and how fidelity compares a trace with a
hand-written preset.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from dataclasses import dataclass
from enum import StrEnum
from typing import Annotated, Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator

from arise.errors import AriseError
from arise.vocabulary import DEFAULT_WEATHER, WEATHER_FIELDS, WEATHER_PRESETS

__all__ = [
    "CONSTRUCTOR_DEFAULTS",
    "PRESET_PARAMETERS",
    "Light",
    "Sky",
    "TimeOfDay",
    "Visibility",
    "Weather",
    "WeatherValueError",
    "fog_density_for",
    "preset_parts",
    "time_of_day",
    "preset_of",
    "visual_range_m",
    "weather_for",
]


class WeatherValueError(AriseError):
    """A weather value that is out of bounds, names something CARLA lacks, or cannot be read."""


# -- CARLA 0.9.16's numbers -----------------------------------------------------------------

# One row per preset, in WEATHER_FIELDS order: cloudiness, precipitation,
# precipitation_deposits, wind_intensity, sun_azimuth_angle, sun_altitude_angle, fog_density,
# fog_distance, fog_falloff, wetness, scattering_intensity, mie_scattering_scale,
# rayleigh_scattering_scale, dust_storm. tests/test_weather.py compares them with the
# installed client's `carla.WeatherParameters`.
_ROWS: dict[str, tuple[float, ...]] = {
    "ClearNoon": (5, 0, 0, 10, -1, 45, 2, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "CloudyNoon": (60, 0, 0, 10, -1, 45, 3, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "WetNoon": (5, 0, 50, 10, -1, 45, 3, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "WetCloudyNoon": (60, 0, 50, 10, -1, 45, 3, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "SoftRainNoon": (20, 30, 50, 30, -1, 45, 3, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "MidRainyNoon": (60, 60, 60, 60, -1, 45, 3, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "HardRainNoon": (100, 100, 90, 100, -1, 45, 7, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "ClearSunset": (5, 0, 0, 10, -1, 15, 2, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "CloudySunset": (60, 0, 0, 10, -1, 15, 3, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "WetSunset": (5, 0, 50, 10, -1, 15, 2, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "WetCloudySunset": (60, 0, 50, 10, -1, 15, 2, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "SoftRainSunset": (20, 30, 50, 30, -1, 15, 2, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "MidRainSunset": (60, 60, 60, 60, -1, 15, 3, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "HardRainSunset": (100, 100, 90, 100, -1, 15, 7, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "ClearNight": (5, 0, 0, 10, -1, -90, 60, 75, 1, 0, 1, 0.03, 0.0331, 0),
    "CloudyNight": (60, 0, 0, 10, -1, -90, 60, 0.75, 0.1, 0, 1, 0.03, 0.0331, 0),
    "WetNight": (5, 0, 50, 10, -1, -90, 60, 75, 1, 60, 1, 0.03, 0.0331, 0),
    "WetCloudyNight": (60, 0, 50, 10, -1, -90, 60, 0.75, 0.1, 60, 1, 0.03, 0.0331, 0),
    "SoftRainNight": (60, 30, 50, 30, -1, -90, 60, 0.75, 0.1, 60, 1, 0.03, 0.0331, 0),
    "MidRainyNight": (80, 60, 60, 60, -1, -90, 60, 0.75, 0.1, 80, 1, 0.03, 0.0331, 0),
    "HardRainNight": (100, 100, 90, 100, -1, -90, 100, 0.75, 0.1, 100, 1, 0.03, 0.0331, 0),
    "DustStorm": (100, 0, 0, 100, -1, 45, 2, 0.75, 0.1, 0, 1, 0.03, 0.0331, 100),
    "Default": (-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 1, 0.03, 0.0331, 0),
}

#: Every preset's 14 parameters, by name.
PRESET_PARAMETERS: Mapping[str, Mapping[str, float]] = {
    name: dict(zip(WEATHER_FIELDS, map(float, row), strict=True)) for name, row in _ROWS.items()
}
#: What `carla.WeatherParameters(**d)` gives a field that `d` leaves out.
CONSTRUCTOR_DEFAULTS: Mapping[str, float] = {
    name: (0.0331 if name == "rayleigh_scattering_scale" else 0.0) for name in WEATHER_FIELDS
}

# -- the visibility model -------------------------------------------------------------------

CLEAR_RANGE_M = 100_000.0
#: Fog density 100 leaves this visual range (m).
DENSEST_RANGE_M = 30.0
FOG_SCALE = 100 / math.log(CLEAR_RANGE_M / DENSEST_RANGE_M)


def visual_range_m(fog_density: float, fog_distance: float = 0.0) -> float:
    """How far one sees through this fog (the module's docstring gives the model)."""
    density = min(100.0, max(0.0, fog_density))
    return max(0.0, fog_distance) + CLEAR_RANGE_M * math.exp(-density / FOG_SCALE)


def fog_density_for(range_m: float) -> float:
    """The fog density (0-100, one decimal) that leaves a visual range of `range_m`."""
    clamped = min(CLEAR_RANGE_M, max(DENSEST_RANGE_M, range_m))
    return round(FOG_SCALE * math.log(CLEAR_RANGE_M / clamped), 1)


# -- names for conditions --------------------------------------------------------------------


# The conditions the language rules name (`weather_for` turns them into parameters).
class Visibility(StrEnum):
    CLEAR = "clear"
    MIST = "mist"
    HAZE = "haze"
    FOG = "fog"
    DENSE_FOG = "dense_fog"
    SMOKE = "smoke"


class Light(StrEnum):
    DAY = "day"
    DAWN = "dawn"
    DUSK = "dusk"
    NIGHT = "night"
    GLARE = "glare"


class Sky(StrEnum):
    """The first half of a preset's name."""

    CLEAR = "Clear"
    CLOUDY = "Cloudy"
    WET = "Wet"
    WET_CLOUDY = "WetCloudy"
    SOFT_RAIN = "SoftRain"
    MID_RAIN = "MidRain"
    HARD_RAIN = "HardRain"
    DUST = "Dust"


class TimeOfDay(StrEnum):
    """The second half of a preset's name."""

    NOON = "Noon"
    SUNSET = "Sunset"
    NIGHT = "Night"


#: The sun's height each time of day has in CARLA's presets (degrees).
SUN_ALTITUDE: Mapping[TimeOfDay, float] = {
    TimeOfDay.NOON: 45.0,
    TimeOfDay.SUNSET: 15.0,
    TimeOfDay.NIGHT: -90.0,
}


def preset_parts(preset: str) -> tuple[Sky, TimeOfDay] | None:
    """(sky, time of day) of a preset; None for Default, which has neither."""
    if preset == "DustStorm":
        return Sky.DUST, TimeOfDay.NOON
    for time in TimeOfDay:
        if preset.endswith(time.value):
            head = preset.removesuffix(time.value).replace("Rainy", "Rain")
            if head in {sky.value for sky in Sky}:
                return Sky(head), time
    return None


def preset_of(sky: Sky, time: TimeOfDay) -> str | None:
    """The preset with that sky and time of day (CARLA spells MidRain two ways), if any."""
    for name in WEATHER_PRESETS:
        if preset_parts(name) == (sky, time):
            return name
    return None


# -- the value ------------------------------------------------------------------------------


#: Bounds of each override (CARLA's documented ranges; ours where CARLA says "to infinity").
BOUNDS: Mapping[str, tuple[float, float]] = {
    "cloudiness": (0, 100),
    "precipitation": (0, 100),
    "precipitation_deposits": (0, 100),
    "wind_intensity": (0, 100),
    "sun_azimuth_angle": (-360, 360),
    "sun_altitude_angle": (-90, 90),
    "fog_density": (0, 100),
    "fog_distance": (0, 10_000),
    "fog_falloff": (0, 10),
    "wetness": (0, 100),
    "scattering_intensity": (0, 10),
    "mie_scattering_scale": (0, 5),
    "rayleigh_scattering_scale": (0, 2),
    "dust_storm": (0, 100),
}
Percent = Annotated[float | None, Field(ge=0, le=100, allow_inf_nan=False)]
Azimuth = Annotated[float | None, Field(ge=-360, le=360, allow_inf_nan=False)]
Altitude = Annotated[float | None, Field(ge=-90, le=90, allow_inf_nan=False)]
Metres = Annotated[float | None, Field(ge=0, le=10_000, allow_inf_nan=False)]
Factor = Annotated[float | None, Field(ge=0, le=10, allow_inf_nan=False)]
Scale = Annotated[float | None, Field(ge=0, le=5, allow_inf_nan=False)]
Rayleigh = Annotated[float | None, Field(ge=0, le=2, allow_inf_nan=False)]
#: The longest weather text a trace may hold (14 fields as JSON take about 500 characters).
MAX_PARAM_TEXT = 2048
#: Two parameter values this close are the same (CARLA stores float32).
TOLERANCE = 1e-3


class Weather(BaseModel):
    """A CARLA preset and the weather parameters that differ from it (None: the preset's)."""

    model_config = ConfigDict(frozen=True, strict=True, extra="forbid")

    preset: str = DEFAULT_WEATHER
    cloudiness: Percent = None
    precipitation: Percent = None
    precipitation_deposits: Percent = None
    wind_intensity: Percent = None
    sun_azimuth_angle: Azimuth = None
    sun_altitude_angle: Altitude = None
    fog_density: Percent = None
    fog_distance: Metres = None
    fog_falloff: Factor = None
    wetness: Percent = None
    scattering_intensity: Factor = None
    mie_scattering_scale: Scale = None
    rayleigh_scattering_scale: Rayleigh = None
    dust_storm: Percent = None

    @field_validator("preset")
    @classmethod
    def _known_preset(cls, value: str) -> str:
        if value not in WEATHER_PRESETS:
            raise ValueError(f"{value!r} is no CARLA weather preset")
        return value

    # -- making one ---------------------------------------------------------------------

    @classmethod
    def preset_only(cls, name: str) -> Weather:
        """The preset as CARLA defines it (WeatherValueError for an unknown name)."""
        return _built(preset=name)

    @classmethod
    def from_parameters(cls, values: Mapping[str, object]) -> Weather:
        """The weather a `param weather = {...}` dict sets in CARLA: fields it leaves out
        get the constructor's defaults, as in CARLA; the base is the preset it differs
        from in the fewest fields (then by sky and light)."""
        unknown = sorted(str(key) for key in values if key not in WEATHER_FIELDS)
        if unknown:
            raise WeatherValueError(f"unknown CARLA weather parameter(s): {', '.join(unknown)}")
        full: dict[str, float] = dict(CONSTRUCTOR_DEFAULTS)
        for key, value in values.items():
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise WeatherValueError(f"weather parameter {key!r} must be a number")
            if not math.isfinite(value):
                raise WeatherValueError(f"weather parameter {key!r} must be finite")
            full[str(key)] = float(value)
        base = min(
            WEATHER_PRESETS,
            key=lambda name: (len(_differing(full, name)), _sky_distance(full, name, sun=True)),
        )
        return _built(preset=base, **{name: full[name] for name in _differing(full, base)})

    @classmethod
    def from_scenic_param(cls, value: object) -> Weather:
        """The weather of a script's `param weather` value (a preset name or a dict)."""
        if isinstance(value, str):
            return cls.preset_only(value)
        if isinstance(value, Mapping):
            return cls.from_parameters(value)
        raise WeatherValueError(
            f"weather must be a preset name or a dict, not {type(value).__name__}"
        )

    @classmethod
    def from_param_text(cls, text: str) -> Weather:
        """The weather a trace recorded as text (`param_text()`; a preset name or a JSON
        object of parameters). The text is untrusted: bounded, parsed as data, validated."""
        if len(text) > MAX_PARAM_TEXT:
            raise WeatherValueError(f"the weather text is longer than {MAX_PARAM_TEXT} characters")
        stripped = text.strip()
        if not stripped.startswith("{"):
            return cls.preset_only(stripped)
        try:
            value = json.loads(stripped, parse_constant=_refuse_constant)
        except (ValueError, RecursionError) as error:
            raise WeatherValueError(f"the weather text is no JSON object: {error}") from None
        if not isinstance(value, dict):
            raise WeatherValueError("the weather text is no JSON object")
        return cls.from_parameters(value)

    # -- reading one --------------------------------------------------------------------

    @property
    def overrides(self) -> dict[str, float]:
        """The parameters set apart from the preset, in CARLA's order."""
        values = {name: getattr(self, name) for name in WEATHER_FIELDS}
        return {name: value for name, value in values.items() if value is not None}

    def parameters(self) -> dict[str, float]:
        """All 14 parameters CARLA runs with: the preset's, then the overrides."""
        base = dict(PRESET_PARAMETERS[self.preset])
        base.update(self.overrides)
        return base

    def as_scenic_param(self) -> str | dict[str, float]:
        """The value of the script's `param weather`: the preset's name, or the full dict
        (Scenic's CARLA simulator passes a dict to `carla.WeatherParameters(**dict)`)."""
        return self.parameters() if self.overrides else self.preset

    def scenic_source(self) -> str:
        """`as_scenic_param()` as Scenic source: `'ClearNoon'` or `{'cloudiness': 60.0, ...}`."""
        return repr(self.as_scenic_param())

    def param_text(self) -> str:
        """How a trace records it: the preset's name, or the parameters as a JSON object."""
        value = self.as_scenic_param()
        return value if isinstance(value, str) else json.dumps(value)

    @property
    def visual_range_m(self) -> float:
        """How far one sees, by the module's visibility model."""
        values = self.parameters()
        return visual_range_m(values["fog_density"], values["fog_distance"])

    def closest_preset(self) -> str:
        """The preset this weather looks most like (the preset itself when nothing is
        overridden): the time of day is read from the sun's height, the sky is the nearest
        preset of that time (or DustStorm) by cloud, rain, road water and dust. Fog,
        scattering and the sun's azimuth do not count."""
        if not self.overrides:
            return self.preset
        values = self.parameters()
        time = time_of_day(values["sun_altitude_angle"])
        candidates = [name for name in WEATHER_PRESETS if preset_parts(name) is not None]
        fitting = [name for name in candidates if preset_parts(name) in _same_time(time)]
        return min(fitting, key=lambda name: _sky_distance(values, name))

    def same_as(self, other: Weather) -> bool:
        """True when both run with the same parameters, however they are split."""
        mine, theirs = self.parameters(), other.parameters()
        return all(abs(mine[name] - theirs[name]) <= TOLERANCE for name in WEATHER_FIELDS)

    def describe(self) -> str:
        """One line for reports: the preset, then what is changed in words."""
        changes = dict(self.overrides)
        words: list[str] = []
        if {"fog_density", "fog_distance", "fog_falloff"} & changes.keys():
            words.append(f"visual range about {_round_range(self.visual_range_m)} m")
            for name in ("fog_density", "fog_distance", "fog_falloff"):
                changes.pop(name, None)
        altitude = changes.pop("sun_altitude_angle", None)
        if altitude is not None:
            where = "above" if altitude >= 0 else "below"
            words.append(f"sun {abs(altitude):g} degrees {where} the horizon")
        azimuth = changes.pop("sun_azimuth_angle", None)
        if azimuth is not None:
            words.append(f"sun azimuth {azimuth:g} degrees")
        words += [f"{name.replace('_', ' ')} {value:g}" for name, value in changes.items()]
        return f"{self.preset}, {', '.join(words)}" if words else self.preset


def _built(**values: Any) -> Weather:
    try:
        return Weather(**values)
    except ValidationError as error:
        problem = error.errors()[0]
        where = ".".join(str(part) for part in problem["loc"]) or "weather"
        raise WeatherValueError(f"weather {where}: {problem['msg']}") from None


def _refuse_constant(name: str) -> float:
    raise ValueError(f"{name} is no number a weather parameter may hold")


def _differing(values: Mapping[str, float], preset: str) -> list[str]:
    base = PRESET_PARAMETERS[preset]
    return [name for name in WEATHER_FIELDS if abs(values[name] - base[name]) > TOLERANCE]


#: What sets one preset's sky apart from another's, and how much a unit of each counts.
_SKY_WEIGHTS: Mapping[str, float] = {
    "cloudiness": 1.0,
    "precipitation": 1.0,
    "precipitation_deposits": 0.5,
    "wetness": 0.5,
    "wind_intensity": 0.1,
    "dust_storm": 1.0,
}


def _sky_distance(values: Mapping[str, float], preset: str, *, sun: bool = False) -> float:
    """How far apart the skies are (and the sun's heights, with `sun`)."""
    base = PRESET_PARAMETERS[preset]
    sky = sum(weight * abs(values[name] - base[name]) for name, weight in _SKY_WEIGHTS.items())
    return sky + (abs(values["sun_altitude_angle"] - base["sun_altitude_angle"]) if sun else 0)


def time_of_day(sun_altitude: float) -> TimeOfDay:
    """The preset time of day whose sun is nearest: above 30 degrees noon, above -37.5 a
    sunset (dusk, dawn, glare), else night."""
    return min(TimeOfDay, key=lambda time: abs(SUN_ALTITUDE[time] - sun_altitude))


def _same_time(time: TimeOfDay) -> set[tuple[Sky, TimeOfDay]]:
    """The (sky, time) pairs a weather of that time may be named by: its own time's, and
    DustStorm's, which CARLA has only at noon."""
    return {(sky, time) for sky in Sky} | {(Sky.DUST, TimeOfDay.NOON)}


def _round_range(metres: float) -> int:
    digits = max(0, len(str(int(metres))) - 2)
    return int(round(metres, -digits))


# -- conditions to parameters ---------------------------------------------------------------


@dataclass(frozen=True)
class _Fog:
    """What one visibility condition sets (see the table in the module's docstring)."""

    range_m: float
    falloff: float
    mie: float | None = None
    dust: float | None = None


_FOGS: Mapping[Visibility, _Fog] = {
    Visibility.MIST: _Fog(1_500, 0.5),
    Visibility.HAZE: _Fog(3_000, 0.1, mie=0.3, dust=50),
    Visibility.SMOKE: _Fog(500, 0.2, mie=0.6),
    Visibility.FOG: _Fog(200, 1.0),
    Visibility.DENSE_FOG: _Fog(50, 2.0),
}
#: The sun at dusk and dawn (civil twilight) and for glare, in degrees.
TWILIGHT_ALTITUDE = -3.0
GLARE_ALTITUDE = 7.0
_FOGGY = (Visibility.MIST, Visibility.FOG, Visibility.DENSE_FOG)
_PARTICLES = (Visibility.HAZE, Visibility.SMOKE)
_TIMES: Mapping[Light, TimeOfDay] = {
    Light.DAY: TimeOfDay.NOON,
    Light.DAWN: TimeOfDay.SUNSET,
    Light.DUSK: TimeOfDay.SUNSET,
    Light.GLARE: TimeOfDay.SUNSET,
    Light.NIGHT: TimeOfDay.NIGHT,
}


def _sky_for(sky: Sky, visibility: Visibility, light: Light | None) -> Sky:
    if visibility in _FOGGY:
        return {Sky.CLEAR: Sky.CLOUDY, Sky.WET: Sky.WET_CLOUDY}.get(sky, sky)
    if visibility in _PARTICLES:
        return Sky.DUST if sky in (Sky.CLEAR, Sky.CLOUDY) else sky
    if light is Light.GLARE:
        return {Sky.CLOUDY: Sky.CLEAR, Sky.WET_CLOUDY: Sky.WET}.get(sky, sky)
    return sky


def weather_for(
    base: str = DEFAULT_WEATHER,
    visibility: Visibility = Visibility.CLEAR,
    light: Light | None = None,
) -> Weather:
    """The weather for a preset read from the words (rain, wet road, clouds, time of day),
    changed for the visibility and light the words state (None: the base's own light).
    The numbers and the reasons for them are in the module's docstring."""
    if base not in WEATHER_PRESETS:
        raise WeatherValueError(f"{base!r} is no CARLA weather preset")
    if visibility is Visibility.CLEAR and light is None:
        return Weather.preset_only(base)
    sky, time = preset_parts(base) or preset_parts(DEFAULT_WEATHER) or (Sky.CLEAR, TimeOfDay.NOON)
    sky = _sky_for(sky, visibility, light)
    if light is not None:
        time = _TIMES[light]
    overrides: dict[str, float] = {}
    preset = preset_of(sky, time)
    if preset is None:  # DustStorm has no Sunset or Night: its sun is moved instead
        preset = preset_of(sky, TimeOfDay.NOON) or DEFAULT_WEATHER
        overrides["sun_altitude_angle"] = SUN_ALTITUDE[time]
    if light in (Light.DUSK, Light.DAWN):
        overrides["sun_altitude_angle"] = TWILIGHT_ALTITUDE
    elif light is Light.GLARE:
        overrides["sun_altitude_angle"] = GLARE_ALTITUDE
    if light is Light.DAWN:
        azimuth = PRESET_PARAMETERS[preset]["sun_azimuth_angle"]
        overrides["sun_azimuth_angle"] = (azimuth + 180.0) % 360.0
    fog = _FOGS.get(visibility)
    if fog is not None:
        overrides["fog_density"] = fog_density_for(fog.range_m)
        overrides["fog_distance"] = 0.0
        overrides["fog_falloff"] = fog.falloff
        if fog.mie is not None:
            overrides["mie_scattering_scale"] = fog.mie
        if fog.dust is not None and preset == "DustStorm":
            overrides["dust_storm"] = fog.dust
    return _built(preset=preset, **overrides)
