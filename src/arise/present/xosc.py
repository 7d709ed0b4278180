"""scenario.xosc (ASAM OpenSCENARIO XML 1.2, via scenariogeneration) and the .xodr map it
references, from a validated trace.

Each agent becomes one entity (class, bounding box, CARLA blueprint), placed at its first
world position with its first speed, and follows one timed trajectory of its trace (its
vertices: `trajectory.simplify`). `EgoMode.FREE` leaves the ego to the system under test.
The weather as it ran (a preset, or its parameters: fog as `Fog visualRange`, the sun from
its altitude and azimuth; `present.weather`) becomes the environment, and the scenario
stops when the trace ends.
"""

from __future__ import annotations

import datetime
import time
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from enum import StrEnum
from pathlib import Path
from typing import Any

from arise.present.actors import EntityKind, entity_of, height_of
from arise.present.errors import ExportError
from arise.present.files import copy_file_atomic, write_bytes_atomic
from arise.present.source import TraceSource, map_file
from arise.present.trajectory import TOLERANCE_M, Vertex, osc_heading, simplify
from arise.present.weather import WeatherValues, weather_values
from arise.validate.types import AgentTrace

XOSC_NAME = "scenario.xosc"
OSC_MINOR_VERSION = 2
AUTHOR = "arise"
#: A fixed date: the export of one trace is the same file every time (light comes from
#: the preset's hour and sun angles, not from the date).
SCENARIO_DATE = datetime.datetime(2026, 1, 1, 0, 0, 0)


class EgoMode(StrEnum):
    """Who drives the ego in the exported scenario."""

    REPLAY = "replay"  # the ego follows its trace like every other agent
    FREE = "free"  # the ego starts where it started; the system under test drives it


@dataclass
class ExportFiles:
    xosc: Path
    xodr: Path | None
    vertices: dict[str, int] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    seconds: float = 0.0


def _bounding_box(xosc: Any, agent: AgentTrace) -> Any:
    height = height_of(agent.kind, agent.blueprint)
    # Centred on the reference point: positions in the file are the agent's centre, as
    # Scenic's are, so the box sits exactly where the trace put the agent.
    return xosc.BoundingBox(
        round(agent.width, 3), round(agent.length, 3), round(height, 3), 0, 0, round(height / 2, 3)
    )


def _entity(xosc: Any, agent: AgentTrace, ego_free: bool) -> Any:
    spec = entity_of(agent.kind)
    blueprint = agent.blueprint or spec.blueprint
    box = _bounding_box(xosc, agent)
    if spec.kind is EntityKind.VEHICLE:
        track = round(agent.width * 0.8, 3)
        axle = round(agent.length * 0.3, 3)
        front = xosc.Axle(0.5, 0.6, track, axle, 0.3)
        rear = xosc.Axle(0.0, 0.6, track, -axle, 0.3)
        entity = xosc.Vehicle(
            blueprint,
            getattr(xosc.VehicleCategory, spec.category),
            box,
            front,
            rear,
            spec.max_speed,
            10,
            10,
            mass=spec.mass,
        )
    elif spec.kind is EntityKind.PEDESTRIAN:
        entity = xosc.Pedestrian(
            blueprint,
            spec.mass,
            getattr(xosc.PedestrianCategory, spec.category),
            box,
            model=blueprint,
        )
    else:
        entity = xosc.MiscObject(
            blueprint, spec.mass, getattr(xosc.MiscObjectCategory, spec.category), box
        )
    if spec.kind is not EntityKind.MISC:
        # ScenarioRunner's convention: the ego is "ego_vehicle", everyone else "simulation".
        entity.add_property("type", "ego_vehicle" if agent.is_ego else "simulation")
    entity.add_property("blueprint", blueprint)
    entity.add_property("arise_class", agent.kind)
    if agent.is_ego:
        entity.add_property("arise_ego_mode", "free" if ego_free else "replay")
    return entity


def _environment(xosc: Any, values: WeatherValues) -> Any:
    weather = xosc.Weather(
        cloudstate=getattr(xosc.FractionalCloudCover, _OKTAS[values.cloud_oktas]),
        sun=xosc.Sun(values.sun_intensity_lux, values.sun_azimuth, values.sun_elevation),
        fog=xosc.Fog(values.fog_visual_range_m),
        precipitation=xosc.Precipitation(
            xosc.PrecipitationType.rain if values.rain_mm_h > 0 else xosc.PrecipitationType.dry,
            values.rain_mm_h,
        ),
        wind=xosc.Wind(0, values.wind_m_s),
    )
    return xosc.Environment(
        values.name,
        xosc.TimeOfDay(False, 2026, 6, 21, values.hour, 0, 0),
        weather,
        xosc.RoadCondition(values.friction_scale),
    )


_OKTAS = (
    "zeroOktas",
    "oneOktas",
    "twoOktas",
    "threeOktas",
    "fourOktas",
    "fiveOktas",
    "sixOktas",
    "sevenOktas",
    "eightOktas",
)


def _position(xosc: Any, x: float, y: float, heading: float) -> Any:
    return xosc.WorldPosition(round(x, 3), round(y, 3), 0, round(heading, 4))


def _follow(xosc: Any, agent: AgentTrace, vertices: list[Vertex]) -> Any:
    trajectory = xosc.Trajectory(f"{agent.name}_trace", False)
    trajectory.add_shape(
        xosc.Polyline(
            [v.time for v in vertices], [_position(xosc, v.x, v.y, v.heading) for v in vertices]
        )
    )
    return xosc.FollowTrajectoryAction(
        trajectory,
        xosc.FollowingMode.position,
        xosc.ReferenceContext.absolute,
        1,
        0,
    )


def _at_start(xosc: Any, name: str) -> Any:
    return xosc.ValueTrigger(
        f"{name}_at_start",
        0,
        xosc.ConditionEdge.none,
        xosc.SimulationTimeCondition(0, xosc.Rule.greaterOrEqual),
    )


def build_scenario(
    source: TraceSource,
    road_file: str,
    ego: EgoMode = EgoMode.REPLAY,
    tolerance: float = TOLERANCE_M,
) -> tuple[Any, dict[str, int], list[str]]:
    """The OpenSCENARIO scenario of a trace, the vertex count per agent, and notes on
    what had to be approximated."""
    from scenariogeneration import xosc

    simulation = source.simulation
    agents = [a for a in simulation.agents if a.trajectory]
    if not agents:
        raise ExportError("the trace has no agent with a trajectory: nothing to export")
    values, notes = weather_values(simulation.params.get("weather"))
    entities = xosc.Entities()
    init = xosc.Init()
    init.add_global_action(xosc.EnvironmentAction(_environment(xosc, values)))
    act = xosc.Act("replay", _at_start(xosc, "replay"))
    counts: dict[str, int] = {}
    ego_free = ego is EgoMode.FREE
    for agent in agents:
        spec = entity_of(agent.kind)
        entities.add_scenario_object(agent.name, _entity(xosc, agent, ego_free))
        first = agent.trajectory[0]
        init.add_init_action(
            agent.name,
            xosc.TeleportAction(_position(xosc, first.x, first.y, osc_heading(first.heading))),
        )
        if spec.kind is not EntityKind.MISC:
            init.add_init_action(
                agent.name,
                xosc.AbsoluteSpeedAction(
                    round(first.speed, 3),
                    xosc.TransitionDynamics(
                        xosc.DynamicsShapes.step, xosc.DynamicsDimension.time, 0
                    ),
                ),
            )
        if agent.is_ego and ego_free:
            continue
        vertices = simplify(agent.trajectory, simulation.timestep, tolerance)
        if len(vertices) < 2:  # a one-step trace: stand still for the whole scenario
            vertices = [
                vertices[0],
                Vertex(simulation.steps * simulation.timestep, *_rest(vertices[0])),
            ]
        counts[agent.name] = len(vertices)
        event = xosc.Event(f"{agent.name}_follow", xosc.Priority.override)
        event.add_action(f"{agent.name}_follow_trace", _follow(xosc, agent, vertices))
        event.add_trigger(_at_start(xosc, f"{agent.name}_follow"))
        maneuver = xosc.Maneuver(f"{agent.name}_maneuver")
        maneuver.add_event(event)
        group = xosc.ManeuverGroup(f"{agent.name}_group")
        group.add_actor(agent.name)
        group.add_maneuver(maneuver)
        act.add_maneuver_group(group)
    duration = round(simulation.steps * simulation.timestep, 4)
    stop = xosc.ValueTrigger(
        "end_of_trace",
        0,
        xosc.ConditionEdge.rising,
        xosc.SimulationTimeCondition(duration, xosc.Rule.greaterThan),
        "stop",
    )
    storyboard = xosc.StoryBoard(init, stop)
    if counts:
        story = xosc.Story("replay")
        story.add_act(act)
        storyboard.add_story(story)
    scenario = xosc.Scenario(
        f"{source.title} (arise trace, {duration:g} s)",
        AUTHOR,
        xosc.ParameterDeclarations(),
        entities,
        storyboard,
        xosc.RoadNetwork(roadfile=road_file),
        xosc.Catalog(),
        osc_minor_version=OSC_MINOR_VERSION,
        creation_date=SCENARIO_DATE,
    )
    return scenario, counts, notes


def _rest(vertex: Vertex) -> tuple[float, float, float]:
    return (vertex.x, vertex.y, vertex.heading)


def scenario_xml(scenario: Any) -> bytes:
    element = scenario.get_element()
    ET.indent(element, space="  ")
    return ET.tostring(element, encoding="utf-8", xml_declaration=True) + b"\n"


def write_export(
    source: TraceSource,
    out_dir: Path,
    ego: EgoMode = EgoMode.REPLAY,
    *,
    map_dir: str | None = None,
    tolerance: float = TOLERANCE_M,
) -> ExportFiles:
    """Write scenario.xosc and a copy of the map it references into out_dir."""
    started = time.perf_counter()
    if source.map is None:
        raise ExportError("the trace names no map; OpenSCENARIO needs the road network")
    # The parent's own copy of the map, and its name, a plain file stem by the schema: the
    # copy lands in out_dir and nowhere else.
    road = map_file(source.map, map_dir)
    xodr_name = f"{source.map.name}.xodr"
    scenario, counts, notes = build_scenario(source, xodr_name, ego, tolerance)
    data = scenario_xml(scenario)
    xodr = copy_file_atomic(road, out_dir / xodr_name)
    xosc_path = write_bytes_atomic(out_dir / XOSC_NAME, data)
    return ExportFiles(
        xosc=xosc_path,
        xodr=xodr,
        vertices=counts,
        notes=notes,
        seconds=time.perf_counter() - started,
    )


__all__ = ["EgoMode", "ExportFiles", "build_scenario", "scenario_xml", "write_export"]
