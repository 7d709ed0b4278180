"""Plain data passed across the validator's boundaries (worker <-> caller <-> CLI).

Everything here is JSON-serialisable with `model_dump()`, so a result can be written to a
report, sent over a pipe or compared in a test.
"""

from __future__ import annotations

from enum import StrEnum

from pydantic import BaseModel, Field

from arise.maps.choice import MapChoice
from arise.vocabulary import Side

__all__ = ["MapChoice"]  # re-exported: results carry the registry's choice


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


class SandboxReport(BaseModel):
    """Which confinement a script ran under: every result carries one."""

    active: list[Mechanism] = Field(default_factory=list)
    missing: list[Mechanism] = Field(default_factory=list)
    landlock_abi: int = 0
    notes: list[str] = Field(default_factory=list)

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


class Rejection(BaseModel):
    """One reason Scenic threw away samples, with how often and where."""

    reason: str
    count: int
    line: int | None = None
    section: str | None = None
    code: str | None = None


class Diagnostic(BaseModel):
    """Why a script did not execute, precise enough to repair it."""

    stage: Stage
    error_type: str
    message: str
    line: int | None = None
    column: int | None = None
    section: str | None = None
    excerpt: str | None = None
    hint: str | None = None
    rejections: list[Rejection] = Field(default_factory=list)

    def one_line(self) -> str:
        where = f" line {self.line}" if self.line else ""
        section = f" [{self.section}]" if self.section else ""
        return f"{self.stage.value}{where}{section}: {self.error_type}: {self.message}"


class TracePoint(BaseModel):
    step: int
    x: float
    y: float
    heading: float
    speed: float


class LaneChange(BaseModel):
    """One move of an agent's centre into a neighbouring lane, read from the road network."""

    step: int
    side: Side  # seen in the agent's direction of travel
    # The lane entered runs against the agent's direction of travel (an overtaking or
    # bypassing car in the oncoming lane); False for a move back from it or within its group.
    into_opposite: bool = False
    # The lane left ran against the agent's direction of travel (the way back).
    from_opposite: bool = False


class AgentTrace(BaseModel):
    name: str
    kind: str
    blueprint: str | None = None
    width: float
    length: float
    is_ego: bool = False
    # The class name of the behavior it ran (`AdversaryBehavior` marks our adversary).
    behavior: str | None = None
    # Steps at which the agent was inside a junction of the map.
    intersection_steps: int = 0
    # Metres from its first position to the nearest junction (None: no road network).
    junction_gap: float | None = None
    # Moves into a neighbouring lane of the same road (None: no road network to tell).
    lane_changes: int | None = None
    # Every move across a lane boundary outside junctions, in order (same-direction lane
    # changes and moves into and out of the oncoming lanes).
    lane_change_log: list[LaneChange] = Field(default_factory=list)
    # Steps spent in a lane that runs against the agent's travel, outside junctions.
    opposite_lane_steps: int | None = None
    # It moved back across a lane boundary within a few seconds of crossing it, i.e. it
    # wove (a controller fault or an erratic driver), not a deliberate lane change.
    weaving: bool | None = None
    trajectory: list[TracePoint] = Field(default_factory=list)


class Collision(BaseModel):
    first: str
    second: str
    step: int
    time: float


class EgoPairFacts(BaseModel):
    """How close another agent came to the ego: the criticality numbers."""

    other: str
    min_distance: float
    min_distance_step: int
    min_ttc: float | None = None
    collided: bool = False


class SimulationFacts(BaseModel):
    steps: int
    timestep: float
    termination_type: str
    termination_reason: str
    agents: list[AgentTrace]
    collisions: list[Collision] = Field(default_factory=list)
    ego_pairs: list[EgoPairFacts] = Field(default_factory=list)
    events: list[dict[str, object]] = Field(default_factory=list)
    # Global parameters of the scene that ran (weather, OPT_* values), as text.
    params: dict[str, str] = Field(default_factory=dict)


class CheckOptions(BaseModel):
    """What to check and how hard; the defaults suit a laptop, offline."""

    simulator: Simulator = Simulator.OFFLINE
    map_dir: str | None = None
    steps: int = 300
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
