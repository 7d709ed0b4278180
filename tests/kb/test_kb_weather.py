"""kb.weather: a Weather written as the WEATHER section and read back; the knowledge base's
weather entries hold complete dicts; the lint catches partial or out-of-bounds ones."""

from __future__ import annotations

import pytest
from tests.kb.test_kb_compose import CORE

from arise.kb.compose import compose
from arise.kb.lints import lint_entry
from arise.kb.loader import load_kb
from arise.kb.schema import Component, Entry
from arise.kb.weather import (
    SPEC_ENTRY_ID,
    entry_weather,
    weather_choice,
    weather_entry,
    weather_problems,
    weather_snippet,
)
from arise.validate.worldmodel.weather import check_weather
from arise.vocabulary import WEATHER_FIELDS
from arise.weather import Light, Visibility, Weather, weather_for


def _weather_entry(snippet: str) -> Entry:
    return Entry(
        id="weather.probe", component=Component.WEATHER, descriptions=["probe"], snippet=snippet
    )


def test_a_preset_is_written_by_its_name() -> None:
    assert weather_snippet(Weather.preset_only("WetNight")) == "param weather = 'WetNight'\n"


def test_a_changed_weather_is_written_as_the_full_dict_and_reads_back() -> None:
    weather = weather_for("ClearNoon", Visibility.FOG, Light.DUSK)
    entry = weather_entry(weather)
    assert entry.id == SPEC_ENTRY_ID and entry.component is Component.WEATHER
    assert entry.descriptions == [weather.describe()]
    assert all(f"'{name}'" in entry.snippet for name in WEATHER_FIELDS)
    back = entry_weather(entry)
    assert back is not None and back.same_as(weather)
    assert lint_entry(entry) == []


def test_the_spec_entry_takes_the_weather_section_of_a_script() -> None:
    kb = load_kb()
    core = [kb.get(i) for i in CORE]
    entry = weather_entry(weather_for("ClearNoon", Visibility.DENSE_FOG))
    script = compose([*core, entry], "Pedestrian", "arise_straight")
    section = script.split("# BEGIN WEATHER\n")[1].split("# END WEATHER")[0]
    assert f"# kb: {SPEC_ENTRY_ID}" in section and "'fog_density': 93.7" in section


def test_every_weather_entry_of_the_knowledge_base_is_a_weather() -> None:
    entries = load_kb(strict=True).of(Component.WEATHER)
    names = {entry.id: entry_weather(entry) for entry in entries}
    assert all(weather is not None for weather in names.values()), names
    fog = names["weather.fog"]
    assert fog is not None and fog.closest_preset() == "CloudyNoon" and fog.visual_range_m < 250
    glare = names["weather.low_sun_glare"]
    assert glare is not None and glare.closest_preset() == "ClearSunset"


def test_a_partial_dict_is_caught() -> None:
    entry = _weather_entry("param weather = {'fog_density': 50.0}\n")
    check_weather({"fog_density": 50.0})  # CARLA takes it ...
    messages = [problem.message for problem in lint_entry(entry)]
    assert any("missing:" in message for message in messages), messages  # ... but means 0s


@pytest.mark.parametrize(
    ("snippet", "words"),
    [
        ("param weather = 'SunnyNoon'\n", "SunnyNoon"),
        ("param weather = ClearNoon\n", "preset name or a dict"),
        ("x = 1\n", "one line"),
    ],
)
def test_a_bad_weather_line_is_named(snippet: str, words: str) -> None:
    assert any(words in problem for problem in weather_problems(snippet))


def test_an_out_of_bounds_parameter_is_caught() -> None:
    values = weather_for("ClearNoon", Visibility.FOG).parameters()
    values["fog_density"] = 400.0
    problems = weather_problems(f"param weather = {values!r}\n")
    assert any("fog_density" in problem for problem in problems), problems
    assert entry_weather(_weather_entry(f"param weather = {values!r}\n")) is None


def test_the_choice_is_the_entry_that_sets_exactly_the_weather_else_the_spec_entry() -> None:
    entries = load_kb().of(Component.WEATHER)
    assert weather_choice(Weather.preset_only("WetNight"), entries).id == "weather.wet_night"
    fog = weather_for("ClearNoon", Visibility.FOG)
    assert weather_choice(fog, entries).id == "weather.fog"
    odd = weather_for("SoftRainNoon", Visibility.SMOKE, Light.DAWN)
    chosen = weather_choice(odd, entries)
    assert chosen.id == SPEC_ENTRY_ID and chosen.snippet == weather_snippet(odd)
