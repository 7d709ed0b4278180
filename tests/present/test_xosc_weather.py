"""scenario.xosc of hand-made traces whose weather is a parameter dict: fog as
`Fog visualRange`, the sun from its altitude and azimuth, valid for the schema and ASAM's
checker."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from arise.present.verify import asam_check, xsd_errors
from arise.present.xosc import write_export
from arise.weather import Light, Visibility, Weather, weather_for
from tests.present.traces import source


def _environment(xosc: Path) -> ET.Element:
    environment = ET.parse(xosc).getroot().find(".//EnvironmentAction/Environment")
    assert environment is not None
    return environment


@pytest.mark.parametrize(
    ("weather", "range_m"),
    [
        (weather_for("ClearNoon", Visibility.FOG), 200),
        (weather_for("ClearNight", Visibility.DENSE_FOG, Light.NIGHT), 50),
        (weather_for("ClearNoon", Visibility.SMOKE, Light.DUSK), 500),
    ],
    ids=["fog", "dense_fog_night", "smoke_dusk"],
)
def test_a_foggy_trace_exports_its_visual_range_and_passes_both_checkers(
    weather: Weather, range_m: float, tmp_path: Path
) -> None:
    trace = source(tmp_path / "scenario.scenic", weather=weather.param_text())
    files = write_export(trace, tmp_path / "out")
    assert not any("weather" in note for note in files.notes)
    assert xsd_errors(files.xosc) == []
    report = asam_check(files.xosc)
    assert report.ok, report.issues
    environment = _environment(files.xosc)
    assert environment.get("name") == weather.describe()
    fog = environment.find("Weather/Fog")
    assert fog is not None and float(fog.get("visualRange", 0)) == pytest.approx(range_m, rel=0.03)


def test_a_low_sun_exports_its_elevation_and_azimuth(tmp_path: Path) -> None:
    glare = weather_for("ClearNoon", light=Light.GLARE)
    trace = source(tmp_path / "scenario.scenic", weather=glare.param_text())
    files = write_export(trace, tmp_path / "out")
    assert xsd_errors(files.xosc) == []
    sun = _environment(files.xosc).find("Weather/Sun")
    assert sun is not None
    assert float(sun.get("elevation", 0)) == pytest.approx(math.radians(7), abs=1e-4)
    assert float(sun.get("azimuth", 0)) == pytest.approx(math.radians(359), abs=1e-4)
    assert 0 < float(sun.get("illuminance", 0)) < 20_000
    fog = _environment(files.xosc).find("Weather/Fog")
    assert fog is not None and float(fog.get("visualRange", 0)) > 50_000


def test_an_unreadable_weather_dict_exports_the_default_with_a_note(tmp_path: Path) -> None:
    trace = source(tmp_path / "scenario.scenic", weather='{"fog_density": NaN}')
    files = write_export(trace, tmp_path / "out")
    assert any("unreadable" in note for note in files.notes)
    assert _environment(files.xosc).get("name") == "ClearNoon"
    assert xsd_errors(files.xosc) == []
