"""Plain data passed across the validator's boundaries (worker <-> caller <-> CLI).

Everything here is JSON-serialisable with `model_dump()`, so a result can be written to a
report, sent over a pipe or compared in a test.

The facts of a simulation come from the worker, whose script may forge them, or from a
run folder anyone may hand over: the schemas below are strict (no unknown fields, finite
numbers, non-negative where physical, bounded sizes: `arise.limits`), so bad data is a
validation error, never a crash or a hang further on.
"""

from __future__ import annotations

from enum import StrEnum
from typing import Annotated

from pydantic import (
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    StringConstraints,
    field_validator,
    model_validator,
)

from arise.agents.types import MAX_SIGNALS, EgoRoute, SignalTrace
from arise.limits import (
    MAX_AGENTS,
    MAX_EVENT_FIELDS,
    MAX_EVENT_LIST,
    MAX_EVENTS,
    MAX_MAGNITUDE,
    MAX_MESSAGE,
    MAX_NAME,
    MAX_NOTE,
    MAX_PARAMS,
    MAX_REJECTIONS,
    MAX_STEPS,
    MAX_TIMESTEP,
    MAX_TIMINGS,
    MAX_TOTAL_POINTS,
    MAX_TRACE_POINTS,
    MAX_WARNINGS,
)
from arise.maps.choice import MapChoice
from arise.vocabulary import Side

__all__ = ["MapChoice"]  # re-exported: results carry the registry's choice

# Bounded building blocks of the strict schemas (see `arise.limits`).
Coordinate = Annotated[float, Field(allow_inf_nan=False, ge=-MAX_MAGNITUDE, le=MAX_MAGNITUDE)]
Magnitude = Annotated[float, Field(allow_inf_nan=False, ge=0, le=MAX_MAGNITUDE)]
Step = Annotated[int, Field(ge=0, le=MAX_STEPS)]
PointCount = Annotated[int, Field(ge=0, le=MAX_TRACE_POINTS)]
Count = Annotated[int, Field(ge=0, le=2**31)]
Name = Annotated[str, StringConstraints(max_length=MAX_NAME)]
# An agent, its class or behavior: identifiers (names a Python class can have).
Identifier = Annotated[str, StringConstraints(pattern=r"^\w{1,128}$")]


def _cut(limit: int) -> BeforeValidator:
    """Free text is cut to its bound rather than refused: a script can make Scenic's own
    messages (a 256 KiB line in an excerpt) longer than any bound, and the worker must
    still be able to say so."""

    def cut(value: object) -> object:
        return value[:limit] if isinstance(value, str) else value

    return BeforeValidator(cut)


Note = Annotated[str, _cut(MAX_NOTE), StringConstraints(max_length=MAX_NOTE)]
Message = Annotated[str, _cut(MAX_MESSAGE), StringConstraints(max_length=MAX_MESSAGE)]
Notes = Annotated[list[Message], Field(max_length=MAX_WARNINGS)]
EventValue = (
    Annotated[bool, Field(strict=True)]
    | Annotated[int, Field(strict=True)]
    | Coordinate
    | Note
    | Annotated[list[Name], Field(max_length=MAX_EVENT_LIST)]
    | None
)
Event = Annotated[dict[Name, EventValue], Field(max_length=MAX_EVENT_FIELDS)]


class Strict(BaseModel):
    """Refuses fields it does not know: a result or a trace holds only what we defined."""

    model_config = ConfigDict(extra="forbid")


class Stage(StrEnum):
    """Where a check stopped. Ordered as the checks run."""

    GATE = "gate"
    PARSE = "parse"
    COMPILE = "compile"
    SAMPLE = "sample"
    SIMULATE = "simulate"
    # The script ran but says something else than the description (the optional gate).
    SEMANTIC = "semantic"


class Simulator(StrEnum):
    """Where a script is simulated."""

    OFFLINE = "offline"  # arise's CARLA-compatible world model on Scenic's Newtonian simulator
    CARLA = "carla"  # a CARLA server, through Scenic's CarlaSimulator


class Mechanism(StrEnum):
    """One layer of OS-level confinement of the worker that runs a script."""

    LANDLOCK_FS = "landlock-fs"  # files: read the interpreter and maps, write only scratch
    LANDLOCK_NET = "landlock-net"  # TCP: no connect or bind (CARLA mode: its ports only)
    LANDLOCK_SCOPE = "landlock-scope"  # signals and abstract sockets stay inside the worker
    SECCOMP = "seccomp"  # no exec, no new processes, no sockets, no kernel-facing calls
    RLIMITS = "rlimits"  # memory, file size, open files, processes, core dumps
    # Own user, mount and (offline) network namespaces: the process limit binds even for
    # root, scratch is a size-limited tmpfs, and there is no network interface but loopback.
    NAMESPACES = "namespaces"


class SandboxReport(Strict):
    """Which confinement a script ran under: every result carries one."""

    active: list[Mechanism] = Field(default_factory=list, max_length=len(Mechanism))
    missing: list[Mechanism] = Field(default_factory=list, max_length=len(Mechanism))
    landlock_abi: int = Field(default=0, ge=0, le=1000)
    notes: Notes = Field(default_factory=list)

    @property
    def full(self) -> bool:
        return not self.missing

    @property
    def label(self) -> str:
        """Short form for one line of output, e.g. `landlock+seccomp+rlimits`."""
        kinds: list[str] = []
        for mechanism in (m for m in Mechanism if m in self.active):
            kind = mechanism.value.split("-")[0]
            if kind not in kinds:
                kinds.append(kind)
        text = "+".join(kinds) or "none"
        if self.missing:
            text += " (MISSING: " + ", ".join(m.value for m in self.missing) + ")"
        return text


def confinement_summary(labels: list[str | None]) -> str:
    """One line for many checks: which confinement they ran under, and how many each."""
    counts: dict[str, int] = {}
    for label in labels:
        key = label or "none (never reached a worker)"
        counts[key] = counts.get(key, 0) + 1
    if len(counts) == 1:
        ((label, count),) = counts.items()
        return f"{label} ({'all ' if count > 1 else ''}{count} check{'s' * (count > 1)})"
    return "; ".join(f"{label}: {count}" for label, count in sorted(counts.items()))


class Rejection(Strict):
    """One reason Scenic threw away samples, with how often and where."""

    reason: Message
    count: Count
    line: Count | None = None
    section: Name | None = None
    code: Message | None = None


class Diagnostic(Strict):
    """Why a script did not execute, precise enough to repair it."""

    stage: Stage
    error_type: Name
    message: Message
    line: Count | None = None
    column: Count | None = None
    section: Name | None = None
    excerpt: Message | None = None
    hint: Message | None = None
    rejections: list[Rejection] = Field(default_factory=list, max_length=MAX_REJECTIONS)

    def one_line(self) -> str:
        where = f" line {self.line}" if self.line else ""
        section = f" [{self.section}]" if self.section else ""
        return f"{self.stage.value}{where}{section}: {self.error_type}: {self.message}"


class TracePoint(Strict):
    step: Step
    x: Coordinate
    y: Coordinate
    heading: Coordinate
    speed: Magnitude


class LaneChange(Strict):
    """One move of an agent's centre into a neighbouring lane, read from the road network."""

    step: Step
    side: Side  # seen in the agent's direction of travel
    # The lane entered runs against the agent's direction of travel (an overtaking or
    # bypassing car in the oncoming lane); False for a move back from it or within its group.
    into_opposite: bool = False
    # The lane left ran against the agent's direction of travel (the way back).
    from_opposite: bool = False


class AgentTrace(Strict):
    name: Identifier
    kind: Identifier
    blueprint: Annotated[str, StringConstraints(pattern=r"^[\w.\-]{1,128}$")] | None = None
    width: Magnitude
    length: Magnitude
    is_ego: bool = False
    # The class name of the behavior it ran (`AdversaryBehavior` marks our adversary).
    behavior: Identifier | None = None
    # Steps at which the agent was inside a junction of the map.
    intersection_steps: PointCount = 0
    # Metres from its first position to the nearest junction (None: no road network, or
    # a network without junctions).
    junction_gap: Magnitude | None = None
    # Moves into a neighbouring lane of the same road (None: no road network to tell).
    lane_changes: PointCount | None = None
    # Every move across a lane boundary outside junctions, in order (same-direction lane
    # changes and moves into and out of the oncoming lanes).
    lane_change_log: list[LaneChange] = Field(default_factory=list, max_length=MAX_TRACE_POINTS)
    # Steps spent in a lane that runs against the agent's travel, outside junctions.
    opposite_lane_steps: PointCount | None = None
    # It moved back across a lane boundary within a few seconds of crossing it, i.e. it
    # wove (a controller fault or an erratic driver), not a deliberate lane change.
    weaving: bool | None = None
    trajectory: list[TracePoint] = Field(default_factory=list, max_length=MAX_TRACE_POINTS)

    @field_validator("junction_gap", mode="before")
    @classmethod
    def _no_junction_is_no_gap(cls, value: object) -> object:
        """A map without junctions is infinitely far from one: no gap, as no network."""
        return None if isinstance(value, float) and value == float("inf") else value


class Collision(Strict):
    first: Identifier
    second: Identifier
    step: Step
    time: Magnitude


class EgoPairFacts(Strict):
    """How close another agent came to the ego: the criticality numbers."""

    other: Identifier
    # -1: no distance could be measured (no common steps).
    min_distance: Annotated[float, Field(allow_inf_nan=False, ge=-1, le=MAX_MAGNITUDE)]
    min_distance_step: Step
    min_ttc: Magnitude | None = None
    collided: bool = False


class SimulationFacts(Strict):
    steps: Step
    timestep: Annotated[float, Field(allow_inf_nan=False, gt=0, le=MAX_TIMESTEP)]
    # Scenic's TerminationType name (e.g. timeLimit, terminatedByMonitor).
    termination_type: Annotated[str, StringConstraints(pattern=r"^\w{1,64}$")]
    termination_reason: Message
    agents: list[AgentTrace] = Field(max_length=MAX_AGENTS)
    collisions: list[Collision] = Field(
        default_factory=list, max_length=MAX_AGENTS * (MAX_AGENTS - 1) // 2
    )
    ego_pairs: list[EgoPairFacts] = Field(default_factory=list, max_length=MAX_AGENTS)
    events: list[Event] = Field(default_factory=list, max_length=MAX_EVENTS)
    # Global parameters of the scene that ran (weather, OPT_* values), as text.
    params: dict[Name, Message] = Field(default_factory=dict, max_length=MAX_PARAMS)
    # The ego's route (None: no ego, or no road network to read it from).
    route: EgoRoute | None = None
    # Who drove the ego: an agent spec (`idm`, `my_agent.py:Mine`); None: its script.
    agent: Annotated[str, StringConstraints(min_length=1, max_length=MAX_NAME)] | None = None
    # The map's traffic lights and stop signs, with every change of state.
    signals: list[SignalTrace] = Field(default_factory=list, max_length=MAX_SIGNALS)

    @model_validator(mode="after")
    def _bounded_in_total(self) -> SimulationFacts:
        """Per-agent bounds alone would still allow 256 x 20,001 points."""
        total = sum(len(agent.trajectory) for agent in self.agents)
        if total > MAX_TOTAL_POINTS:
            raise ValueError(
                f"the trace holds {total} trajectory points; the limit is {MAX_TOTAL_POINTS}"
            )
        return self


class CheckOptions(BaseModel):
    """What to check and how hard; the defaults suit a laptop, offline."""

    simulator: Simulator = Simulator.OFFLINE
    map_dir: str | None = None
    steps: Annotated[int, Field(ge=1, le=MAX_STEPS)] = 300
    spawn_attempts: int = 15
    sample_iterations: int = 500
    seed: int | None = None
    timeout: float = 60.0
    memory_mb: int = 1536
    png: str | None = None
    carla_host: str = "127.0.0.1"
    carla_port: int = 2000
    carla_timeout: float = 5.0
    # Refuse to run a script when any confinement mechanism is missing.
    require_sandbox: bool = False
    # Skip the static gate (tests use it to prove the OS-level confinement holds alone).
    static_gate: bool = True
    # Who drives the ego: None (or "scripted") the script's own behavior; a built-in
    # (`idm`, `cautious`, `blind`), `path/to/agent.py:ClassName` or an entry point of
    # the `arise.agents` group (docs/agents.md).
    agent: str | None = None


class WorkerResult(Strict):
    """What the parent takes from a worker's result: the facts of the check, validated.

    Never where the check ran or what it wrote: the map, the world model, the script's
    name and the picture's path come from the request the parent made, because a script
    that forges its result line could name any file there.
    """

    diagnostic: Diagnostic | None = None
    warnings: Notes = Field(default_factory=list)
    timings: dict[Name, Magnitude] = Field(default_factory=dict, max_length=MAX_TIMINGS)
    spawn_attempts_used: Count = 0
    sample_iterations_used: Count = 0
    simulation: SimulationFacts | None = None
    simulation_rejections: list[Rejection] = Field(default_factory=list, max_length=MAX_REJECTIONS)
    # Stamped by the pool from the worker's first message, sent before any script ran.
    sandbox: SandboxReport | None = None


#: Fields of a worker's result the parent ignores and fills from its own request.
PARENT_FIELDS = ("ok", "script", "map", "model", "png", "png_data")


class CheckResult(BaseModel):
    ok: bool
    script: str
    diagnostic: Diagnostic | None = None
    map: MapChoice | None = None
    model: str | None = None
    warnings: list[str] = Field(default_factory=list)
    timings: dict[str, float] = Field(default_factory=dict)
    spawn_attempts_used: int = 0
    sample_iterations_used: int = 0
    simulation: SimulationFacts | None = None
    # Simulations rejected (and re-sampled) before the one that ran, e.g. a `require always`
    # that failed for some scenes: a script may pass yet be fragile.
    simulation_rejections: list[Rejection] = Field(default_factory=list)
    png: str | None = None
    # The confinement the script ran under (None: it never reached a worker).
    sandbox: SandboxReport | None = None

    def summary(self) -> str:
        if self.ok and self.simulation is not None:
            sim = self.simulation
            return (
                f"OK: {sim.steps} steps, {len(sim.agents)} agents, "
                f"ended by {sim.termination_type} ({sim.termination_reason})"
            )
        assert self.diagnostic is not None
        return f"FAILED at {self.diagnostic.one_line()}"
