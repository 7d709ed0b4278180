"""Fidelity's weather verdict on traces whose weather is a dict of CARLA parameters (fog, a
low sun), as the worker records it, against hand-written preset labels."""

from __future__ import annotations

import json

import pytest

from arise.evaluate.fidelity import score_fidelity
from arise.weather import PRESET_PARAMETERS, Light, Visibility, Weather, weather_for
from tests.evaluate.test_fidelity import EGO_STRAIGHT, ran, truth


def _verdict(label: str | None, weather: Weather | str):
    text = weather if isinstance(weather, str) else weather.param_text()
    labels = {"weather": label} if label else {}
    return score_fidelity(truth(**labels), ran(EGO_STRAIGHT, weather=text)).verdict("weather")


@pytest.mark.parametrize(
    ("label", "visibility", "light"),
    [
        ("CloudyNoon", Visibility.FOG, None),
        ("CloudyNoon", Visibility.DENSE_FOG, None),
        ("CloudyNoon", Visibility.MIST, None),
        ("CloudyNight", Visibility.FOG, Light.NIGHT),
        ("DustStorm", Visibility.SMOKE, None),
        ("DustStorm", Visibility.HAZE, None),
        ("ClearSunset", Visibility.CLEAR, Light.DUSK),
        ("ClearSunset", Visibility.CLEAR, Light.DAWN),
        ("ClearSunset", Visibility.CLEAR, Light.GLARE),
    ],
)
def test_a_parameter_run_matches_the_preset_its_label_names(
    label: str, visibility: Visibility, light: Light | None
) -> None:
    weather = weather_for("ClearNoon", visibility, light)
    assert weather.overrides  # a dict in the script and in the trace, not a preset's name
    verdict = _verdict(label, weather)
    assert verdict.match is True and verdict.observed == weather.describe()


def test_the_verdict_shows_the_weather_in_words() -> None:
    verdict = _verdict("CloudyNoon", weather_for("ClearNoon", Visibility.FOG))
    assert verdict.observed == "CloudyNoon, visual range about 200 m"
    assert verdict.expected == "CloudyNoon"


@pytest.mark.parametrize(
    ("label", "visibility", "light"),
    [
        ("ClearNoon", Visibility.FOG, None),  # fog is a grey sky, not a clear one
        ("CloudyNoon", Visibility.FOG, Light.NIGHT),  # night asked for noon
        ("ClearNoon", Visibility.CLEAR, Light.GLARE),  # a low sun is a sunset
        ("CloudyNoon", Visibility.SMOKE, None),
        ("MidRainyNoon", Visibility.FOG, None),
    ],
)
def test_a_parameter_run_of_another_sky_or_time_does_not_match(
    label: str, visibility: Visibility, light: Light | None
) -> None:
    assert _verdict(label, weather_for("ClearNoon", visibility, light)).match is False


def test_rain_stays_rain_under_fog() -> None:
    assert _verdict("MidRainyNoon", weather_for("HardRainNoon", Visibility.FOG)).match is True


def test_fog_nobody_asked_for_is_a_mismatch() -> None:
    verdict = _verdict(None, weather_for("ClearNoon", Visibility.FOG))
    assert verdict.match is False and verdict.expected == "ClearNoon (not stated)"
    # even fog over the neutral preset itself: it is weather nobody asked for
    assert _verdict(None, Weather(preset="ClearNoon", fog_density=80.0)).match is False


def test_the_neutral_preset_written_as_a_dict_is_the_neutral_preset() -> None:
    assert _verdict(None, json.dumps(dict(PRESET_PARAMETERS["ClearNoon"]))).match is True
    same = Weather(preset="ClearNoon", cloudiness=5.0)  # an override equal to the preset's
    assert _verdict(None, same).match is True


@pytest.mark.parametrize(
    "text", ['{"fog_density": NaN}', '{"fogginess": 3}', "{broken", '{"fog_density": 900}']
)
def test_an_unreadable_weather_dict_is_not_scored(text: str) -> None:
    verdict = _verdict("CloudyNoon", text)
    assert verdict.match is None and verdict.observed == text
