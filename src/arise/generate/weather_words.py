"""Weather and light from the description's words: a CARLA preset, or ClearNoon unstated.

Only words about the sky, the road surface and the time of day count ("a dark blue sedan" is
no night); what the model says about weather is never asked.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from arise.generate.facts import FactSource, GroundedFact
from arise.vocabulary import DEFAULT_WEATHER, WEATHER_PRESETS

_SKY = (
    (
        "HardRain",
        r"heavy rain\w*|hard rain|downpour|pouring rain|torrential rain|"
        r"thunderstorms?|rainstorms?|storm",
    ),
    ("SoftRain", r"light rain|drizzl\w*|soft rain|light showers?|sprinkl\w+|misty rain"),
    ("MidRain", r"rain\w*|showers"),
    (
        "Wet",
        r"slippery|icy|wet (?:\w+ )?(?:road|roads|street|streets|asphalt|pavement|surface)|puddles?|"
        r"slick (?:road|street|surface)|road (?:is|was) wet|damp (?:road|street)",
    ),
    ("Cloudy", r"cloud\w*|overcast|grey skies?|gray skies?"),
    (
        "Clear",
        r"clear (?:sky|skies|weather|day|conditions)|sunny|sunshine|dry weather|"
        r"weather (?:is|was) clear|clear and dry",
    ),
)
_TIME = (
    (
        "Night",
        r"night\w*|darkness|after dark|in the dark|midnight|dark(?![\s-]+(?:red|blue|"
        r"green|grey|gray|colou?red|sedan|suv|car|van|truck|jacket|cloth\w*|coat))",
    ),
    ("Sunset", r"sunset|dusk|twilight|sundown|setting sun|low sun|dawn|sunrise|daybreak"),
    ("Noon", r"daylight|daytime|midday|noon|broad day"),
)
_RAIN_NAMES = {
    "HardRain": "HardRain",
    "SoftRain": "SoftRain",
    "MidRain": "MidRainy",
}


def first_match(table: Sequence[tuple[str, str]], text: str) -> tuple[str, str] | None:
    for value, pattern in table:
        match = re.search(rf"\b(?:{pattern})\b", text, re.I)
        if match:
            return value, match.group(0)
    return None


def read_weather(description: str) -> GroundedFact:
    """The CARLA preset the description's weather and light words name; ClearNoon if none."""
    sky = first_match(_SKY, description)
    time = first_match(_TIME, description)
    if sky is None and time is None:
        return GroundedFact(name="weather", value=DEFAULT_WEATHER, source=FactSource.DEFAULT)
    sky_name = sky[0] if sky else "Clear"
    time_name = time[0] if time else "Noon"
    if sky_name == "Wet" and re.search(r"\b(?:cloud\w*|overcast)\b", description, re.I):
        sky_name = "WetCloudy"
    candidates = [f"{_RAIN_NAMES.get(sky_name, sky_name)}{time_name}"]
    if sky_name == "MidRain":
        candidates += [f"MidRain{time_name}", f"MidRainy{time_name}"]
    candidates.append(f"HardRain{time_name}" if "Rain" in sky_name else f"Clear{time_name}")
    preset = next((c for c in candidates if c in WEATHER_PRESETS), DEFAULT_WEATHER)
    words = [found[1] for found in (sky, time) if found]
    return GroundedFact(
        name="weather", value=preset, source=FactSource.TEXT, quote=" ... ".join(words)
    )
