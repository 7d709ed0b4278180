"""The child process that runs checks: gate, parse, compile, sample, simulate.

It is started by `arise.validate.pool` in a private scratch folder with a scrubbed
environment, imports Scenic, then confines itself for good (`arise.validate.sandbox`:
Landlock, seccomp, rlimits) before it reads any script, and says in its first message
which confinement is active. Scripts arrive as text over a private pipe, are written into
the scratch folder and run from there; Scenic's own prints go to /dev/null. It reports
each stage as it enters it, so the parent can name the stage of a timeout, and stays warm
between checks.
"""

from __future__ import annotations

import _thread
import base64
import contextlib
import errno
import gc
import io
import json
import os
import random
import re
import select
import shutil
import signal
import sys
import tempfile
import threading
import time
import warnings
from collections.abc import Callable
from contextlib import redirect_stdout
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from arise.agents.loader import (
    AgentError,
    AgentFactory,
    AgentSpec,
    SpecKind,
    check_agent_spec,
    load_agent_factory,
)
from arise.agents.types import BuiltinAgent
from arise.errors import AriseError
from arise.limits import MAX_NAME
from arise.validate.diagnostics import (
    from_exception,
    locate,
    rejection_diagnostic,
    rejections_from_log,
)
from arise.validate.gate import Refusal, scan_tokens, scan_tree
from arise.validate.lanes import LaneReading, find_weaving, read_lanes
from arise.validate.lineage import ParentMark, recorded_parent
from arise.validate.protocol import (
    ChildDied,
    ProtocolError,
    Ready,
    Result,
    StageEntered,
    WorkerMessage,
    dump_message,
    parse_message,
)
from arise.validate.script_info import CARLA_MODEL, KNOWN_MODELS, ScriptInfo, read_script_info
from arise.validate.types import (
    AgentTrace,
    CheckOptions,
    CheckResult,
    Diagnostic,
    MapChoice,
    Mechanism,
    SandboxReport,
    SimulationFacts,
    Stage,
    TracePoint,
)

Emit = Callable[[WorkerMessage], None]
OFFLINE_MODEL = "arise.validate.worldmodel.model"
# Our own interrupt comes this long before the time limit (the parent kills KILL_GRACE
# after it): a loaded machine once needed more than the 5 s that 2.0 left.
SOFT_TIMEOUT_GRACE = 3.0
MESSAGE_LIMIT_BYTES = 64 * 1024 * 1024  # a child's message longer than this is a flood


class CheckTimeout(AriseError):
    """The check ran past its time limit; raised inside the script's code to get its line."""


class _Failed(AriseError):
    def __init__(self, diagnostic: Diagnostic):
        super().__init__(diagnostic.message)
        self.diagnostic = diagnostic


# --- once per worker --------------------------------------------------------------------
_VOCABULARY: list[str] = []
# The user's agent this worker imported before confinement (its canonical name), or why
# it could not: the script that runs later must not be able to reach the user's files.
_AGENTS: dict[str, AgentFactory] = {}
_AGENT_PROBLEMS: dict[str, str] = {}


def _preload_agent() -> None:
    """Import the user's agent the pool named (ARISE_WORKER_AGENT), while files may still
    be read; a failure is kept and becomes the diagnostic of every check that asks for it."""
    import arise.agents.builtin  # noqa: F401  (the built-ins, imported once)

    text = os.environ.get("ARISE_WORKER_AGENT", "").strip()
    if not text:
        return
    try:
        spec = check_agent_spec(text)
        _AGENTS[spec.text] = load_agent_factory(spec)
    except AgentError as error:
        _AGENT_PROBLEMS[text] = str(error)


def _agent_for(options: CheckOptions) -> tuple[str, AgentFactory] | None:
    """Who drives the ego in this check: None for the script's own behavior."""
    name = options.agent
    if name is None or name == BuiltinAgent.SCRIPTED.value:
        return None
    if name in {agent.value for agent in BuiltinAgent}:
        builtin = BuiltinAgent(name)
        return name, load_agent_factory(AgentSpec(SpecKind.BUILTIN, name, builtin=builtin))
    if name in _AGENTS:
        return name, _AGENTS[name]
    problem = _AGENT_PROBLEMS.get(name) or (
        f"agent '{name[:200]}' was not imported by this worker before confinement"
    )
    raise _Failed(
        Diagnostic(
            stage=Stage.SIMULATE,
            error_type="AgentError",
            message=problem,
            hint="the agent failed, not the script: fix the agent's file or class (a pool "
            "made by hand needs WorkerPool(agent=...) for a user's agent).",
        )
    )


def _warm_up() -> None:
    """Import Scenic once and patch it (`scenic_patches`), so each check pays only for
    itself; load what later checks read while files may still be written."""
    from arise.validate import scenic_patches

    scenic_patches.install()
    _VOCABULARY.extend(_build_vocabulary())
    # matplotlib's font list (built and cached on first use) and the world model's Python.
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.font_manager  # noqa: F401
    import matplotlib.pyplot  # noqa: F401

    import arise.validate.render  # noqa: F401
    import arise.validate.worldmodel.simulator  # noqa: F401

    _preload_agent()

    _import_verifai()
    from arise.validate import gate

    gate.warm()  # what the gate's names resolve to, read once and inherited by every check


def _import_verifai() -> None:
    """VerifAI, when installed, before confinement: scripts that declare `VerifaiRange`
    and friends have Scenic import it at compile time, and loading it (with the Ray it
    probes for) in every check would cost about half a second each."""
    import importlib.util

    if importlib.util.find_spec("verifai") is None:
        return
    with contextlib.suppress(Exception):  # a broken install shows up in the check itself
        import verifai.features  # noqa: F401
        import verifai.server  # noqa: F401


def _build_vocabulary() -> list[str]:
    """Names a script may use, for 'did you mean' hints on NameErrors."""
    import scenic.domains.driving as driving
    import scenic.syntax.veneer as veneer

    import arise.validate.worldmodel as worldmodel

    names: set[str] = set(getattr(veneer, "__all__", ()))
    pattern = re.compile(r"^\s*(?:class|behavior|def|monitor|scenario)\s+(\w+)", re.M)
    assignment = re.compile(r"^(\w+)\s*(?::[^=]*)?=", re.M)
    for folder in (Path(worldmodel.__file__).parent, Path(driving.__file__).parent):
        for source in folder.glob("*.scenic"):
            text = source.read_text(encoding="utf-8")
            names.update(pattern.findall(text))
            names.update(assignment.findall(text))
        for source in folder.glob("*.py"):
            names.update(pattern.findall(source.read_text(encoding="utf-8")))
    return sorted(n for n in names if not n.startswith("_"))


# --- one check ---------------------------------------------------------------------------
class _Watchdog:
    """Interrupts the main thread shortly before the parent would kill us."""

    def __init__(self, seconds: float):
        self.fired = False
        self._timer = threading.Timer(max(0.5, seconds), self._fire)
        self._timer.daemon = True

    def _fire(self) -> None:
        self.fired = True
        _thread.interrupt_main()

    def __enter__(self) -> _Watchdog:
        self._timer.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._timer.cancel()


def _gate_and_parse(text: str, path: str, static_gate: bool = True) -> None:
    from scenic.core.errors import ScenicSyntaxError
    from scenic.syntax.compiler import compileScenicAST
    from scenic.syntax.parser import parse_string

    try:
        tree = parse_string(text, "exec", filename=path)
    except (ScenicSyntaxError, SyntaxError) as error:
        refusals = scan_tokens(text)
        if refusals:
            raise _Failed(_refusal(refusals, text)) from error
        raise
    refusals = scan_tree(tree) if static_gate else []
    if refusals:
        raise _Failed(_refusal(refusals, text))
    compileScenicAST(tree, filename=path)


def _refusal(refusals: list[Refusal], text: str) -> Diagnostic:
    first = refusals[0]
    others = "; ".join(str(r) for r in refusals[1:4])
    message = first.what + (f" (also {others})" if others else "")
    return Diagnostic(
        stage=Stage.GATE,
        error_type="ForbiddenConstruct",
        message=message,
        hint="scripts may not touch files, processes, the network or the "
        "interpreter; remove the construct.",
        **locate(text, first.line, first.column),
    )


def _model_problem(
    info: ScriptInfo, text: str, options: CheckOptions
) -> tuple[str | None, list[str]]:
    """Which model to compile with, and warnings about the script's own model line."""
    notes: list[str] = []
    if options.simulator == "carla":
        return None, notes
    if info.model is None:
        notes.append(
            "the script has no `model` line; it was checked with the CARLA model "
            "(add `model scenic.simulators.carla.model`)"
        )
    elif info.model not in KNOWN_MODELS:
        # Looked up without importing: find_spec('a.b') runs `a`, which can be the script
        # itself (its folder is on sys.path), before the gate has read it.
        from arise.validate.gate import module_exists

        if not module_exists(info.model):
            raise _Failed(
                Diagnostic(
                    stage=Stage.COMPILE,
                    error_type="ModuleNotFoundError",
                    message=f"world model '{info.model}' does not exist",
                    hint=f"use `model {CARLA_MODEL}`",
                    **locate(text, info.model_line),
                )
            )
        notes.append(
            f"the script's model is '{info.model}'; it was checked with arise's offline CARLA model"
        )
    elif info.model != CARLA_MODEL:
        notes.append(
            f"the script uses the {KNOWN_MODELS[info.model]} model "
            f"('{info.model}'); it was checked with arise's offline CARLA model"
        )
    return OFFLINE_MODEL, notes


def _agent_traces(simulation: Any) -> list[AgentTrace]:
    trajectory = simulation.result.trajectory
    counts: dict[str, int] = {}
    traces = []
    ego = simulation.scene.egoObject
    for index, obj in enumerate(simulation.objects):
        kind = type(obj).__name__
        counts[kind] = counts.get(kind, 0) + 1
        is_ego = obj is ego or getattr(obj, "_obj", None) is ego
        name = "ego" if is_ego else f"{kind}{counts[kind]}"
        points = [
            TracePoint(
                step=step,
                x=round(state[index][0], 3),
                y=round(state[index][1], 3),
                heading=round(state[index][2], 4),
                speed=round(state[index][3], 3),
            )
            for step, state in enumerate(trajectory)
            if index < len(state) and isinstance(state[index], tuple)
        ]
        blueprint = getattr(obj, "blueprint", None)
        behavior = getattr(obj, "behavior", None)
        driver = getattr(simulation, "arise_driver", None)
        if is_ego and driver is not None:
            behavior = driver.agent  # the agent drove; the script's behavior was off
        lanes = _lane_reading(simulation, points)
        traces.append(
            AgentTrace(
                name=name,
                kind=kind,
                blueprint=blueprint if isinstance(blueprint, str) else None,
                width=float(obj.width),
                length=float(obj.length),
                is_ego=is_ego,
                behavior=type(behavior).__name__ if behavior is not None else None,
                intersection_steps=_steps_in_junctions(simulation, points),
                junction_gap=_junction_gap(simulation, points),
                lane_changes=None if lanes is None else lanes.same_direction_changes,
                lane_change_log=[] if lanes is None else lanes.changes,
                opposite_lane_steps=None if lanes is None else lanes.opposite_steps,
                weaving=None
                if lanes is None
                else find_weaving(lanes.changes, float(simulation.timestep)),
                trajectory=points,
            )
        )
    return traces


def _network(simulation: Any) -> Any:
    """The road network of a driving scene, or None (a scene without a map)."""
    return getattr(getattr(simulation.scene, "workspace", None), "network", None)


def _steps_in_junctions(simulation: Any, points: list[TracePoint]) -> int:
    region = getattr(_network(simulation), "intersectionRegion", None)
    if region is None:
        return 0
    try:
        return sum(bool(region.containsPoint((p.x, p.y))) for p in points)
    except Exception:  # an odd region must not cost the facts of a run that worked
        return 0


def _junction_gap(simulation: Any, points: list[TracePoint]) -> float | None:
    """Metres from the first point to the nearest junction: a car waiting at the stop line
    is at the junction without ever entering it."""
    region = getattr(_network(simulation), "intersectionRegion", None)
    if region is None or not points:
        return None
    try:
        return round(float(region.distanceTo((points[0].x, points[0].y))), 2)
    except Exception:  # an odd region must not cost the facts of a run that worked
        return None


def _lane_reading(simulation: Any, points: list[TracePoint]) -> LaneReading | None:
    """Lane changes and oncoming-lane use read with the road network (None: no network,
    or one too odd to read: that must not cost the facts of a run that worked)."""
    network = _network(simulation)
    if network is None:
        return None
    try:
        return read_lanes(network, points)
    except Exception:
        return None


def _scene_params(scene: Any) -> dict[str, str]:
    params = {
        str(name): str(value)
        for name, value in dict(scene.params).items()
        if isinstance(value, str | int | float | bool)
    }
    weather = _weather_text(scene.params.get("weather"))
    if weather is not None:
        params["weather"] = weather
    return params


def _weather_text(value: Any) -> str | None:
    """A weather dict as the JSON object the parent reads back (`Weather.from_param_text`);
    None for anything but a small dict of names to numbers."""
    if not isinstance(value, dict) or len(value) > 32:
        return None
    if not all(
        isinstance(k, str)
        and len(k) <= 64
        and isinstance(v, int | float)
        and not isinstance(v, bool)
        for k, v in value.items()
    ):
        return None
    return json.dumps({k: float(v) for k, v in value.items()})


def _simulation_facts(simulation: Any) -> SimulationFacts:
    from arise.validate.facts import ego_pair_facts, find_collisions

    agents = _agent_traces(simulation)
    events = [dict(e) for e in getattr(simulation, "arise_events", [])]
    result = simulation.result
    steps = max(0, len(result.trajectory) - 1)
    driver = getattr(simulation, "arise_driver", None)
    signals = getattr(simulation, "arise_signals", None)
    return SimulationFacts(
        steps=steps,
        timestep=float(simulation.timestep),
        termination_type=str(result.terminationType.name),
        termination_reason=str(result.terminationReason),
        agents=agents,
        collisions=find_collisions(agents, float(simulation.timestep)),
        ego_pairs=ego_pair_facts(agents),
        events=events,
        params=_scene_params(simulation.scene),
        route=getattr(simulation, "arise_route", None),
        agent=driver.name[-MAX_NAME:] if driver is not None else None,  # the parent renames it
        signals=signals.traces(steps) if signals is not None else [],
    )


def _fresh_scratch(scratch: Path, name: str, text: str) -> str:
    """Empty the scratch folder and put the script in it; returns the path to run."""
    for entry in scratch.iterdir():
        if entry.is_dir() and not entry.is_symlink():
            shutil.rmtree(entry, ignore_errors=True)
        else:
            entry.unlink(missing_ok=True)
    folder = scratch / "script"
    folder.mkdir()
    path = folder / (Path(name).name or "scenario.scenic")
    path.write_text(text, encoding="utf-8")
    return str(path)


def _sandbox_hint(error: BaseException) -> str | None:
    """A refusal by the OS-level confinement, said as such."""
    if isinstance(error, RuntimeError) and "can't start new thread" in str(error):
        return (
            "the sandbox refused this: a script may run only a few threads; remove the construct."
        )
    if isinstance(error, OSError) and error.errno in (
        errno.EPERM,
        errno.EACCES,
        errno.ENOSYS,
        errno.EFBIG,
        errno.ENOSPC,
    ):
        return (
            "the sandbox refused this: scripts run confined and may not read the user's "
            "files, write outside their scratch folder, open network connections or "
            "start programs; remove the construct."
        )
    return None


def run_check(request: dict[str, Any], emit: Emit, scratch: Path) -> CheckResult:
    """One check, from text to facts. Errors come back as a Diagnostic, never raised."""
    options = CheckOptions.model_validate(request["options"])
    text = str(request["text"])
    path = _fresh_scratch(scratch, str(request.get("name") or "scenario.scenic"), text)
    if options.png:
        options = options.model_copy(update={"png": str(scratch / "scene.png")})
    map_choice = MapChoice.model_validate(request["map"]) if request.get("map") else None
    info = read_script_info(text)
    result = CheckResult(ok=False, script=path, map=map_choice, model=info.model)
    timings = result.timings
    stage = Stage.GATE

    def enter(next_stage: Stage) -> float:
        nonlocal stage
        stage = next_stage
        emit(StageEntered(stage=next_stage))
        return time.perf_counter()

    seed = options.seed if options.seed is not None else random.randrange(2**31)
    random.seed(seed)
    import numpy

    numpy.random.seed(seed % 2**32)
    try:
        with _Watchdog(options.timeout - SOFT_TIMEOUT_GRACE) as watchdog:
            try:
                _run_stages(path, text, info, options, map_choice, result, enter, timings)
            except KeyboardInterrupt as interrupt:
                if not watchdog.fired:
                    raise
                timeout = CheckTimeout(
                    f"the check ran longer than {options.timeout:g} s (in the {stage.value} stage)"
                )
                timeout.__traceback__ = interrupt.__traceback__
                diagnostic = from_exception(timeout, stage, text, path, info, _VOCABULARY)
                diagnostic.hint = (
                    "an endless loop or a very slow computation; make loops "
                    "`wait` or `take` an action each step, or raise --timeout."
                )
                raise _Failed(diagnostic) from None
    except _Failed as failure:
        result.diagnostic = failure.diagnostic
    except AgentError as error:  # the user's agent failed (raised, bad control): not the script
        result.diagnostic = Diagnostic(
            stage=stage,
            error_type="AgentError",
            message=str(error),
            hint="the agent failed, not the script: fix the agent.",
        )
    except MemoryError as error:
        result.diagnostic = from_exception(error, stage, text, path, info, _VOCABULARY)
        result.diagnostic.message = (
            f"the script exceeded the memory limit of {options.memory_mb} MB"
        )
    except Exception as error:  # noqa: BLE001  (any script failure becomes a Diagnostic)
        stage_of_error = Stage.PARSE if _is_syntax_error(error) else stage
        result.diagnostic = from_exception(error, stage_of_error, text, path, info, _VOCABULARY)
        result.diagnostic.hint = _sandbox_hint(error) or result.diagnostic.hint
    result.ok = result.diagnostic is None and result.simulation is not None
    return result


def _is_syntax_error(error: BaseException) -> bool:
    from scenic.core.errors import ScenicSyntaxError

    return isinstance(error, (ScenicSyntaxError, SyntaxError))


def _run_stages(
    path: str,
    text: str,
    info: ScriptInfo,
    options: CheckOptions,
    map_choice: MapChoice | None,
    result: CheckResult,
    enter: Callable[[Stage], float],
    timings: dict[str, float],
) -> None:
    import scenic
    from scenic.core.distributions import RejectionException
    from scenic.core.simulators import SimulationCreationError

    started = enter(Stage.GATE)
    agent = _agent_for(options)
    model, notes = _model_problem(info, text, options)
    result.warnings.extend(notes)
    if map_choice is not None and map_choice.substituted and map_choice.reason:
        result.warnings.append(map_choice.reason)
    _gate_and_parse(text, path, options.static_gate)
    timings["gate+parse"] = round(time.perf_counter() - started, 3)

    started = enter(Stage.COMPILE)
    params: dict[str, Any] = {}
    if map_choice is not None:
        params["map"] = map_choice.path
        params["carla_map"] = map_choice.name
    if options.simulator == "carla":
        params.update(
            address=options.carla_host,
            port=options.carla_port,
            timeout=int(max(1, options.carla_timeout)),
        )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        from scenic.core.dynamics import StuckBehaviorWarning

        warnings.simplefilter("error", StuckBehaviorWarning)
        scenario = scenic.scenarioFromFile(path, params=params, model=model, mode2D=True)
    result.warnings.extend(_useful_warnings(caught))
    timings["compile"] = round(time.perf_counter() - started, 3)

    rejected_sims: list[str] = []
    simulator = None
    for attempt in range(1, options.spawn_attempts + 1):
        result.spawn_attempts_used = attempt
        started = enter(Stage.SAMPLE)
        log = io.StringIO()
        try:
            with redirect_stdout(log):
                scene, iterations = scenario.generate(
                    maxIterations=options.sample_iterations, verbosity=2
                )
        except RejectionException as error:
            rejections = rejections_from_log(log.getvalue(), text)
            result.sample_iterations_used += options.sample_iterations
            raise _Failed(
                rejection_diagnostic(
                    Stage.SAMPLE,
                    f"no scene satisfied the requirements in "
                    f"{options.sample_iterations} samples ({error})",
                    rejections,
                    text,
                    options.sample_iterations,
                )
            ) from None
        result.sample_iterations_used += iterations
        timings["sample"] = round(timings.get("sample", 0) + time.perf_counter() - started, 3)

        started = enter(Stage.SIMULATE)
        if simulator is None:
            simulator = scenario.getSimulator()
            if agent is not None and hasattr(simulator, "arise_agent"):
                simulator.arise_agent = agent
        log = io.StringIO()
        try:
            with redirect_stdout(log):
                simulation = simulator.simulate(scene, maxSteps=options.steps, verbosity=2)
        except SimulationCreationError as error:
            rejected_sims.append(f"Rejected simulation {attempt} because: spawn failed: {error}")
            continue
        finally:
            timings["simulate"] = round(
                timings.get("simulate", 0) + time.perf_counter() - started, 3
            )
        if simulation is None:
            rejected_sims.extend(
                line for line in log.getvalue().splitlines() if "Rejected simulation" in line
            )
            continue
        result.simulation = _simulation_facts(simulation)
        result.simulation_rejections = rejections_from_log("\n".join(rejected_sims), text)
        if options.png:
            started = time.perf_counter()
            from arise.validate.render import draw_scene

            title = f"{Path(path).name} on {map_choice.name if map_choice else '?'}"
            result.png = draw_scene(
                getattr(scene.workspace, "network", None),
                result.simulation.agents,
                options.png,
                title,
                result.simulation.collisions,
                result.simulation.timestep,
            )
            timings["png"] = round(time.perf_counter() - started, 3)
        simulator.destroy()
        return
    if simulator is not None:
        simulator.destroy()
    rejections = rejections_from_log("\n".join(rejected_sims), text)
    raise _Failed(
        rejection_diagnostic(
            Stage.SIMULATE,
            f"every one of {options.spawn_attempts} simulations was rejected",
            rejections,
            text,
            options.spawn_attempts,
        )
    )


def _useful_warnings(caught: list[warnings.WarningMessage]) -> list[str]:
    seen = []
    for warning in caught:
        message = str(warning.message)
        if "carla" in message and "package is not installed" in message:
            continue
        if message not in seen:
            seen.append(message)
    return seen[:10]


# --- process entry point -------------------------------------------------------------------
def _connect_ports() -> tuple[int, ...]:
    return tuple(
        int(p) for p in os.environ.get("ARISE_WORKER_CONNECT_PORTS", "").split(",") if p.strip()
    )


def _confined() -> bool:
    return os.environ.get("ARISE_WORKER_CONFINE", "1") != "0"


def _enter_namespaces(scratch: Path) -> str | None:
    """First thing the worker does, while it is still one thread: its own namespaces."""
    if not _confined():
        return "namespaces: confinement turned off by the caller"
    from arise.validate.sandbox import enter_namespaces

    size = int(os.environ.get("ARISE_WORKER_SCRATCH_BYTES", str(256 * 1024 * 1024)))
    problem = enter_namespaces(scratch, size, network=bool(_connect_ports()))
    return f"namespaces: {problem}" if problem else None


def _confine(scratch: Path, namespace_problem: str | None) -> SandboxReport:
    import dataclasses

    from arise.validate.sandbox import confine, python_policy

    memory_mb = int(os.environ.get("ARISE_WORKER_MEMORY_MB", "0"))
    policy = dataclasses.replace(
        python_policy(scratch, memory_mb=memory_mb, connect_ports=_connect_ports()),
        allow_fork=True,
        in_namespaces=namespace_problem is None,
    )
    if not _confined():
        import resource

        if policy.memory_bytes:
            resource.setrlimit(resource.RLIMIT_AS, (policy.memory_bytes, policy.memory_bytes))
        return SandboxReport(
            missing=list(Mechanism),
            notes=["confinement turned off by the caller (benchmarks only)"],
        )
    report = confine(policy)
    if namespace_problem:
        report.notes.append(namespace_problem)
    report.notes.append(
        "each script runs in a fresh child process that cannot start "
        "processes; nothing it changes outlives its check"
    )
    return report


# --- the fork server ------------------------------------------------------------------------
PRIME_SCRIPT = """param map = localPath('prime.xodr')
model scenic.simulators.carla.model
ego = new Car on road, with behavior FollowLaneBehavior(target_speed=5)
"""


def _prime() -> None:
    """Compile and sample one script of ours before confinement, so that the parsed world
    model and driving domain are in memory that every child inherits."""
    import scenic

    from arise.maps.registry import MapRegistry
    from arise.validate.map_cache import prepare_map

    choice = MapRegistry(None).resolve("arise_straight")
    prepare_map(Path(choice.path))
    scenario = scenic.scenarioFromString(
        PRIME_SCRIPT,
        params={"map": choice.path, "carla_map": choice.name},
        model=OFFLINE_MODEL,
        mode2D=True,
    )
    scenario.generate(maxIterations=50)


def _preload_map(request: dict[str, Any]) -> None:
    """Load the map the parent chose into the fork server's memo before forking (the
    file is the parent's choice and its .snet the parent's preparation: no script data)."""
    from scenic.domains.driving.roads import Network

    path = (request.get("map") or {}).get("path")
    if path:
        with contextlib.suppress(Exception):
            Network.fromFile(path)


@dataclass
class _Relayed:
    """What came from a child: whether a result did, and whether it broke the protocol."""

    result: bool = False
    garbled: bool = False  # a line that was not one of our messages
    flooded: bool = False  # more than a message may hold without a newline


def _relay(read_fd: int, emit: Emit) -> _Relayed:
    """Pass a child's stage and result messages on, and note anything else it wrote."""
    seen = _Relayed()
    buffer = bytearray()
    with os.fdopen(read_fd, "rb") as stream:
        while chunk := stream.read1(1 << 20):
            start = len(buffer)
            buffer += chunk
            if buffer.find(b"\n", start) < 0:
                if len(buffer) > MESSAGE_LIMIT_BYTES:
                    seen.flooded = True
                    return seen
                continue
            *lines, rest = bytes(buffer).split(b"\n")
            buffer = bytearray(rest)
            for line in lines:
                try:
                    message = parse_message(line)
                except ProtocolError:
                    seen.garbled = True
                    continue
                # A child says only stages, then one result; a `ready` or `child_died` of its
                # own, or anything after its result, is forged.
                if isinstance(message, StageEntered) and not seen.result:
                    emit(message)
                elif isinstance(message, Result) and not seen.result:
                    emit(message)
                    seen.result = True
                else:
                    seen.garbled = True
    return seen


def _child(request: dict[str, Any], write_fd: int, scratch: Path, closing: list[int]) -> None:
    """In the forked child: drop the server's channels, forbid processes, run the check."""
    for fd in closing:
        with contextlib.suppress(OSError):
            os.close(fd)
    if _confined():
        from arise.validate.sandbox import isolate_child

        isolate_child()
    channel = os.fdopen(write_fd, "w", buffering=1, encoding="utf-8")

    def emit(message: WorkerMessage) -> None:
        channel.write(dump_message(message))
        channel.flush()

    result = run_check(request, emit, scratch)
    payload = result.model_dump(mode="json")
    if result.png:
        payload["png_data"] = base64.b64encode(Path(result.png).read_bytes()).decode()
    emit(Result(result=payload))


def _serve_one(request: dict[str, Any], emit: Emit, scratch: Path, private_fds: list[int]) -> None:
    """Run one check in a fresh child; `private_fds` (requests, results, the parent's
    pidfd) are closed in it."""
    read_fd, write_fd = os.pipe()
    server = os.getpid()
    # Move everything the server holds out of the collector's reach, so the child's
    # collections do not write to (and so copy) every inherited page: ~0.2 s per check.
    gc.freeze()
    pid = os.fork()
    if pid == 0:
        try:
            _die_with(server)  # before isolate_child: the script may not undo it
            os.close(read_fd)
            _child(request, write_fd, scratch, private_fds)
        finally:
            os._exit(0)
    os.close(write_fd)
    seen = _relay(read_fd, emit)
    if seen.flooded:
        os.kill(pid, signal.SIGKILL)  # a nested domain may be signalled from outside
    _, status = os.waitpid(pid, 0)
    if not seen.result:
        code = -os.WTERMSIG(status) if os.WIFSIGNALED(status) else os.WEXITSTATUS(status)
        emit(ChildDied(code=code, flooded=seen.flooded, garbled=seen.garbled))


# --- dying with the parent --------------------------------------------------------------------
_PR_SET_PDEATHSIG = 1  # prctl(2), include/uapi/linux/prctl.h
_LIBC: Any = None


def _libc() -> Any:
    """The C library, loaded while the server may still open files (children reuse it)."""
    global _LIBC
    if _LIBC is None:
        import ctypes

        _LIBC = ctypes.CDLL(None, use_errno=True)
    return _LIBC


def _die_with(parent_pid: int) -> None:
    """SIGKILL this process when the thread that started it ends (prctl PDEATHSIG); exit
    now if the parent is already gone (we were reparented before the call)."""
    _libc().prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    if os.getppid() != parent_pid:
        os._exit(1)


@dataclass
class _Parent:
    """The process that started this worker (`--parent`), and a pidfd to watch it by."""

    mark: ParentMark
    pidfd: int | None
    death_signal: bool  # the parent started us from its main thread: PDEATHSIG is exact


def _hold_on_to_parent() -> _Parent | None:
    """First thing, still unconfined: whose worker this is, a pidfd of that process, and
    the kernel's parent-death signal when the parent asked for it. A worker started by
    hand records no parent and watches none."""
    _libc()
    mark = recorded_parent(sys.argv[1:])
    if mark is None:
        return None
    parent = _Parent(mark, None, os.environ.get("ARISE_WORKER_PDEATHSIG") == "1")
    with contextlib.suppress(OSError, AttributeError):  # pidfd_open: Linux >= 5.3
        parent.pidfd = os.pidfd_open(mark.pid)
    if parent.death_signal:
        _die_with(mark.pid)
    elif os.getppid() != mark.pid:  # gone before the pidfd was opened: not ours to watch
        os._exit(1)
    return parent


def _watch_parent(parent: _Parent) -> None:
    """Kill this worker's process group (the script's child with it) the moment the
    parent is gone: its pidfd turns readable when it exits, and the request pipe hangs
    up when its last writer closes. A thread started once confined, so Landlock covers
    it too; it needs only poll and kill."""
    poller = select.poll()
    poller.register(0, 0)  # no events asked: only a hang-up or an error, nothing is read
    if parent.pidfd is not None:
        poller.register(parent.pidfd, select.POLLIN)
    gone = select.POLLHUP | select.POLLERR | select.POLLNVAL

    def watch() -> None:
        while not any(fd == parent.pidfd or flags & gone for fd, flags in poller.poll()):
            pass
        if os.getpgrp() == os.getpid():  # the pool starts us as a session leader
            with contextlib.suppress(OSError):
                os.killpg(0, signal.SIGKILL)
        os._exit(1)  # a child left behind gets its parent-death signal

    threading.Thread(target=watch, name="arise-parent-watch", daemon=True).start()


def main() -> None:
    parent = _hold_on_to_parent()
    protocol = os.fdopen(os.dup(1), "w", buffering=1, encoding="utf-8")
    sink = os.open(os.devnull, os.O_WRONLY)
    os.dup2(sink, 1)
    if os.environ.get("ARISE_WORKER_STDERR") != "1":
        os.dup2(sink, 2)

    def emit(message: WorkerMessage) -> None:
        protocol.write(dump_message(message))
        protocol.flush()

    # Started by hand (to see why a worker fails): a scratch folder of its own.
    scratch = Path(
        os.environ.get("ARISE_WORKER_SCRATCH") or tempfile.mkdtemp(prefix="arise-worker-")
    )
    namespace_problem = _enter_namespaces(scratch)
    if parent is not None and parent.death_signal:
        _die_with(parent.mark.pid)  # again: a changed identity would clear it
    os.chdir(scratch)  # the tmpfs now mounted there, not the folder beneath it
    _warm_up()
    _prime()
    sandbox = _confine(scratch, namespace_problem)
    private = [0, protocol.fileno()]
    if parent is not None:
        _watch_parent(parent)
        if parent.pidfd is not None:
            private.append(parent.pidfd)
    emit(Ready(pid=os.getpid(), sandbox=sandbox))
    for line in sys.stdin:
        if not line.strip():
            continue
        request = json.loads(line)
        _preload_map(request)
        _serve_one(request, emit, scratch, private)


if __name__ == "__main__":
    main()
