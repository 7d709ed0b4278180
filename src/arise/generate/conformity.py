"""Deterministic conformity: does the scenario that ran say what the spec says?

No model is asked. Facts come from the simulation the validator ran (which agent is the
adversary, its class, where it started and which way it went, the ego's maneuver, the
junction steps, the weather parameter, the other objects) and are compared with the spec.
A fact that cannot be read (no trace, a weather dict) is "unknown" and does not count.

It lives in the generator because the semantic gate (`semantic_gate`, on by default in
arise mode) makes a script that runs but contradicts the spec fail and be repaired; the
evaluation reads the same check.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from arise.generate.conflict import ConflictLevel, conflict_facts, conflict_level
from arise.generate.spec import Actor, ScenarioSpec
from arise.validate.types import (
    AgentTrace,
    CheckResult,
    Diagnostic,
    SimulationFacts,
    Stage,
    TracePoint,
)
from arise.vocabulary import ActorClass, ActorRole, EgoManeuver, RelativePosition, RoadType
from arise.weather import Weather, WeatherValueError

LANE_HALF = 1.8  # |lateral offset| below this is "in the ego's lane"
NEXT_LANE = 5.6  # up to this is the adjacent lane
TURN_DEGREES = 45.0
LANE_CHANGE_METRES = 2.2
MOVED_METRES = 1.5
AT_JUNCTION_METRES = 5.0  # a stopped ego this close to a junction waits at it
REACH_MARGIN = 1.0  # metres beyond the two half-widths that still count as "in the path"
# A roadside adversary (a parked car, a bystander) may do its part without entering the path.
ROADSIDE = frozenset({RelativePosition.ROADSIDE_LEFT, RelativePosition.ROADSIDE_RIGHT})
# Checks the semantic gate enforces, and the script section that decides each.
GATED_CHECKS = {
    "adversary_type": "SPAWN",
    "spawn_position": "SPAWN",
    "ego_maneuver": "GEOMETRY",
    "ego_stopped": "GEOMETRY",
    "road_type": "GEOMETRY",
    "reaches_ego_path": "BEHAVIOR",
    "conflict": "BEHAVIOR",
    "participants": "MISC",
    "extra_actors": "MISC",
    "weather": "WEATHER",
}


@dataclass(frozen=True)
class ConformityCheck:
    name: str
    expected: str
    observed: str
    ok: bool | None  # None: the fact could not be read
    # False: counted in the score but never failed by the gate (e.g. a roadside actor that
    # may stay at the roadside need not reach the ego's path).
    gated: bool = True

    def as_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "expected": self.expected,
            "observed": self.observed,
            "ok": self.ok,
        }


@dataclass
class Conformity:
    checks: list[ConformityCheck] = field(default_factory=list)
    # The adversary against the ego (`ConflictFacts.as_dict`), when the run has both.
    conflict: dict[str, Any] | None = None

    @property
    def known(self) -> list[ConformityCheck]:
        return [c for c in self.checks if c.ok is not None]

    @property
    def score(self) -> float | None:
        """Share of the readable facts that agree with the spec."""
        known = self.known
        return sum(bool(c.ok) for c in known) / len(known) if known else None

    @property
    def mismatches(self) -> list[str]:
        return [
            f"{c.name}: expected {c.expected}, observed {c.observed}"
            for c in self.checks
            if c.ok is False
        ]

    def as_dict(self) -> dict[str, Any]:
        return {
            "score": self.score,
            "mismatches": self.mismatches,
            "checks": [c.as_dict() for c in self.checks],
            "conflict": self.conflict,
        }


# -- facts from the trace -------------------------------------------------------------------


def find_adversary(agents: list[AgentTrace]) -> AgentTrace | None:
    """Our scripts name the adversary's behavior AdversaryBehavior; else the first mover."""
    others = [a for a in agents if not a.is_ego]
    for agent in others:
        if agent.behavior == "AdversaryBehavior":
            return agent
    movers = [a for a in others if a.behavior]
    candidates = movers or others
    return candidates[0] if candidates else None


def wrap(angle: float) -> float:
    """An angle in radians brought into [-pi, pi)."""
    return (angle + math.pi) % (2 * math.pi) - math.pi


def frame(origin: TracePoint, x: float, y: float) -> tuple[float, float]:
    """(ahead, left) of a point in the frame of `origin` (Scenic heading 0 = +y, CCW)."""
    dx, dy = x - origin.x, y - origin.y
    forward = (-math.sin(origin.heading), math.cos(origin.heading))
    left = (-math.cos(origin.heading), -math.sin(origin.heading))
    return dx * forward[0] + dy * forward[1], dx * left[0] + dy * left[1]


def at_junction(ego: AgentTrace) -> bool:
    """An ego that never moves and starts at a junction's edge (a stop line) is at it."""
    return (
        ego.junction_gap is not None
        and ego.junction_gap <= AT_JUNCTION_METRES
        and travel_heading(ego) is None
    )


def travel_heading(trace: AgentTrace) -> float | None:
    """Heading of the first few metres actually driven or walked, or None if it never moved."""
    if not trace.trajectory:
        return None
    start = trace.trajectory[0]
    for point in trace.trajectory:
        dx, dy = point.x - start.x, point.y - start.y
        if math.hypot(dx, dy) >= MOVED_METRES:
            return math.atan2(-dx, dy)
    return None


def ego_maneuver(ego: AgentTrace) -> EgoManeuver | None:
    if len(ego.trajectory) < 2:
        return None
    start, end = ego.trajectory[0], ego.trajectory[-1]
    turn = math.degrees(wrap(end.heading - start.heading))
    if turn > TURN_DEGREES:
        return EgoManeuver.TURN_LEFT
    if turn < -TURN_DEGREES:
        return EgoManeuver.TURN_RIGHT
    if ego.lane_changes is not None:
        # A bypass through the oncoming lane is a lane change out and one back.
        moves = ego.lane_changes + sum(1 for c in ego.lane_change_log if c.into_opposite)
        return EgoManeuver.CHANGE_LANE if moves else EgoManeuver.GO_STRAIGHT
    _, lateral = frame(start, end.x, end.y)  # no map to ask: sideways drift is the sign
    return EgoManeuver.CHANGE_LANE if abs(lateral) > LANE_CHANGE_METRES else EgoManeuver.GO_STRAIGHT


@dataclass(frozen=True)
class StartRelation:
    ahead: float
    left: float
    direction: str  # same | opposite | crossing | unknown

    @property
    def side(self) -> str:
        if abs(self.left) < LANE_HALF:
            return "centre"
        return "left" if self.left > 0 else "right"

    def describe(self) -> str:
        where = "ahead" if self.ahead >= 0 else "behind"
        return (
            f"{abs(self.ahead):.0f} m {where}, {abs(self.left):.1f} m "
            f"{'left' if self.left >= 0 else 'right'}, moving {self.direction}"
        )


def start_relation(ego: AgentTrace, adversary: AgentTrace) -> StartRelation | None:
    if not ego.trajectory or not adversary.trajectory:
        return None
    origin, first = ego.trajectory[0], adversary.trajectory[0]
    ahead, left = frame(origin, first.x, first.y)
    heading = travel_heading(adversary)
    if heading is None:
        direction = "unknown"
    else:
        delta = abs(math.degrees(wrap(heading - origin.heading)))
        direction = "same" if delta < 45 else "opposite" if delta > 135 else "crossing"
    return StartRelation(ahead=ahead, left=left, direction=direction)


def _spawn_agrees(position: RelativePosition, rel: StartRelation, on_route: bool = False) -> bool:
    """Does the start relation fit the spec's position? `on_route`: the adversary starts on
    the path the ego then drives (ahead in its lane, for an ego that turns into it)."""
    side, direction = rel.side, rel.direction
    moving = direction != "unknown"
    lateral = abs(rel.left)
    rules = {
        RelativePosition.AHEAD_SAME_LANE: (rel.ahead > 0 and side == "centre" or on_route)
        and direction != "opposite",
        RelativePosition.BEHIND_SAME_LANE: rel.ahead < 0 and side == "centre",
        RelativePosition.ADJACENT_LANE_LEFT: side == "left"
        and lateral <= NEXT_LANE
        and direction in ("same", "unknown"),
        RelativePosition.ADJACENT_LANE_RIGHT: side == "right"
        and lateral <= NEXT_LANE
        and direction in ("same", "unknown"),
        RelativePosition.ONCOMING: rel.ahead > 0 and direction == "opposite" and side != "right",
        RelativePosition.ROADSIDE_RIGHT: side == "right",
        RelativePosition.ROADSIDE_LEFT: side == "left",
        RelativePosition.CROSSING_FROM_LEFT: side == "left"
        and (direction == "crossing" or not moving),
        RelativePosition.CROSSING_FROM_RIGHT: side == "right"
        and (direction == "crossing" or not moving),
    }
    return rules[position]


def _starts_on_route(ego: AgentTrace, adversary: AgentTrace) -> bool:
    """Whether the adversary starts ahead on the path the ego drives: within half a lane of
    it, beyond the ego's first few metres (a turning ego's exit lane is its lane ahead)."""
    if len(ego.trajectory) < 2 or not adversary.trajectory:
        return False
    from shapely.geometry import LineString, Point

    path = LineString([(p.x, p.y) for p in ego.trajectory])
    if path.length == 0:
        return False
    start = Point(adversary.trajectory[0].x, adversary.trajectory[0].y)
    return path.distance(start) < LANE_HALF and path.project(start) > MOVED_METRES


def _reach(ego: AgentTrace, adversary: AgentTrace) -> float | None:
    """Smallest distance from the adversary, at any step, to the path the ego's body swept
    (its centre's path, stretched by half its length at both ends: a car that runs into a
    standing ego's rear bumper is on its path)."""
    if not ego.trajectory or not adversary.trajectory:
        return None
    from shapely.geometry import LineString, Point

    first, last = ego.trajectory[0], ego.trajectory[-1]
    half = ego.length / 2

    def along(point: TracePoint, metres: float) -> tuple[float, float]:
        return point.x - math.sin(point.heading) * metres, point.y + math.cos(
            point.heading
        ) * metres

    path_points = [along(first, -half), *((p.x, p.y) for p in ego.trajectory), along(last, half)]
    path = LineString(path_points) if len(set(path_points)) > 1 else Point(path_points[0])
    return min(path.distance(Point(p.x, p.y)) for p in adversary.trajectory)


def actor_counts(actors: list[Actor]) -> tuple[int, int | None]:
    """Fewest and most other objects the cast's actors (the adversary's copies aside)
    account for (None: no upper bound, a plural or a group with no number)."""
    others = [a for a in actors if a.role is not ActorRole.ADVERSARY]
    most = None if any(not a.count_stated for a in others) else sum(a.count for a in others)
    return len(others), most


# -- the comparison -------------------------------------------------------------------------


def check_conformity(
    spec: ScenarioSpec, facts: SimulationFacts | None, map_features: frozenset[str] = frozenset()
) -> Conformity:
    """Compare the spec with what ran; every check says what it expected and saw."""
    result = Conformity()
    add = result.checks.append
    if facts is None:
        add(ConformityCheck("executed", "a simulation", "none", False))
        return result
    ego = next((a for a in facts.agents if a.is_ego), None)
    if spec.no_adversary:  # props and parked cars are not an adversary
        adversary = next((a for a in facts.agents if a.behavior == "AdversaryBehavior"), None)
        observed = adversary.kind if adversary else "no adversary"
        add(ConformityCheck("adversary_type", "no adversary", observed, adversary is None))
    else:
        adversary = find_adversary(facts.agents)
        expected_class = spec.scenic_class
        add(
            ConformityCheck(
                "adversary_type",
                expected_class,
                adversary.kind if adversary else "no adversary",
                adversary is not None and adversary.kind == expected_class,
            )
        )
    if ego is not None and spec.ego_stopped:
        moved = travel_heading(ego) is not None
        add(ConformityCheck("ego_stopped", "stopped", "moved" if moved else "stopped", not moved))
    elif ego is not None and ego.weaving:
        # Weaving across lane lines is no maneuver a description asks for (issue 13).
        add(ConformityCheck("ego_maneuver", spec.ego_maneuver.value, "weaving", False))
    elif ego is not None:
        maneuver = ego_maneuver(ego)
        add(
            ConformityCheck(
                "ego_maneuver",
                spec.ego_maneuver.value,
                maneuver.value if maneuver else "unknown",
                None if maneuver is None else maneuver is spec.ego_maneuver,
            )
        )
    if ego is not None:
        add(_road_check(spec.road_type, ego, adversary, map_features))
    if ego is not None and adversary is not None:
        relation = start_relation(ego, adversary)
        add(
            ConformityCheck(
                "spawn_position",
                spec.spawn_position.value,
                relation.describe() if relation else "unknown",
                None
                if relation is None
                else _spawn_agrees(spec.spawn_position, relation, _starts_on_route(ego, adversary)),
            )
        )
        reach = _reach(ego, adversary)
        limit = (ego.width + adversary.width) / 2 + REACH_MARGIN
        add(
            ConformityCheck(
                "reaches_ego_path",
                f"within {limit:.1f} m of the ego's path",
                "unknown" if reach is None else f"{reach:.1f} m",
                None if reach is None else reach <= limit,
                gated=spec.spawn_position not in ROADSIDE,
            )
        )
        level = conflict_level(spec)
        conflict = conflict_facts(ego, adversary)
        result.conflict = conflict.as_dict(level)
        if level is not ConflictLevel.NONE:
            add(
                ConformityCheck(
                    "conflict", level.wanted, conflict.describe(), conflict.meets(level)
                )
            )
    add(_weather_check(spec, facts.params.get("weather")))
    others = [a for a in facts.agents if not a.is_ego and a is not adversary]
    fewest, most = actor_counts(spec.actors)
    # The others of a counted adversary ("two pedestrians") are neither missing nor extra.
    more = sum(a.count for a in spec.actors if a.role is ActorRole.ADVERSARY)
    fewest, most = fewest + more, None if most is None else most + more
    named = _named_classes(spec)
    missing = sorted(cls for cls in named if not any(_same_class(a.kind, cls) for a in others))
    add(
        ConformityCheck(
            "participants",
            f"at least {fewest} other object(s)"
            + (f": {', '.join(sorted(named))}" if named else ""),
            f"{len(others)}" + (f", no {', '.join(missing)}" if missing else ""),
            len(others) >= fewest and not missing,
        )
    )
    # An object of a class the text never names is extra, however few there are.
    unnamed = [a for a in others if not any(_same_class(a.kind, cls) for cls in named)]
    add(
        ConformityCheck(
            "extra_actors",
            _allowed(most) + (f", only {', '.join(sorted(named))}" if named else ""),
            _describe_others(others),
            (True if most is None else len(others) <= most) and not unnamed,
        )
    )
    for index, actor in enumerate(spec.actors):
        if actor.road_user:
            result.checks.append(_actor_check(index, actor, ego, others))
    return result


def _actor_check(
    index: int, actor: Actor, ego: AgentTrace | None, others: list[AgentTrace]
) -> ConformityCheck:
    """Another road user of the spec: as many of its class in the trace, on its side when
    the text says one (not gated: the participant checks are)."""
    mine = [a for a in others if a.kind == actor.scenic_class]
    start = actor.start
    if actor.role is ActorRole.PARKED and start is RelativePosition.AHEAD_SAME_LANE:
        start = None  # "parked ahead" is at the kerb ahead, not in the ego's lane
    expected = f"{actor.count} {actor.scenic_class}"
    observed = f"{len(mine)} {actor.scenic_class}"
    placed = mine
    if start is not None and ego is not None:
        expected += f" {start.value}"
        relations = [start_relation(ego, a) for a in mine]
        placed = [a for a, r in zip(mine, relations, strict=True) if r and _spawn_agrees(start, r)]
        observed += f", {len(placed)} there"
    return ConformityCheck(
        f"actor {index + 1}", expected, observed, len(placed) >= actor.count, gated=False
    )


def _weather_check(spec: ScenarioSpec, seen: str | None) -> ConformityCheck:
    """The weather that ran against the spec's: the same parameters when the words needed
    more than a preset (fog, dusk), else the same preset. Unreadable text is unknown."""
    wanted = spec.weather_parameters or Weather.preset_only(spec.weather)
    if seen is None:
        return ConformityCheck("weather", spec.weather, "unset", False)
    try:
        ran = Weather.from_param_text(seen)
    except WeatherValueError:
        return ConformityCheck("weather", wanted.describe(), "unreadable", None)
    return ConformityCheck("weather", wanted.describe(), ran.describe(), ran.same_as(wanted))


def _allowed(most: int | None) -> str:
    if most is None:
        return "any number of other objects"
    return "no other object" if most == 0 else f"at most {most} other object(s)"


def _named_classes(spec: ScenarioSpec) -> set[ActorClass]:
    """The classes of what the text names besides the adversary (its other copies too)."""
    return {actor.scenic_class for actor in spec.actors}


def _same_class(kind: str, named: ActorClass) -> bool:
    """A trace agent of class `kind` (untrusted text) is the thing named `named` (an
    NPCCar is a Car)."""
    seen = ActorClass.of(kind)
    return seen is named or (seen is ActorClass.NPC_CAR and named is ActorClass.CAR)


def _describe_others(others: list[AgentTrace]) -> str:
    if not others:
        return "none"
    return f"{len(others)}: " + ", ".join(a.name for a in others)


def _road_check(
    road: RoadType, ego: AgentTrace, adversary: AgentTrace | None, map_features: frozenset[str]
) -> ConformityCheck:
    junction_steps = ego.intersection_steps + (adversary.intersection_steps if adversary else 0)
    observed = (
        "through a junction"
        if junction_steps
        else ("waits at a junction" if at_junction(ego) else "no junction")
    )
    if road in (RoadType.INTERSECTION, RoadType.T_JUNCTION):
        return ConformityCheck(
            "road_type", road.value, observed, junction_steps > 0 or at_junction(ego)
        )
    if road is RoadType.HIGHWAY and map_features:
        on_highway = "highway" in map_features
        return ConformityCheck(
            "road_type",
            road.value,
            f"{observed}, {'highway' if on_highway else 'no highway'} map",
            on_highway and ego.intersection_steps == 0,
        )
    if road is RoadType.MERGE:
        # The merge zone is a junction: the ego or the adversary drives through it.
        on_ramp_map = not map_features or "merge" in map_features
        return ConformityCheck(
            "road_type",
            road.value,
            f"{observed}, {'on-ramp' if on_ramp_map else 'no on-ramp'} map",
            on_ramp_map and junction_steps > 0,
        )
    return ConformityCheck("road_type", road.value, observed, ego.intersection_steps == 0)


@dataclass(frozen=True)
class Contradiction:
    """One gated fact where the trace contradicts the spec, and the section that decides it."""

    check: str
    expected: str
    observed: str
    section: str

    def text(self) -> str:
        return f"{self.check}: expected {self.expected}, observed {self.observed}"

    def as_dict(self) -> dict[str, str]:
        return {
            "check": self.check,
            "expected": self.expected,
            "observed": self.observed,
            "section": self.section,
        }


def contradictions(conformity: Conformity) -> list[Contradiction]:
    """The gated checks that fail (unknown facts never count against a script)."""
    return [
        Contradiction(c.name, c.expected, c.observed, GATED_CHECKS[c.name])
        for c in conformity.checks
        if c.ok is False and c.gated and c.name in GATED_CHECKS
    ]


def gate_result(result: CheckResult, found: list[Contradiction]) -> CheckResult:
    """A result that ran but has contradictions becomes a SEMANTIC failure naming the
    section of the first; anything else is returned as it is."""
    if not result.ok or not found:
        return result
    diagnostic = Diagnostic(
        stage=Stage.SEMANTIC,
        error_type="ConformityMismatch",
        message="; ".join(c.text() for c in found),
        section=found[0].section,
        hint="the script runs but does not do what the description says",
    )
    return result.model_copy(update={"ok": False, "diagnostic": diagnostic})


def semantic_gate(result: CheckResult, conformity: Conformity) -> CheckResult:
    """A script that runs but contradicts the spec fails, naming the section to change."""
    return gate_result(result, contradictions(conformity))
