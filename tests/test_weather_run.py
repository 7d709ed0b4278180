"""A script whose weather is a dict of CARLA parameters (fog at dusk), compiled and
simulated by the real validator: the trace records the weather as it ran, the replay names
it, the .xosc carries the fog and passes the schema and ASAM's checker, fidelity scores it,
and the saved trace reads back."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from arise.evaluate.fidelity import Truth, score_fidelity
from arise.present.outputs import write_run_files
from arise.present.source import from_check, load_trace
from arise.present.verify import asam_check, xsd_errors
from arise.validate import CheckOptions, WorkerPool, check
from arise.weather import Light, Visibility, Weather, weather_for
from tests.conftest import EXAMPLES

pytestmark = pytest.mark.slow

FOG_AT_DUSK = weather_for("ClearNoon", Visibility.FOG, Light.DUSK)
OPTIONS = CheckOptions(seed=3, steps=80)


def _script(folder: Path, weather_source: str) -> Path:
    text = (EXAMPLES / "pedestrian_crossing.scenic").read_text(encoding="utf-8")
    assert "param weather = 'ClearNoon'" in text
    script = folder / "foggy.scenic"
    script.write_text(
        text.replace("param weather = 'ClearNoon'", f"param weather = {weather_source}"),
        encoding="utf-8",
    )
    return script


def test_a_foggy_script_runs_and_every_output_carries_the_fog(
    validator_pool: WorkerPool, tmp_path: Path
) -> None:
    script = _script(tmp_path, FOG_AT_DUSK.scenic_source())
    result = check(script, OPTIONS, pool=validator_pool)
    assert result.ok, result.diagnostic
    assert result.simulation is not None
    ran = Weather.from_param_text(result.simulation.params["weather"])
    assert ran.same_as(FOG_AT_DUSK) and ran.closest_preset() == "CloudySunset"

    truth = Truth.from_dict({"weather": "CloudySunset"})
    assert score_fidelity(truth, result).verdict("weather").match is True

    files = write_run_files(from_check(script, result, OPTIONS), tmp_path / "run")
    page = files.replay.html.read_text(encoding="utf-8")
    assert "visual range about 200 m" in page
    xosc = files.export.xosc
    assert xsd_errors(xosc) == []
    report = asam_check(xosc)
    assert report.ok, report.issues
    fog = ET.parse(xosc).getroot().find(".//EnvironmentAction/Environment/Weather/Fog")
    assert fog is not None and 190 <= float(fog.get("visualRange", 0)) <= 210

    saved = json.loads(files.trace.read_text(encoding="utf-8"))
    assert Weather.from_param_text(saved["simulation"]["params"]["weather"]).same_as(ran)


def test_a_partial_dict_runs_as_carla_would_run_it(
    validator_pool: WorkerPool, tmp_path: Path
) -> None:
    script = _script(tmp_path, "{'fog_density': 60.0, 'sun_altitude_angle': 10.0}")
    source = load_trace(script, pool=validator_pool, options=OPTIONS)
    ran = Weather.from_param_text(source.simulation.params["weather"])
    assert ran.parameters()["fog_density"] == 60.0
    assert ran.parameters()["scattering_intensity"] == 0.0  # CARLA's constructor default


def test_an_unknown_weather_parameter_fails_the_run_with_the_world_models_error(
    validator_pool: WorkerPool, tmp_path: Path
) -> None:
    script = _script(tmp_path, "{'fogginess': 60.0}")
    result = check(script, OPTIONS, pool=validator_pool)
    assert not result.ok and result.diagnostic is not None
    assert result.diagnostic.error_type == "WeatherError"
    assert "fogginess" in result.diagnostic.message
