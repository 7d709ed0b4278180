"""The WEATHER section of a script, from a typed `Weather` and back.

A weather section is one line, `param weather = <preset or dict>`. Written here from a
`Weather` it holds the preset's name, or the full dict of CARLA's 14 parameters (a partial
dict would leave the rest at CARLA's constructor defaults, not at the preset's values).
`entry_weather` reads the line of a knowledge-base entry back into a `Weather`, so that
retrieval can compare weathers as values and the lint can check the bounds.
"""

from __future__ import annotations

import ast
import re
from collections.abc import Iterable

from arise.kb.schema import Component, Entry
from arise.vocabulary import WEATHER_FIELDS
from arise.weather import Weather, WeatherValueError

__all__ = [
    "SPEC_ENTRY_ID",
    "entry_weather",
    "weather_choice",
    "weather_entry",
    "weather_problems",
    "weather_snippet",
]

#: The id of the entry `weather_entry` makes (it is in no data file).
SPEC_ENTRY_ID = "weather.from_spec"
_LINE = re.compile(r"^\s*param\s+weather\s*=\s*(.+?)\s*$", re.S)


def weather_snippet(weather: Weather) -> str:
    """The section's text: `param weather = 'ClearNoon'` or `param weather = {...}`."""
    return f"param weather = {weather.scenic_source()}\n"


def weather_entry(weather: Weather) -> Entry:
    """An entry that writes exactly this weather, for a spec whose weather no data entry
    holds (fog at dusk, ...): the assembler places it like any chosen weather entry."""
    return Entry(
        id=SPEC_ENTRY_ID,
        component=Component.WEATHER,
        descriptions=[weather.describe()],
        snippet=weather_snippet(weather),
        tags=["spec"],
    )


def weather_choice(weather: Weather, entries: Iterable[Entry]) -> Entry:
    """The entry to place for this weather: a knowledge-base entry that sets exactly it
    (its `# kb:` mark then names a proven entry), else `weather_entry(weather)`."""
    for entry in entries:
        found = entry_weather(entry)
        if found is not None and found.same_as(weather):
            return entry
    return weather_entry(weather)


def _value(snippet: str) -> object:
    match = _LINE.match(snippet.strip())
    if not match:
        raise WeatherValueError("a weather snippet is one line: `param weather = <preset or dict>`")
    try:
        return ast.literal_eval(match.group(1))
    except (ValueError, SyntaxError, MemoryError, RecursionError):
        raise WeatherValueError(
            "the weather value must be a preset name or a dict of numbers"
        ) from None


def entry_weather(entry: Entry) -> Weather | None:
    """The weather a weather entry sets; None when its line cannot be read as one."""
    if entry.component is not Component.WEATHER:
        return None
    try:
        return Weather.from_scenic_param(_value(entry.snippet))
    except WeatherValueError:
        return None


def weather_problems(snippet: str) -> list[str]:
    """What is wrong with a weather snippet beyond what CARLA refuses: a dict must name all
    14 parameters, each within `Weather`'s bounds."""
    try:
        value = _value(snippet)
    except WeatherValueError as error:
        return [str(error)]
    problems: list[str] = []
    if isinstance(value, dict):
        missing = [name for name in WEATHER_FIELDS if name not in value]
        if missing:
            problems.append(
                f"a weather dict names all {len(WEATHER_FIELDS)} CARLA parameters (CARLA gives "
                f"a missing one 0, not the preset's value); missing: {', '.join(missing)}"
            )
    try:
        Weather.from_scenic_param(value)
    except WeatherValueError as error:
        problems.append(str(error))
    return problems
