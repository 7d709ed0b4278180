"""Weather, light and visibility from the description's words (rules in
language/data/rules/weather.yaml): a CARLA preset, and the weather parameters fog, haze,
smoke, dusk, dawn and glare change; ClearNoon when nothing is said.

What the model says about weather is never asked.
"""

from __future__ import annotations

from dataclasses import dataclass

from arise.language.facts import FactSource, GroundedFact
from arise.language.rules import Fact, Hit, rulebook
from arise.vocabulary import DEFAULT_WEATHER, WEATHER_PRESETS
from arise.weather import Light, Visibility, Weather, weather_for

_TIME_OF_LIGHT = {
    Light.NIGHT: "Night",
    Light.DUSK: "Sunset",
    Light.DAWN: "Sunset",
    Light.GLARE: "Sunset",
    Light.DAY: "Noon",
}
_RAIN_NAMES = {"HardRain": "HardRain", "SoftRain": "SoftRain", "MidRain": "MidRainy"}
#: Lights a preset alone cannot show (its sun is moved): they make a parameter dict.
_LIGHTS_WITH_SUN = frozenset({Light.DUSK, Light.DAWN, Light.GLARE})


@dataclass(frozen=True)
class WeatherReading:
    """The preset (the grounded fact) and, when the words need more than a preset, the
    full weather; plus the visibility and light the words gave."""

    fact: GroundedFact
    weather: Weather
    visibility: Visibility
    light: Light | None

    @property
    def parameters(self) -> Weather | None:
        """The weather when it differs from its preset, else None."""
        return self.weather if self.weather.overrides else None


def _base_preset(sky: str | None, time: str, cloudy: bool) -> str:
    sky_name = sky or "Clear"
    if sky_name == "Wet" and cloudy:
        sky_name = "WetCloudy"
    candidates = [f"{_RAIN_NAMES.get(sky_name, sky_name)}{time}"]
    if sky_name == "MidRain":
        candidates += [f"MidRain{time}", f"MidRainy{time}"]
    candidates.append(f"HardRain{time}" if "Rain" in sky_name else f"Clear{time}")
    return next((c for c in candidates if c in WEATHER_PRESETS), DEFAULT_WEATHER)


def read_weather(description: str) -> WeatherReading:
    """The weather the description's words name; ClearNoon if none."""
    book = rulebook()
    sky = book.by_order(Fact.SKY, description)
    light_hit = book.by_order(Fact.LIGHT, description)
    seen = book.by_order(Fact.VISIBILITY, description)
    light = Light(light_hit.value) if light_hit else None
    visibility = Visibility(seen.value) if seen else Visibility.CLEAR
    if sky is None and light_hit is None and seen is None:
        fact = GroundedFact(name="weather", value=DEFAULT_WEATHER, source=FactSource.DEFAULT)
        return WeatherReading(fact, Weather.preset_only(DEFAULT_WEATHER), visibility, None)
    cloudy = book.first(Fact.SKY, description) is not None and any(
        hit.value == "Cloudy" for hit in book.hits(Fact.SKY, description)
    )
    time = _TIME_OF_LIGHT[light] if light else "Noon"
    base = _base_preset(sky.value if sky else None, time, cloudy)
    changes = visibility is not Visibility.CLEAR or light in _LIGHTS_WITH_SUN
    weather = (
        weather_for(base, visibility, light if light in _LIGHTS_WITH_SUN else None)
        if changes
        else Weather.preset_only(base)
    )
    words = [hit.quote for hit in (sky, light_hit, seen) if isinstance(hit, Hit)]
    fact = GroundedFact(
        name="weather",
        value=weather.closest_preset(),
        source=FactSource.TEXT,
        quote=" ... ".join(words),
    )
    return WeatherReading(fact, weather, visibility, light)
