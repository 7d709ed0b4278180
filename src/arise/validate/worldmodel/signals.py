"""Traffic lights and stop signs of the offline world: where they stand and their state.

OpenDRIVE signals as Scenic reads them carry no position, so the world model places its
own: one traffic light per road that enters a signalised junction (a stop line across the
lanes it brings in, at the junction's edge), and one stop sign per road entering a
junction that carries a stop sign (OpenDRIVE type 206) on it or on a connecting road
from it.

The lights run a fixed cycle, deterministic from the map: at each junction the entries
roughly parallel to the first one (within 45 degrees, either way) form phase A, the rest
phase B; A is green for 10 s, yellow 3 s, then all red 1 s, then B likewise (28 s). A
script that sets a light (the CARLA model's traffic-light helpers) holds it, and its
junction with it, from then on (`SignalModel.hold`). `traces` gives every light's changes
for the trace (`SignalTrace`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from itertools import combinations
from typing import Any

from arise.agents.types import LightState, SignalKind, SignalTrace

GREEN_SECONDS = 10.0
YELLOW_SECONDS = 3.0
ALL_RED_SECONDS = 1.0
CYCLE_SECONDS = 2 * (GREEN_SECONDS + YELLOW_SECONDS + ALL_RED_SECONDS)
STOP_SIGN_TYPES = frozenset({"206", "R1-1"})  # Germany/Vienna convention (CARLA), US MUTCD
_COLORS = {"red": LightState.RED, "yellow": LightState.YELLOW, "green": LightState.GREEN}


@dataclass
class Approach:
    """One road's entry into one junction, with the signal that controls it."""

    id: str
    kind: SignalKind
    lanes: frozenset[str]  # uids of the incoming lanes it controls
    stop_line: tuple[tuple[float, float], tuple[float, float]]
    intersection: str
    phase: int = 0  # 0: A, 1: B (lights only)
    # (step, state, set on this very approach): a state a script set on this approach
    # beats one its junction implied at the same step (see `SignalModel.state`).
    overrides: list[tuple[int, LightState, bool]] = field(default_factory=list)

    @property
    def midpoint(self) -> tuple[float, float]:
        (ax, ay), (bx, by) = self.stop_line
        return ((ax + bx) / 2, (ay + by) / 2)


def cycle_state(phase: int, seconds: float) -> LightState:
    """A light's state in the fixed cycle."""
    t = (seconds + phase * CYCLE_SECONDS / 2) % CYCLE_SECONDS
    if t < GREEN_SECONDS:
        return LightState.GREEN
    if t < GREEN_SECONDS + YELLOW_SECONDS:
        return LightState.YELLOW
    return LightState.RED


class SignalModel:
    """The signals of one simulation: built from its road network, changed by scripts."""

    def __init__(self, network: Any, timestep: float):
        self.timestep = timestep
        self.approaches: list[Approach] = []
        self._by_lane: dict[str, list[Approach]] = {}
        if network is not None:
            try:
                self._build(network)
            except Exception:  # an odd map must not cost a run its other facts
                self.approaches = []
        for approach in self.approaches:
            for lane in approach.lanes:
                self._by_lane.setdefault(lane, []).append(approach)

    # --- building -----------------------------------------------------------------------
    def _build(self, network: Any) -> None:
        stop_roads = {
            id(road)
            for road in (*network.roads, *network.connectingRoads)
            if any(str(s.type) in STOP_SIGN_TYPES for s in road.signals)
        }
        for inter in network.intersections:
            lit = any(s.isTrafficLight for s in inter.signals)
            entries: dict[int, list[Any]] = {}
            for lane in inter.incomingLanes:
                entries.setdefault(id(lane.road), []).append(lane)
            stopped_from = {
                id(m.startLane.road)
                for m in inter.maneuvers
                if id(m.connectingLane.road) in stop_roads
            }
            lights: list[Approach] = []
            for key, lanes in entries.items():
                road = lanes[0].road
                line = _stop_line(lanes)
                if line is None:
                    continue
                ids = frozenset(str(lane.uid) for lane in lanes)
                if lit:
                    lights.append(
                        Approach(
                            f"{inter.uid}/{road.uid}",
                            SignalKind.TRAFFIC_LIGHT,
                            ids,
                            line,
                            str(inter.uid),
                        )
                    )
                elif key in stop_roads or key in stopped_from:
                    self.approaches.append(
                        Approach(
                            f"{inter.uid}/{road.uid}",
                            SignalKind.STOP_SIGN,
                            ids,
                            line,
                            str(inter.uid),
                        )
                    )
            _assign_phases(lights)
            self.approaches.extend(lights)

    # --- state ---------------------------------------------------------------------------
    def state(self, approach: Approach, step: int) -> LightState:
        if approach.kind is SignalKind.STOP_SIGN:
            return LightState.RED
        held = [
            (at, own, order, state)
            for order, (at, state, own) in enumerate(approach.overrides)
            if at <= step
        ]
        if held:
            # The latest; at one step, what a script set here beats what the junction implied
            # (both approaches set red at the start: both stay red, an all-red junction).
            return max(held, key=lambda item: item[:3])[3]
        return cycle_state(approach.phase, step * self.timestep)

    def approaches_of(self, lane_uid: str | None) -> list[Approach]:
        return self._by_lane.get(str(lane_uid), []) if lane_uid is not None else []

    def light_for(self, network: Any, position: Any) -> Approach | None:
        """The traffic light controlling a vehicle: that of the lane it is in, or of the
        lane a connecting lane it is on started from."""
        if network is None or not self.approaches:
            return None
        lane = network.laneAt(position)
        if lane is None:
            return None
        for approach in self.approaches_of(lane.uid):
            if approach.kind is SignalKind.TRAFFIC_LIGHT:
                return approach
        for inter in network.intersections:
            for maneuver in inter.maneuvers:
                if maneuver.connectingLane is lane:
                    for approach in self.approaches_of(maneuver.startLane.uid):
                        if approach.kind is SignalKind.TRAFFIC_LIGHT:
                            return approach
        return None

    def hold(self, approach: Approach, color: str, step: int) -> None:
        """A script set this light: from now on it stays at that colour, and its junction
        switches with it, as a signal controller would: green or yellow here holds the
        crossing phase red, red here holds the crossing phase green (a light set red so
        that someone runs it: the traffic crossing its path has green). The entries of
        its own phase follow it. Off darkens this light alone."""
        state = _COLORS.get(color, LightState.OFF)
        if approach.kind is not SignalKind.TRAFFIC_LIGHT:
            return
        if state is LightState.OFF:
            approach.overrides.append((step, state, True))
            return
        crossing = LightState.GREEN if state is LightState.RED else LightState.RED
        for other in self.approaches:
            if (
                other.kind is SignalKind.TRAFFIC_LIGHT
                and other.intersection == approach.intersection
            ):
                same = other.phase == approach.phase
                other.overrides.append((step, state if same else crossing, other is approach))

    def hold_intersection(self, intersection_uid: str, color: str, step: int) -> None:
        """Every light of a junction held at one colour (`setAllIntersectionTrafficLightsStatus`)."""
        state = _COLORS.get(color, LightState.OFF)
        for approach in self.approaches:
            if (
                approach.intersection == intersection_uid
                and approach.kind is SignalKind.TRAFFIC_LIGHT
            ):
                approach.overrides.append((step, state, True))

    def traces(self, steps: int) -> list[SignalTrace]:
        """Every signal's state changes over steps 0..steps, for the trace."""
        out = []
        for approach in self.approaches:
            changes: list[tuple[int, LightState]] = []
            for step in range(steps + 1):
                state = self.state(approach, step)
                if not changes or changes[-1][1] is not state:
                    changes.append((step, state))
                if approach.kind is SignalKind.STOP_SIGN:
                    break
            out.append(
                SignalTrace(
                    id=approach.id, kind=approach.kind, stop_line=approach.stop_line, states=changes
                )
            )
        return out


def _stop_line(lanes: list[Any]) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The segment across the ends of these lanes (the two end points farthest apart of
    their left and right edges), ordered (p1, p2) with p1 on the right and p2 on the left
    as the stopping traffic sees them: it travels along p2 - p1 turned clockwise."""
    ends: list[tuple[float, float]] = []
    for lane in lanes:
        for edge in (lane.leftEdge, lane.rightEdge):
            coords = list(edge.lineString.coords)
            if coords:
                ends.append((round(float(coords[-1][0]), 3), round(float(coords[-1][1]), 3)))
    if len(ends) < 2:
        return None
    a, b = max(combinations(ends, 2), key=lambda pair: math.dist(*pair))
    centre = [(float(x), float(y)) for x, y, *_ in lanes[0].centerline.lineString.coords]
    if len(centre) >= 2:
        tx, ty = centre[-1][0] - centre[-2][0], centre[-1][1] - centre[-2][1]
        if (b[1] - a[1]) * tx - (b[0] - a[0]) * ty < 0:
            a, b = b, a
    return (a, b)


def _assign_phases(lights: list[Approach]) -> None:
    """Phase A: entries within 45 degrees of the first one's direction, either way."""
    if not lights:
        return
    headings = [_entry_heading(approach) for approach in lights]
    first = headings[0]
    for approach, heading in zip(lights, headings, strict=True):
        turn = abs(math.atan2(math.sin(heading - first), math.cos(heading - first)))
        approach.phase = 0 if turn < math.pi / 4 or turn > 3 * math.pi / 4 else 1


def _entry_heading(approach: Approach) -> float:
    """The direction across its stop line (perpendicular to it)."""
    (ax, ay), (bx, by) = approach.stop_line
    return math.atan2(by - ay, bx - ax) + math.pi / 2
