"""Fidelity: does the scenario that ran do what the *description* says?

Why a second number next to conformity: `generate/conformity.py` compares the trace with
the spec the model extracted, so a hallucinated spec (rain nobody asked for, the adversary
on the wrong side, the ego given the other car's turn) agrees with itself. Fidelity compares
the trace with truth written by hand before anything ran (`devsets/*.jsonl`, see
`devsets/README.md`) and never looks at a spec.

Every fact is read from the trace the validator recorded: classes (from the blueprint when
it names a CARLA category, else the Scenic class), start positions and headings in the ego's
initial frame, how each agent moved, junction steps and lane changes from the road network,
the closest approach to the ego, the weather parameter (a preset, or CARLA parameters named
by their closest preset: `_weather_verdict`); plus the features of the map it ran
on when the caller knows them. Each labeled fact gets a `Verdict` (expected, observed,
match); `match` is None when the text does not state the fact or the trace cannot tell, and
such facts do not count. The score is matched / scored.
"""

from __future__ import annotations

import difflib
import json
import math
from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass, field
from enum import StrEnum
from functools import cache
from itertools import islice, permutations
from pathlib import Path
from typing import Any, TypeVar

from arise.errors import AriseError
from arise.generate.conformity import (
    LANE_HALF,
    NEXT_LANE,
    TURN_DEGREES,
    at_junction,
    ego_maneuver,
    frame,
    start_relation,
    travel_heading,
    wrap,
)
from arise.validate.types import AgentTrace, CheckResult, SimulationFacts, Stage, TracePoint
from arise.vocabulary import (
    ACTOR_CLASSES,
    DEFAULT_WEATHER,
    MAP_FEATURES,
    POINT_CLASSES,
    PROP_CLASSES,
    WEATHER_PRESETS,
    ActorClass,
    ActorRole,
    EgoManeuver,
    Side,
)
from arise.weather import Weather, WeatherValueError

#: Closer than this (metres between footprints), or touching, is "came close".
CLOSE_METRES = 3.0
#: Headings within this many degrees of the ego's are "same"; beyond 180 minus it, "opposite".
PARALLEL_DEGREES = 45.0
#: Assignments of trace agents to labeled actors tried per class before taking the best.
MAX_ASSIGNMENTS = 5040
#: How much of an unreadable weather text a verdict shows.
_SHOWN = 80

DEVSET_DIR = Path(__file__).resolve().parent / "devsets"
#: Classes a label may name: road users and props of CARLA's Scenic model.
LABEL_CLASSES: tuple[str, ...] = ACTOR_CLASSES + PROP_CLASSES
# A subclass the text cannot tell from its parent.
_CLASS_ALIASES = {ActorClass.NPC_CAR: ActorClass.CAR}


class DevsetError(AriseError):
    """A dev-set file or a truth does not follow the schema; the message lists every line."""


# -- the labels -----------------------------------------------------------------------------


class DevSet(StrEnum):
    SHORT = "short"
    NHTSA = "nhtsa"
    CRASH_REPORT = "crash_report"
    # the held-apart set's six styles, written later by us to tune on (devsets/README.md)
    STYLES = "styles"
    # many ways of saying where a road user starts and moves (devsets/README.md)
    VARIANTS = "variants"
    # new text in the held-apart set's styles, written before any run (devsets/README.md)
    FRESH = "fresh"
    # a second probe of the same kind, kept unread until a session scores it first
    FRESH2 = "fresh2"
    # a third probe, kept unread until the lead scores it first
    FRESH3 = "fresh3"
    # a fourth probe, written 2026-11-29 and first scored on a change it was not written for
    FRESH4 = "fresh4"
    # a fifth probe, written 2026-11-29, five per paper category, first scored by the lead
    FRESH5 = "fresh5"
    # a sixth probe, written 2026-11-30 by a helper that read no reader, first scored by the lead
    FRESH6 = "fresh6"
    # a seventh probe, written 2026-11-30 by a helper, aimed at where road users start
    FRESH7 = "fresh7"
    # an eighth probe, written 2026-11-30 by a helper, aimed at stationary hazards and props
    FRESH8 = "fresh8"
    # placement probes of our own: two roles, parked and stalled, lanes beside the ego
    PLACEMENT = "placement"
    # tests/heldapart: measured only, never tuned on (its README states the rule)
    HELDAPART = "heldapart"


DEVSET_FILES: dict[DevSet, str] = {
    DevSet.SHORT: "short.jsonl",
    DevSet.NHTSA: "nhtsa.jsonl",
    DevSet.CRASH_REPORT: "crash_reports.jsonl",
    DevSet.STYLES: "styles.jsonl",
    DevSet.VARIANTS: "variants.jsonl",
    DevSet.FRESH: "fresh.jsonl",
    DevSet.FRESH2: "fresh2.jsonl",
    DevSet.FRESH3: "fresh3.jsonl",
    DevSet.FRESH4: "fresh4.jsonl",
    DevSet.FRESH5: "fresh5.jsonl",
    DevSet.FRESH6: "fresh6.jsonl",
    DevSet.FRESH7: "fresh7.jsonl",
    DevSet.FRESH8: "fresh8.jsonl",
    DevSet.PLACEMENT: "placement.jsonl",
}


#: What an actor is for in the text (kept for reading the labels; not scored): the spec's
#: own roles, so a label and a grounded actor use the same words.
Role = ActorRole


class Start(StrEnum):
    """Where an actor starts, seen from the ego where the ego starts."""

    AHEAD = "ahead"  # in the ego's lane, in front
    BEHIND = "behind"  # in the ego's lane, behind
    LEFT = "left"  # left of the ego's lane, anywhere along it
    RIGHT = "right"
    LEFT_FRONT = "left_front"
    RIGHT_FRONT = "right_front"
    LEFT_REAR = "left_rear"
    RIGHT_REAR = "right_rear"
    ONCOMING = "oncoming"  # in front, facing the ego, not on its right
    OPPOSITE_SIDEWALK = "opposite_sidewalk"  # beyond the lane next to the ego on the left


class Direction(StrEnum):
    """Which way an actor goes, in the ego's initial frame (turns: its own heading change)."""

    SAME = "same"
    OPPOSITE = "opposite"
    CROSSING_LEFT_TO_RIGHT = "crossing_left_to_right"
    CROSSING_RIGHT_TO_LEFT = "crossing_right_to_left"
    TURNING_LEFT = "turning_left"
    TURNING_RIGHT = "turning_right"
    STATIONARY = "stationary"


class Maneuver(StrEnum):
    """What the ego does ("stopped": it never moves; slowing to a stop is "straight")."""

    STRAIGHT = "straight"
    LEFT_TURN = "left_turn"
    RIGHT_TURN = "right_turn"
    LANE_CHANGE_LEFT = "lane_change_left"
    LANE_CHANGE_RIGHT = "lane_change_right"
    STOPPED = "stopped"


class Road(StrEnum):
    STRAIGHT = "straight"  # no junction on the ego's way
    INTERSECTION = "intersection"
    T_JUNCTION = "t_junction"
    HIGHWAY = "highway"
    MULTILANE = "multilane"  # more than one lane in the ego's direction


class FactKind(StrEnum):
    """The facts a verdict can be about; `by_fact` in the report groups them so."""

    ACTOR = "actor"  # a labeled actor (class and count) is in the scene
    NO_EXTRA_ACTORS = "no_extra_actors"  # nothing the text does not mention
    START = "start"
    DIRECTION = "direction"
    EGO_MANEUVER = "ego_maneuver"
    ROAD = "road"
    WEATHER = "weather"
    REQUIRED_OBJECT = "required_object"
    MUST_COME_CLOSE = "must_come_close"


@dataclass(frozen=True)
class LabeledActor:
    """One kind of road user (or hazard prop) the text names, `count` of them."""

    cls: ActorClass
    count: int = 1
    role: Role | None = None
    start: Start | None = None
    direction: Direction | None = None

    def __post_init__(self) -> None:
        cls = ActorClass.of(self.cls)  # also when given as text
        if cls is None:
            raise DevsetError("actor: " + _unknown("class", self.cls, LABEL_CLASSES))
        object.__setattr__(self, "cls", cls)

    def as_dict(self) -> dict[str, Any]:
        return {
            "class": self.cls.value,
            "count": self.count,
            "role": self.role.value if self.role else None,
            "start": self.start.value if self.start else None,
            "direction": self.direction.value if self.direction else None,
        }


@dataclass(frozen=True)
class Truth:
    """What a description states; None (or empty) means the text does not say.

    Weather is the exception: None means "not stated", which must come out as the neutral
    `DEFAULT_WEATHER`, since weather nobody asked for is a fault (issue 12).
    `required_objects` are props (`BusStop`) that must be in the scene or map features
    (`signalized`, `sidewalk`) that the map must have.
    """

    actors: tuple[LabeledActor, ...] = ()
    ego_maneuver: Maneuver | None = None
    road: Road | None = None
    weather: str | None = None
    required_objects: tuple[str, ...] = ()
    must_come_close: bool | None = None

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> Truth:
        """Parse a truth (as in the JSONL files); every problem is listed in one DevsetError."""
        truth, problems = _parse_truth(data)
        if problems or truth is None:
            raise DevsetError("invalid truth: " + "; ".join(problems))
        return truth

    def as_dict(self) -> dict[str, Any]:
        return {
            "actors": [a.as_dict() for a in self.actors],
            "ego_maneuver": self.ego_maneuver.value if self.ego_maneuver else None,
            "road": self.road.value if self.road else None,
            "weather": self.weather,
            "required_objects": list(self.required_objects),
            "must_come_close": self.must_come_close,
        }


@dataclass(frozen=True)
class LabeledDescription:
    id: str
    set: DevSet
    category: str
    text: str
    truth: Truth


# -- loading and validating -----------------------------------------------------------------

_TRUTH_KEYS = {"actors", "ego_maneuver", "road", "weather", "required_objects", "must_come_close"}
_ACTOR_KEYS = {"class", "count", "role", "start", "direction"}
_LINE_KEYS = {"id", "set", "category", "text", "truth"}
E = TypeVar("E", bound=StrEnum)


def _unknown(kind: str, value: object, known: Sequence[str]) -> str:
    close = difflib.get_close_matches(str(value), list(known), n=3, cutoff=0.6)
    hint = f" (did you mean {', '.join(close)}?)" if close else f" (one of: {', '.join(known)})"
    return f"unknown {kind} {value!r}{hint}"


def _enum(enum: type[E], value: object, where: str, problems: list[str]) -> E | None:
    if value is None:
        return None
    try:
        if not isinstance(value, str):
            raise ValueError(value)
        return enum(value)
    except ValueError:
        problems.append(
            f"{where}: " + _unknown(where.split(".")[-1], value, [m.value for m in enum])
        )
        return None


def _parse_actor(data: object, where: str, problems: list[str]) -> LabeledActor | None:
    if not isinstance(data, dict):
        problems.append(f"{where}: an actor must be an object")
        return None
    for key in sorted(set(data) - _ACTOR_KEYS):
        problems.append(f"{where}: unknown key {key!r}")
    cls = ActorClass.of(data.get("class"))
    if cls is None:
        problems.append(f"{where}.class: " + _unknown("class", data.get("class"), LABEL_CLASSES))
    count = data.get("count", 1)
    if not isinstance(count, int) or isinstance(count, bool) or count < 1:
        problems.append(f"{where}.count: must be a whole number >= 1, got {count!r}")
    role = _enum(Role, data.get("role"), f"{where}.role", problems)
    start = _enum(Start, data.get("start"), f"{where}.start", problems)
    direction = _enum(Direction, data.get("direction"), f"{where}.direction", problems)
    if cls is None or not isinstance(count, int) or count < 1:
        return None
    return LabeledActor(cls=cls, count=count, role=role, start=start, direction=direction)


def _parse_truth(data: object) -> tuple[Truth | None, list[str]]:
    problems: list[str] = []
    if not isinstance(data, Mapping):
        return None, ["truth must be an object"]
    for key in sorted(set(data) - _TRUTH_KEYS):
        problems.append(f"truth: unknown key {key!r}")
    raw_actors = data.get("actors") or []
    if not isinstance(raw_actors, list):
        problems.append("truth.actors: must be a list")
        raw_actors = []
    actors = [_parse_actor(a, f"actors[{i}]", problems) for i, a in enumerate(raw_actors)]
    maneuver = _enum(Maneuver, data.get("ego_maneuver"), "ego_maneuver", problems)
    road = _enum(Road, data.get("road"), "road", problems)
    weather = data.get("weather")
    if weather is not None and weather not in WEATHER_PRESETS:
        problems.append("weather: " + _unknown("weather preset", weather, WEATHER_PRESETS))
    required = data.get("required_objects") or []
    if not isinstance(required, list):
        problems.append("required_objects: must be a list")
        required = []
    for name in required:
        if name not in PROP_CLASSES and name not in MAP_FEATURES:
            problems.append(
                "required_objects: "
                + _unknown("prop or map feature", name, PROP_CLASSES + MAP_FEATURES)
            )
    close = data.get("must_come_close")
    if close not in (True, None):
        problems.append(f"must_come_close: only true or null (not stated), got {close!r}")
    if problems:
        return None, problems
    return Truth(
        actors=tuple(a for a in actors if a is not None),
        ego_maneuver=maneuver,
        road=road,
        weather=weather,
        required_objects=tuple(required),
        must_come_close=close,
    ), []


def parse_truth(data: object, where: str = "truth") -> Truth:
    """One truth object (a dev-set line's "truth", or a bench prompt's); raise DevsetError
    naming every problem."""
    truth, problems = _parse_truth(data)
    if problems or truth is None:
        raise DevsetError(f"{where}: " + "; ".join(problems or ["unreadable truth"]))
    return truth


def load_devset(path: str | Path) -> list[LabeledDescription]:
    """Read one dev-set file (JSONL); raise DevsetError listing every bad line and why."""
    path = Path(path)
    items: list[LabeledDescription] = []
    problems: list[str] = []
    seen: set[str] = set()
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        if not line.strip():
            continue
        where = f"{path.name}:{number}"
        try:
            data = json.loads(line)
        except json.JSONDecodeError as error:
            problems.append(f"{where}: not JSON ({error.msg})")
            continue
        if not isinstance(data, dict):
            problems.append(f"{where}: a line must be a JSON object")
            continue
        line_problems = [f"unknown key {k!r}" for k in sorted(set(data) - _LINE_KEYS)]
        for key in ("id", "category", "text"):
            if not isinstance(data.get(key), str) or not data[key].strip():
                line_problems.append(f"{key}: missing or empty")
        dev_set = _enum(DevSet, data.get("set"), "set", line_problems)
        if dev_set is None and "set" not in data:
            line_problems.append("set: missing")
        truth, truth_problems = _parse_truth(data.get("truth"))
        line_problems += truth_problems
        if data.get("id") in seen:
            line_problems.append(f"id: {data['id']!r} appears twice")
        seen.add(str(data.get("id")))
        if line_problems or truth is None or dev_set is None:
            problems += [f"{where}: {p}" for p in line_problems]
            continue
        items.append(
            LabeledDescription(
                id=data["id"],
                set=dev_set,
                category=data["category"],
                text=data["text"],
                truth=truth,
            )
        )
    if problems:
        raise DevsetError(f"{path}: {len(problems)} problem(s):\n  " + "\n  ".join(problems))
    return items


def load_devsets(folder: Path = DEVSET_DIR) -> dict[DevSet, list[LabeledDescription]]:
    """The dev sets shipped with arise (or in `folder`)."""
    return {dev_set: load_devset(folder / name) for dev_set, name in DEVSET_FILES.items()}


# -- verdicts -------------------------------------------------------------------------------


@dataclass(frozen=True)
class Verdict:
    """One fact: what the text says, what the trace shows, and whether they agree."""

    fact: FactKind
    subject: str  # which actor or object ("Pedestrian[0]"), or "" for scene facts
    expected: str
    observed: str
    match: bool | None  # None: not stated, or the trace cannot tell

    @property
    def name(self) -> str:
        return f"{self.fact.value}:{self.subject}" if self.subject else self.fact.value

    def as_dict(self) -> dict[str, Any]:
        return {
            "fact": self.fact.value,
            "subject": self.subject,
            "expected": self.expected,
            "observed": self.observed,
            "match": self.match,
        }


@dataclass
class Fidelity:
    """The verdicts on one run; a run that did not execute has none and no score."""

    executed: bool
    verdicts: list[Verdict] = field(default_factory=list)

    @property
    def scored(self) -> list[Verdict]:
        return [v for v in self.verdicts if v.match is not None]

    @property
    def matched(self) -> int:
        return sum(bool(v.match) for v in self.scored)

    @property
    def score(self) -> float | None:
        scored = self.scored
        return self.matched / len(scored) if scored else None

    @property
    def mismatches(self) -> list[str]:
        return [
            f"{v.name}: expected {v.expected}, observed {v.observed}"
            for v in self.verdicts
            if v.match is False
        ]

    def by_fact(self) -> dict[str, dict[str, int]]:
        """Matched and scored facts per kind, for tables per fact across runs."""
        table: dict[str, dict[str, int]] = {}
        for verdict in self.scored:
            row = table.setdefault(verdict.fact.value, {"matched": 0, "scored": 0})
            row["scored"] += 1
            row["matched"] += bool(verdict.match)
        return table

    def verdict(self, name: str) -> Verdict:
        """The verdict called `name` (`start:Car[0]`, `weather`, ...)."""
        for verdict in self.verdicts:
            if verdict.name == name:
                return verdict
        raise KeyError(
            f"no verdict {name!r}; there are: {', '.join(v.name for v in self.verdicts) or 'none'}"
        )

    def as_dict(self) -> dict[str, Any]:
        return {
            "executed": self.executed,
            "score": self.score,
            "matched": self.matched,
            "scored": len(self.scored),
            "mismatches": self.mismatches,
            "by_fact": self.by_fact(),
            "verdicts": [v.as_dict() for v in self.verdicts],
        }


# -- facts from the trace -------------------------------------------------------------------


def _wrap_degrees(angle: float) -> float:
    return math.degrees(wrap(angle))


def _lateral(origin: TracePoint, point: TracePoint) -> float:
    """Metres `point` lies left of `origin`."""
    return frame(origin, point.x, point.y)[1]


@cache
def _blueprint_classes() -> dict[str, ActorClass]:
    """CARLA blueprint -> our class name, from Scenic's table (a firetruck is a Truck even
    when the script says `new Car`). Imported on first use: it pulls in Scenic."""
    try:
        import scenic.simulators.carla.blueprints as table
    except ImportError:  # pragma: no cover - Scenic is a dependency
        return {}
    by_lower = {cls.value.lower(): cls for cls in ActorClass} | {"walker": ActorClass.PEDESTRIAN}
    classes: dict[str, ActorClass] = {}
    for attribute in dir(table):
        category = attribute.removesuffix("Models").lower()
        models = getattr(table, attribute)
        if (
            attribute.endswith("Models")
            and category in by_lower
            and isinstance(models, list | tuple)
        ):
            classes.update({model: by_lower[category] for model in models})
    return classes


def observed_class(agent: AgentTrace) -> ActorClass | str:
    """What the agent is in the scene: its blueprint's category, else its Scenic class
    (as the trace names it when the vocabulary has no such class)."""
    if agent.blueprint:
        found = _blueprint_classes().get(agent.blueprint)
        if found:
            return found
    cls = ActorClass.of(agent.kind)
    return agent.kind if cls is None else _CLASS_ALIASES.get(cls, cls)


@dataclass(frozen=True)
class Placement:
    """Where an agent starts and how it moves, in the ego's initial frame."""

    ahead: float
    left: float
    facing: float  # degrees between its initial heading and the ego's (+: to the ego's left)
    direction: Direction

    def describe(self) -> str:
        return (
            f"{abs(self.ahead):.1f} m {'ahead' if self.ahead >= 0 else 'behind'}, "
            f"{abs(self.left):.1f} m {'left' if self.left >= 0 else 'right'}, "
            f"facing {self.facing:+.0f} deg, {self.direction.value}"
        )


def placement(ego: AgentTrace, agent: AgentTrace) -> Placement | None:
    """Start and direction of `agent` seen from the ego's first trace point."""
    relation = start_relation(ego, agent)
    if relation is None:
        return None
    origin = ego.trajectory[0]
    facing = _wrap_degrees(agent.trajectory[0].heading - origin.heading)
    return Placement(relation.ahead, relation.left, facing, _direction(origin, agent))


def _direction(origin: TracePoint, agent: AgentTrace) -> Direction:
    travel = travel_heading(agent)
    if travel is None:
        return Direction.STATIONARY
    turn = _wrap_degrees(agent.trajectory[-1].heading - agent.trajectory[0].heading)
    if turn > TURN_DEGREES:
        return Direction.TURNING_LEFT
    if turn < -TURN_DEGREES:
        return Direction.TURNING_RIGHT
    relative = _wrap_degrees(travel - origin.heading)
    if abs(relative) < PARALLEL_DEGREES:
        return Direction.SAME
    if abs(relative) > 180 - PARALLEL_DEGREES:
        return Direction.OPPOSITE
    # Moving toward the ego's left means it came from the right.
    return Direction.CROSSING_RIGHT_TO_LEFT if relative > 0 else Direction.CROSSING_LEFT_TO_RIGHT


def start_matches(start: Start, where: Placement) -> bool:
    """Does the observed start fit the labeled one? Sides are read outside the ego's lane
    half-width; front and rear by the sign of the distance along the ego's heading."""
    in_lane = abs(where.left) < LANE_HALF
    left, right = not in_lane and where.left > 0, not in_lane and where.left < 0
    front = where.ahead > 0
    rules = {
        Start.AHEAD: in_lane and front,
        Start.BEHIND: in_lane and not front,
        Start.LEFT: left,
        Start.RIGHT: right,
        Start.LEFT_FRONT: left and front,
        Start.RIGHT_FRONT: right and front,
        Start.LEFT_REAR: left and not front,
        Start.RIGHT_REAR: right and not front,
        Start.ONCOMING: front
        and abs(where.facing) > 180 - PARALLEL_DEGREES
        and where.left > -LANE_HALF,
        Start.OPPOSITE_SIDEWALK: where.left > NEXT_LANE,
    }
    return rules[start]


def observed_maneuver(ego: AgentTrace) -> Maneuver | None:
    """The ego's maneuver: stopped, a turn (heading change), a lane change (the road network's
    count) to the side of its first change (without a road network: the side it drifted
    furthest), or straight."""
    if not ego.trajectory:
        return None
    if travel_heading(ego) is None:
        return Maneuver.STOPPED
    coarse = ego_maneuver(ego)
    if coarse is None:
        return None
    if coarse is EgoManeuver.CHANGE_LANE:
        if ego.lane_change_log:  # the road network's side; a curve's drift says nothing
            left = ego.lane_change_log[0].side is Side.LEFT
            return Maneuver.LANE_CHANGE_LEFT if left else Maneuver.LANE_CHANGE_RIGHT
        origin = ego.trajectory[0]
        widest = max((_lateral(origin, p) for p in ego.trajectory), key=abs)
        return Maneuver.LANE_CHANGE_LEFT if widest > 0 else Maneuver.LANE_CHANGE_RIGHT
    return {
        EgoManeuver.TURN_LEFT: Maneuver.LEFT_TURN,
        EgoManeuver.TURN_RIGHT: Maneuver.RIGHT_TURN,
    }.get(coarse, Maneuver.STRAIGHT)


def _weather_kind(preset: str) -> tuple[str, str]:
    """(sky, time of day) of a preset: labels say "rain at night", not how hard it rains,
    so the intensity of rain is not judged."""
    time = (
        "night" if preset.endswith("Night") else "sunset" if preset.endswith("Sunset") else "noon"
    )
    for word, sky in (
        ("Rain", "rain"),
        ("Wet", "wet"),
        ("Cloudy", "cloudy"),
        ("Clear", "clear"),
        ("Dust", "dust"),
    ):
        if word in preset:
            return sky, time
    return preset.lower(), time


# -- the comparison -------------------------------------------------------------------------


@dataclass(frozen=True)
class _Slot:
    """One labeled individual: actor entry `index`, number `number` of its count."""

    index: int
    number: int
    actor: LabeledActor

    def subject(self) -> str:
        suffix = f"#{self.number + 1}" if self.actor.count > 1 else ""
        return f"{self.actor.cls}[{self.index}]{suffix}"


def _pair_score(slot: _Slot, where: Placement | None) -> int:
    if where is None:
        return 0
    return (slot.actor.start is not None and start_matches(slot.actor.start, where)) + (
        slot.actor.direction is not None and slot.actor.direction is where.direction
    )


def _best_pairs(scores: list[list[int]]) -> list[tuple[int, int]]:
    """The (slot, agent) pairing with the most matching facts (`scores[slot][agent]`): the
    text does not say which trace agent is which actor, so the kindest reading is taken
    (the first one in trace order on ties)."""
    n_slots, n_agents = len(scores), len(scores[0]) if scores else 0
    if not n_slots or not n_agents:
        return []
    if n_slots <= n_agents:
        candidates = (
            list(zip(range(n_slots), perm, strict=True))
            for perm in permutations(range(n_agents), n_slots)
        )
    else:
        candidates = (
            list(zip(perm, range(n_agents), strict=True))
            for perm in permutations(range(n_slots), n_agents)
        )
    return max(
        islice(candidates, MAX_ASSIGNMENTS), key=lambda pairs: sum(scores[s][a] for s, a in pairs)
    )


def score_fidelity(
    truth: Truth, check: CheckResult, map_features: Collection[str] | None = None
) -> Fidelity:
    """Compare what ran (the trace of `check`) with the hand-written `truth`.

    `map_features` are the features of the map the script ran on (the registry's entry for
    `check.map.name`); without them the road type is judged by junction steps alone, and
    highway, multi-lane and map-feature objects cannot be told (None).
    """
    facts = check.simulation
    # A script the semantic gate found wanting still ran: its trace is what a user gets.
    gated = check.diagnostic is not None and check.diagnostic.stage is Stage.SEMANTIC
    if not (check.ok or gated) or facts is None:
        return Fidelity(executed=False)
    features = frozenset(map_features) if map_features is not None else None
    verdicts: list[Verdict] = []
    ego = next((a for a in facts.agents if a.is_ego), None)
    others = [a for a in facts.agents if not a.is_ego and a.kind not in POINT_CLASSES]
    places = {id(a): placement(ego, a) if ego else None for a in others}

    # Labeled actors <- trace agents, class by class.
    slots = [_Slot(i, n, actor) for i, actor in enumerate(truth.actors) for n in range(actor.count)]
    assigned: dict[_Slot, AgentTrace] = {}
    for cls in dict.fromkeys(s.actor.cls for s in slots):
        mine = [s for s in slots if s.actor.cls == cls]
        theirs = [a for a in others if observed_class(a) == cls]
        pairs = _best_pairs([[_pair_score(s, places[id(a)]) for a in theirs] for s in mine])
        assigned.update({mine[s]: theirs[a] for s, a in pairs})

    for index, actor in enumerate(truth.actors):
        found = sum(1 for s in assigned if s.index == index)
        verdicts.append(
            Verdict(
                FactKind.ACTOR,
                f"{actor.cls}[{index}]",
                f"{actor.count} {actor.cls}",
                f"{found} {actor.cls}",
                found == actor.count,
            )
        )
    for slot in slots:
        verdicts.extend(_placement_verdicts(slot, assigned.get(slot), places))

    used = {id(agent) for agent in assigned.values()}
    extras = [a for a in others if id(a) not in used]
    for name in truth.required_objects:  # a named prop is not an extra (one each)
        prop = next((a for a in extras if observed_class(a) == name), None)
        if prop is not None:
            extras.remove(prop)
    verdicts.append(
        Verdict(
            FactKind.NO_EXTRA_ACTORS,
            "",
            "none",
            ", ".join(f"{a.name} ({observed_class(a)})" for a in extras) or "none",
            not extras,
        )
    )

    verdicts.append(_maneuver_verdict(truth.ego_maneuver, ego))
    verdicts.append(_road_verdict(truth.road, ego, others, features))
    verdicts.append(_weather_verdict(truth.weather, facts))
    present = [observed_class(a) for a in others]
    for name in truth.required_objects:
        verdicts.append(_object_verdict(name, present, features))
    verdicts.append(
        _close_verdict(truth.must_come_close, facts, {a.name for a in assigned.values()})
    )
    return Fidelity(executed=True, verdicts=verdicts)


def _placement_verdicts(
    slot: _Slot, agent: AgentTrace | None, places: Mapping[int, Placement | None]
) -> list[Verdict]:
    where = places.get(id(agent)) if agent is not None else None
    observed = (
        "absent"
        if agent is None
        else f"{agent.name}: {where.describe()}"
        if where
        else f"{agent.name}: no trace"
    )
    start, direction = slot.actor.start, slot.actor.direction
    start_ok = (
        None
        if start is None or (agent is not None and where is None)
        else where is not None and start_matches(start, where)
    )
    direction_ok = (
        None
        if direction is None or (agent is not None and where is None)
        else where is not None and where.direction is direction
    )
    return [
        Verdict(
            FactKind.START,
            slot.subject(),
            start.value if start else "not stated",
            observed,
            start_ok,
        ),
        Verdict(
            FactKind.DIRECTION,
            slot.subject(),
            direction.value if direction else "not stated",
            observed,
            direction_ok,
        ),
    ]


def _maneuver_verdict(expected: Maneuver | None, ego: AgentTrace | None) -> Verdict:
    seen = observed_maneuver(ego) if ego is not None else None
    return Verdict(
        FactKind.EGO_MANEUVER,
        "",
        expected.value if expected else "not stated",
        seen.value if seen else "unknown",
        None if expected is None or seen is None else seen is expected,
    )


def _road_verdict(
    road: Road | None,
    ego: AgentTrace | None,
    others: list[AgentTrace],
    features: frozenset[str] | None,
) -> Verdict:
    expected = road.value if road else "not stated"
    if ego is None:
        return Verdict(FactKind.ROAD, "", expected, "no ego", None)
    others_steps = sum(a.intersection_steps for a in others)
    observed = f"ego {ego.intersection_steps} junction steps, others {others_steps}"
    if features is not None:
        observed += f"; map: {', '.join(sorted(features)) or 'no features'}"
    # A stopped ego at the stop line is at the junction without entering it.
    in_junction = ego.intersection_steps + others_steps > 0 or at_junction(ego)
    match: bool | None
    if road is None:
        match = None
    elif road is Road.STRAIGHT:
        match = ego.intersection_steps == 0
    elif road is Road.INTERSECTION:
        match = in_junction and (features is None or "intersection4" in features)
    elif road is Road.T_JUNCTION:
        match = in_junction and (features is None or "tjunction" in features)
    elif features is None:  # highway and multi-lane are properties of the map
        match = None
    elif road is Road.HIGHWAY:
        # A motorway's only junction is where an on-ramp joins it (the merge zone).
        match = "highway" in features and (ego.intersection_steps == 0 or "merge" in features)
    else:
        match = bool({"multilane", "highway"} & features)
    return Verdict(FactKind.ROAD, "", expected, observed, match)


def _weather_verdict(expected: str | None, facts: SimulationFacts) -> Verdict:
    """A trace's weather is a preset's name or the parameter dict the script set (fog,
    a low sun); either is read into a `Weather` and named by its closest preset by sky
    and light (`Weather.closest_preset`), which is compared with the label by sky and time
    of day: fog over CloudyNoon is CloudyNoon, so a fog run matches the label "CloudyNoon"
    that the labelling rules give fog, and dusk or glare match a Sunset. The labels name
    presets only, so the visibility itself is not scored. Unstated weather must be exactly
    the neutral preset: fog or a low sun nobody asked for does not match."""
    seen = facts.params.get("weather")
    label = expected or f"{DEFAULT_WEATHER} (not stated)"
    if seen is None:
        return Verdict(FactKind.WEATHER, "", label, "unset", None)
    try:
        weather = Weather.from_param_text(seen)
    except WeatherValueError:
        return Verdict(FactKind.WEATHER, "", label, seen[:_SHOWN], None)
    if expected is None:
        match = weather.same_as(Weather.preset_only(DEFAULT_WEATHER))
    else:
        match = _weather_kind(weather.closest_preset()) == _weather_kind(expected)
    return Verdict(FactKind.WEATHER, "", label, weather.describe(), match)


def _object_verdict(name: str, present: list[str], features: frozenset[str] | None) -> Verdict:
    if name in PROP_CLASSES:
        count = present.count(name)
        return Verdict(
            FactKind.REQUIRED_OBJECT, name, f"a {name} in the scene", f"{count} {name}", count > 0
        )
    if features is None:
        return Verdict(
            FactKind.REQUIRED_OBJECT, name, f"map with {name}", "map features unknown", None
        )
    return Verdict(
        FactKind.REQUIRED_OBJECT,
        name,
        f"map with {name}",
        ", ".join(sorted(features)) or "no features",
        name in features,
    )


def _close_verdict(expected: bool | None, facts: SimulationFacts, labeled: set[str]) -> Verdict:
    label = f"within {CLOSE_METRES:g} m of the ego or touching" if expected else "not stated"
    pairs = [p for p in facts.ego_pairs if p.other in labeled] or facts.ego_pairs
    pairs = [p for p in pairs if p.collided or p.min_distance >= 0]
    if not pairs:
        return Verdict(
            FactKind.MUST_COME_CLOSE,
            "",
            label,
            "no other agent",
            None if expected is None else False,
        )
    closest = min(pairs, key=lambda p: (not p.collided, p.min_distance))
    observed = (
        f"collision with {closest.other}"
        if closest.collided
        else f"{closest.min_distance:.1f} m from {closest.other}"
    )
    match = None if expected is None else closest.collided or closest.min_distance < CLOSE_METRES
    return Verdict(FactKind.MUST_COME_CLOSE, "", label, observed, match)
