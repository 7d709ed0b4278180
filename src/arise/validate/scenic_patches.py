"""Every change arise makes to Scenic's internals, in one place, and why.

The validator runs inside Scenic 3.1 (`scenic>=3.1.1,<3.2` in pyproject.toml, pinned
because of the patches below). Each patch is installed once per worker by `install()`.
`check_shapes()` verifies that the internals still look as the patches expect; the
worker calls it before patching and `tests/validate/test_scenic_coupling.py` calls it in
CI, so a Scenic release that moves them fails loudly instead of silently giving wrong
traces. docs/architecture.md says what moving to Scenic 3.2 would take.

1. `Network.fromFile` (scenic.domains.driving.roads): memoised per worker, keyed by the
   map's path, mtime and options; and always called with `writeCache=False`.
   Why: loading a map's `.snet` costs 0.1-0.7 s per compile; a confined worker may not
   write beside the map, and a pickle written by a process that ran a script must not be
   trusted (`map_cache.py` prepares it instead).
   Breaks if: the classmethod's name or its `(path, useCache, writeCache, **kwargs)`
   parameters change: maps would be re-parsed each check (slow) or the call would fail.

2. `Simulation.currentState` (scenic.core.simulators): returns, per object,
   `(x, y, heading, speed)`. Scenic records `currentState()` after every step into
   `result.trajectory`; by default it holds positions only.
   Why: the trace facts (headings, speeds, TTC, lanes) need heading and speed per step.
   Breaks if: Scenic stops recording `currentState()` into the trajectory or changes
   what the trajectory holds (Scenic 3.2 does): traces would lose heading and speed, and
   `worker._agent_traces` would misread them.

3. `translator.parse_string` and `translator.compileScenicAST`
   (scenic.syntax.translator): Scenic and world-model modules are parsed and translated
   once per worker; user scripts are always parsed afresh.
   Why: parsing the world model's Scenic source dominates compile time (~1.5 s -> ~0.3 s).
   Breaks if: the translator stops calling these two module-level functions by name, or
   changes their signatures: compiles get slower (first case) or fail (second).

4. `scenic.core.dynamics.stuckBehaviorWarningTimeout`: lowered to a few seconds, and
   `StuckBehaviorWarning` is turned into an error.
   Why: a behavior that loops without taking an action hangs forever; Scenic's own
   SIGALRM handler means an alarm in-process does not fire.
   Breaks if: the module global is renamed: endless loops are then caught only by the
   wall-clock timeout.

5. VerifAI parameters with weights under the cross-entropy sampler
   (scenic.core.external_params): `VerifaiDiscreteRange` keeps its `low` and `high`, and
   the module's `numpy.array` accepts rows of different lengths (as a list of rows).
   Why: when a script gives a VerifAI parameter weights or buckets (or uses
   `VerifaiParameter.withPrior`, or `VerifaiOptions` with weights) and sets
   `param verifaiSamplerType = 'ce'`, Scenic 3.1.1 reads `param.high - param.low`, which
   the class never stored, and builds one array from per-parameter bucket rows of
   different lengths, which numpy >= 1.24 refuses: such scripts fail to compile, with
   or without arise. The rows are what VerifAI's sampler iterates over, so a list of rows
   is what it needs.
   Breaks if: `VerifaiDiscreteRange.__init__` stops taking `(low, high, weights)` or the
   module stops importing numpy as `numpy`: those scripts fail to compile again.

6. `RegulatedControlAction` (scenic.domains.driving.actions): replaced by the world
   model's `BrakingRegulatedControlAction`, a subclass that brakes on a negative signal
   when the simulation is the offline one, and is Scenic's own action anywhere else.
   Why: Scenic 3.1 zeroes the throttle before it computes the brake from it, so the
   driving behaviors could never brake, and with no drag offline a car could not slow
   for a curve or a turn. The driving behaviors are Scenic modules, executed afresh at
   each compile; they take the action by name from this Python module, so they find the
   subclass.
   Breaks if: the action's `(throttle, steer, past_steer, max_throttle, max_brake,
   max_steer)` parameters change, or the behaviors stop naming it: the offline cars coast
   again instead of braking (the check below catches the first).
"""

from __future__ import annotations

import inspect
import os
import warnings
from pathlib import Path
from typing import Any

from arise.errors import AriseError

STUCK_BEHAVIOR_SECONDS = 3  # a behavior step this long without an action is a bug
# Parsed maps kept per worker, budgeted by OpenDRIVE file size: a CARLA town (1-3.5 MB of
# XML) costs ~30-100 MB parsed; our own maps (< 40 kB) almost nothing.
NETWORK_CACHE_BYTES = 4_000_000

REGULATED_CONTROL_PARAMETERS = (
    "self",
    "throttle",
    "steer",
    "past_steer",
    "max_throttle",
    "max_brake",
    "max_steer",
)

_NETWORK_CACHE: dict[tuple[Any, ...], Any] = {}


class ScenicChanged(AriseError):
    """Scenic's internals no longer look as arise's patches expect (an installation problem:
    the pinned Scenic 3.1 line was replaced), so no worker may run with half the patches."""


def check_shapes() -> list[str]:
    """What no longer matches, as sentences (empty when every patch still fits)."""
    from importlib.metadata import version as installed_version

    import scenic.core.dynamics as dynamics
    import scenic.core.simulators as simulators
    import scenic.syntax.translator as translator
    from scenic.domains.driving.roads import Network

    problems = []
    release = installed_version("scenic")
    if tuple(int(p) for p in release.split(".")[:2] if p.isdigit()) >= (3, 2):
        problems.append(f"Scenic {release} is newer than the 3.1 line the patches were written for")
    from_file = inspect.getattr_static(Network, "fromFile", None)
    if not isinstance(from_file, classmethod):
        problems.append("Network.fromFile is no longer a classmethod")
    else:
        names = list(inspect.signature(from_file.__func__).parameters)
        if names[:4] != ["cls", "path", "useCache", "writeCache"]:
            problems.append(
                f"Network.fromFile takes {names}, not (cls, path, useCache, writeCache, **kwargs)"
            )
    if not callable(getattr(simulators.Simulation, "currentState", None)):
        problems.append("Simulation.currentState is gone")
    elif "self.currentState()" not in inspect.getsource(simulators.Simulation):
        problems.append("Simulation no longer records currentState() into its trajectory")
    for name in ("parse_string", "compileScenicAST"):
        if not callable(getattr(translator, name, None)):
            problems.append(f"scenic.syntax.translator.{name} is gone")
        elif f"{name}(" not in inspect.getsource(translator).replace(f"def {name}(", ""):
            problems.append(f"the translator no longer calls {name} by name")
    if not hasattr(dynamics, "stuckBehaviorWarningTimeout"):
        problems.append("scenic.core.dynamics.stuckBehaviorWarningTimeout is gone")
    import scenic.core.external_params as external

    names = list(inspect.signature(external.VerifaiDiscreteRange.__init__).parameters)
    if names[:4] != ["self", "low", "high", "weights"]:
        problems.append(f"VerifaiDiscreteRange takes {names}, not (self, low, high, weights)")
    shim = getattr(external, "numpy", None)
    if shim is not _numpy_module() and not isinstance(shim, _RaggedNumpy):
        problems.append("scenic.core.external_params no longer imports numpy as `numpy`")
    import scenic.domains.driving.actions as driving_actions

    names = list(inspect.signature(driving_actions.RegulatedControlAction.__init__).parameters)
    if names != list(REGULATED_CONTROL_PARAMETERS):
        problems.append(f"RegulatedControlAction takes {names}, not {REGULATED_CONTROL_PARAMETERS}")
    return problems


def install() -> None:
    """Install the six patches (once per worker process)."""
    problems = check_shapes()
    if problems:
        raise ScenicChanged("; ".join(problems))
    _memoise_networks()
    _trace_heading_and_speed()
    _memoise_library_parsing()
    _stop_stuck_behaviors()
    _verifai_weights_under_cross_entropy()
    _brake_in_regulated_control()


def _memoise_networks() -> None:
    from scenic.domains.driving.roads import Network

    original = Network.fromFile.__func__

    def cached_from_file(
        cls: Any, path: Any, useCache: bool = True, writeCache: bool = True, **kwargs: Any
    ) -> Any:
        resolved = os.path.realpath(str(path))
        try:
            stamp = os.stat(resolved).st_mtime_ns
        except OSError:
            stamp = None
        key = (resolved, stamp, repr(sorted(kwargs.items())))
        entry = _NETWORK_CACHE.pop(key, None)
        if entry is None:
            size = os.path.getsize(resolved) if stamp is not None else 0
            entry = (original(cls, path, useCache=useCache, writeCache=False, **kwargs), size)
        _NETWORK_CACHE[key] = entry  # most recently used last
        while (
            len(_NETWORK_CACHE) > 1
            and sum(size for _, size in _NETWORK_CACHE.values()) > NETWORK_CACHE_BYTES
        ):
            del _NETWORK_CACHE[next(iter(_NETWORK_CACHE))]
        return entry[0]

    Network.fromFile = classmethod(cached_from_file)


def _trace_heading_and_speed() -> None:
    import scenic.core.simulators as simulators

    def trace_state(self: Any) -> tuple[tuple[float, float, float, float], ...]:
        return tuple(
            (float(o.position.x), float(o.position.y), float(o.heading), float(o.speed or 0.0))
            for o in self.objects
        )

    simulators.Simulation.currentState = trace_state


def _memoise_library_parsing() -> None:
    import scenic.syntax.translator as translator

    import arise

    parse = translator.parse_string
    translate = translator.compileScenicAST
    library_roots = (str(Path(translator.__file__).parents[1]), str(Path(arise.__file__).parent))
    translated: dict[tuple[str, str], Any] = {}

    class _Known:
        def __init__(self, key: tuple[str, str]):
            self.key = key

    def parse_string(
        source: str, mode: str, *args: Any, filename: str = "<unknown>", **kwargs: Any
    ) -> Any:
        if str(filename).startswith(library_roots) and mode == "exec":
            key = (str(filename), source)
            if key in translated:
                return _Known(key)
            tree = parse(source, mode, *args, filename=filename, **kwargs)
            translated[key] = translate(tree, filename=filename)
            return _Known(key)
        return parse(source, mode, *args, filename=filename, **kwargs)

    def compile_scenic_ast(tree: Any, *args: Any, **kwargs: Any) -> Any:
        if isinstance(tree, _Known):
            return translated[tree.key]
        return translate(tree, *args, **kwargs)

    translator.parse_string = parse_string
    translator.compileScenicAST = compile_scenic_ast


def _stop_stuck_behaviors() -> None:
    import scenic.core.dynamics as dynamics
    from scenic.core.dynamics import StuckBehaviorWarning

    warnings.simplefilter("error", StuckBehaviorWarning)
    dynamics.stuckBehaviorWarningTimeout = STUCK_BEHAVIOR_SECONDS


def _numpy_module() -> Any:
    import numpy

    return numpy


class _RaggedNumpy:
    """numpy, except that `array` of rows of different lengths gives the list of rows."""

    def __init__(self, module: Any):
        self._module = module

    def __getattr__(self, name: str) -> Any:
        return getattr(self._module, name)

    def array(self, rows: Any, *args: Any, **kwargs: Any) -> Any:
        try:
            return self._module.array(rows, *args, **kwargs)
        except ValueError:
            return [self._module.asarray(row) for row in rows]


def _verifai_weights_under_cross_entropy() -> None:
    import scenic.core.external_params as external

    if isinstance(external.numpy, _RaggedNumpy):
        return
    external.numpy = _RaggedNumpy(external.numpy)
    original = external.VerifaiDiscreteRange.__init__

    def keep_bounds(self: Any, low: Any, high: Any, weights: Any = None) -> None:
        original(self, low, high, weights)
        self.__dict__["low"], self.__dict__["high"] = low, high

    external.VerifaiDiscreteRange.__init__ = keep_bounds


def _brake_in_regulated_control() -> None:
    import scenic.domains.driving.actions as driving_actions

    from arise.validate.worldmodel.actions import BrakingRegulatedControlAction

    driving_actions.RegulatedControlAction = BrakingRegulatedControlAction
