"""scenario.xosc from a hand-made trace: the schema, ASAM's checker, and the motion read back."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from arise.present.errors import ExportError
from arise.present.verify import asam_check, read_back, worst_gap, xsd_errors, xsd_path
from arise.present.xosc import EgoMode, write_export
from tests.present.traces import TIMESTEP, source

ROUND_TRIP_M = 0.1


@pytest.fixture(scope="module")
def exported(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, object]:
    folder = tmp_path_factory.mktemp("export")
    trace = source(folder / "scenario.scenic")
    files = write_export(trace, folder / "out")
    return files.xosc, trace


def test_the_schema_comes_from_an_installed_package() -> None:
    path = xsd_path(2)
    assert path.is_file() and path.name == "OpenSCENARIO_1_2.xsd"


def test_export_is_valid_against_the_openscenario_1_2_schema(exported) -> None:
    xosc, _ = exported
    assert xsd_errors(xosc) == []
    root = ET.parse(xosc).getroot()
    header = root.find("FileHeader")
    assert header is not None and header.get("revMajor") == "1" and header.get("revMinor") == "2"


def test_a_broken_file_fails_the_schema(exported, tmp_path: Path) -> None:
    xosc, _ = exported
    broken = tmp_path / "broken.xosc"
    broken.write_text(xosc.read_text().replace("<Storyboard>", "<Storyboard><Nonsense/>"))
    assert xsd_errors(broken)


def test_export_passes_asams_openscenario_xml_checker(exported) -> None:
    xosc, _ = exported
    report = asam_check(xosc)
    assert report.ok, report.issues
    assert report.statuses["check_asam_xosc_xml_valid_schema"] == "completed"
    assert all(status in ("completed", "skipped") for status in report.statuses.values())


def test_every_agent_is_within_10_cm_of_its_trace_at_every_step(exported) -> None:
    xosc, trace = exported
    back = read_back(xosc)
    agents = trace.simulation.agents
    assert set(back) == {a.name for a in agents}
    for agent in agents:
        motion = back[agent.name]
        first = agent.trajectory[0]
        assert math.hypot(motion.start[0] - first.x, motion.start[1] - first.y) < 1e-3
        assert motion.times[0] == 0 and motion.times[-1] == pytest.approx(
            agent.trajectory[-1].step * TIMESTEP
        )
        assert worst_gap(agent, motion, TIMESTEP) <= ROUND_TRIP_M, agent.name
        # ... and exactly at the exported vertices themselves
        by_time = {round(p.step * TIMESTEP, 4): p for p in agent.trajectory}
        for t, (x, y) in zip(motion.times, motion.points, strict=True):
            point = by_time[round(t, 4)]
            assert math.hypot(x - point.x, y - point.y) < 1e-3


def test_straight_motion_needs_two_vertices_and_a_bend_more(exported) -> None:
    xosc, _ = exported
    back = read_back(xosc)
    assert len(back["ego"].times) == 2
    assert len(back["Car1"].times) > 2


def test_entities_carry_class_box_blueprint_and_speed(exported) -> None:
    xosc, trace = exported
    root = ET.parse(xosc).getroot()
    objects = {o.get("name"): o for o in root.iter("ScenarioObject")}
    ego = objects["ego"].find("Vehicle")
    assert ego is not None
    assert ego.get("name") == "vehicle.lincoln.mkz_2017"
    assert ego.get("vehicleCategory") == "car"
    dims = ego.find("BoundingBox/Dimensions")
    assert dims is not None and float(dims.get("width", 0)) == 2.0
    assert float(dims.get("length", 0)) == 4.5
    props = {p.get("name"): p.get("value") for p in ego.iter("Property")}
    assert props["type"] == "ego_vehicle" and props["arise_class"] == "Car"
    walker = objects["Pedestrian1"].find("Pedestrian")
    assert walker is not None and walker.get("name") == "walker.pedestrian.0001"
    cone = objects["Cone1"].find("MiscObject")
    assert cone is not None and cone.get("name") == "static.prop.constructioncone"
    # A car without a blueprint in the trace gets the class's default one.
    car = objects["Car1"].find("Vehicle")
    assert car is not None and car.get("name", "").startswith("vehicle.")
    back = read_back(xosc)
    assert back["ego"].speed == 10.0 and back["Pedestrian1"].speed == 1.0
    assert back["Cone1"].speed is None


def test_weather_preset_becomes_the_environment(exported) -> None:
    xosc, _ = exported
    root = ET.parse(xosc).getroot()
    environment = root.find(".//EnvironmentAction/Environment")
    assert environment is not None and environment.get("name") == "HardRainNight"
    precipitation = environment.find("Weather/Precipitation")
    assert precipitation is not None and precipitation.get("precipitationType") == "rain"
    sun = environment.find("Weather/Sun")
    assert sun is not None and float(sun.get("illuminance", 1)) == 0.0
    time_of_day = environment.find("TimeOfDay")
    assert time_of_day is not None and "T23:" in time_of_day.get("dateTime", "")


def test_stop_trigger_ends_with_the_trace(exported) -> None:
    xosc, trace = exported
    root = ET.parse(xosc).getroot()
    condition = root.find("Storyboard/StopTrigger//SimulationTimeCondition")
    assert condition is not None
    assert float(condition.get("value", 0)) == pytest.approx(trace.simulation.steps * TIMESTEP)


def test_the_map_is_copied_beside_and_referenced_relatively(exported) -> None:
    xosc, trace = exported
    logic = ET.parse(xosc).getroot().find("RoadNetwork/LogicFile")
    assert logic is not None and logic.get("filepath") == "arise_straight.xodr"
    copy = xosc.parent / "arise_straight.xodr"
    assert copy.read_bytes() == Path(trace.map.path).read_bytes()


def test_ego_free_leaves_the_ego_without_a_trajectory(tmp_path: Path) -> None:
    trace = source(tmp_path / "scenario.scenic")
    files = write_export(trace, tmp_path / "free", EgoMode.FREE)
    assert "ego" not in files.vertices and "Pedestrian1" in files.vertices
    assert xsd_errors(files.xosc) == []
    assert asam_check(files.xosc).ok
    back = read_back(files.xosc)
    assert back["ego"].times == [] and back["ego"].start[:2] == (10.0, -5.25)
    props = {
        p.get("name"): p.get("value")
        for p in ET.parse(files.xosc).getroot().iter("Property")
        if p.get("name") == "arise_ego_mode"
    }
    assert props == {"arise_ego_mode": "free"}


def test_missing_weather_is_the_default_with_a_note(tmp_path: Path) -> None:
    trace = source(tmp_path / "scenario.scenic", weather=None)
    files = write_export(trace, tmp_path / "out")
    assert any("no weather" in note for note in files.notes)
    environment = ET.parse(files.xosc).getroot().find(".//Environment")
    assert environment is not None and environment.get("name") == "ClearNoon"


def test_a_trace_without_agents_is_refused_and_writes_nothing(tmp_path: Path) -> None:
    trace = source(tmp_path / "scenario.scenic")
    trace.simulation.agents = []
    with pytest.raises(ExportError):
        write_export(trace, tmp_path / "out")
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_export_is_the_same_file_every_time(tmp_path: Path) -> None:
    trace = source(tmp_path / "scenario.scenic")
    first = write_export(trace, tmp_path / "a").xosc.read_bytes()
    second = write_export(trace, tmp_path / "b").xosc.read_bytes()
    assert first == second
