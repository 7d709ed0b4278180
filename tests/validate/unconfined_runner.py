"""Runs hostile scripts with NO confinement and NO static gate: the liveness test only.

`python tests/validate/unconfined_runner.py MAP.xodr WARM_UP.scenic` imports Scenic once,
compiles a harmless script to warm its caches, then reads one JSON request per line on
stdin ({"script", "cwd", "home", "output", "timeout"}) and runs each script in a forked
child of its own: its own session, working folder and HOME, its stdout and stderr in the
output file. Each script is compiled with arise's offline world model, sampled and
simulated for 40 steps, exactly as `scenic.scenarioFromFile` would run it for anyone. One
JSON line answers each request: the child's exit status and how many SIGUSR2 this
process received meanwhile (the script's parent is this process).
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import sys
import time
import traceback
from pathlib import Path
from typing import Any

_signals = 0


def _count_signal(number: int, frame: object) -> None:
    global _signals
    _signals += 1


def _memoise_library_parsing() -> None:
    """Parse Scenic's and arise's own Scenic modules once; user scripts are parsed afresh
    (what arise's worker does, so that each run costs only its own script)."""
    import scenic.syntax.translator as translator

    import arise

    parse, translate = translator.parse_string, translator.compileScenicAST
    roots = (str(Path(translator.__file__).parents[1]), str(Path(arise.__file__).parent))
    translated: dict[tuple[str, str], Any] = {}

    class Known:
        def __init__(self, key: tuple[str, str]):
            self.key = key

    def parse_string(
        source: str, mode: str, *args: Any, filename: str = "<unknown>", **kwargs: Any
    ) -> Any:
        if str(filename).startswith(roots) and mode == "exec":
            key = (str(filename), source)
            if key not in translated:
                tree = parse(source, mode, *args, filename=filename, **kwargs)
                translated[key] = translate(tree, filename=filename)
            return Known(key)
        return parse(source, mode, *args, filename=filename, **kwargs)

    def compile_scenic_ast(tree: Any, *args: Any, **kwargs: Any) -> Any:
        return translated[tree.key] if isinstance(tree, Known) else translate(tree, *args, **kwargs)

    translator.parse_string = parse_string
    translator.compileScenicAST = compile_scenic_ast


def run_script(script: str, map_path: str, steps: int = 40) -> None:
    import scenic

    scenario = scenic.scenarioFromFile(
        script,
        model="arise.validate.worldmodel.model",
        params={"map": map_path, "carla_map": "arise_straight"},
        mode2D=True,
    )
    scene, _ = scenario.generate(maxIterations=500)
    print("params:", {str(k): str(v) for k, v in dict(scene.params).items()}, flush=True)
    simulation = scenario.getSimulator().simulate(scene, maxSteps=steps)
    print("simulated:", simulation is not None and simulation.result.terminationReason, flush=True)


def _child(request: dict[str, Any], map_path: str, protocol_fd: int) -> int:
    os.setsid()
    signal.signal(signal.SIGUSR2, signal.SIG_DFL)
    os.close(protocol_fd)
    null = os.open(os.devnull, os.O_RDONLY)
    os.dup2(null, 0)
    output = os.open(request["output"], os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    os.dup2(output, 1)
    os.dup2(output, 2)
    os.close(output)
    os.chdir(request["cwd"])
    os.environ["HOME"] = request["home"]
    try:
        run_script(request["script"], map_path)
        return 0
    except BaseException:  # noqa: BLE001  (the script's own failure, printed for the test)
        traceback.print_exc()
        return 1
    finally:
        sys.stdout.flush()
        sys.stderr.flush()


def main() -> None:
    map_path, warm_up = sys.argv[1], sys.argv[2]
    protocol = os.fdopen(os.dup(1), "w", buffering=1, encoding="utf-8")
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    _memoise_library_parsing()
    run_script(warm_up, map_path, steps=2)
    signal.signal(signal.SIGUSR2, _count_signal)
    protocol.write(json.dumps({"ready": True}) + "\n")
    for line in sys.stdin:
        if not line.strip():
            continue
        request = json.loads(line)
        before = _signals
        sys.stdout.flush()
        sys.stderr.flush()
        pid = os.fork()
        if pid == 0:
            os._exit(_child(request, map_path, protocol.fileno()))
        deadline = time.monotonic() + float(request.get("timeout", 60))
        status: int | None = None
        while status is None:
            done, code = os.waitpid(pid, os.WNOHANG)
            if done:
                status = os.waitstatus_to_exitcode(code)
            elif time.monotonic() > deadline:
                os.killpg(pid, signal.SIGKILL)
                os.waitpid(pid, 0)
                status = -signal.SIGKILL
            else:
                time.sleep(0.02)
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(pid, signal.SIGKILL)  # whatever the script left running
        time.sleep(0.05)  # let a signal sent just before the exit arrive
        protocol.write(json.dumps({"status": status, "signals": _signals - before}) + "\n")


if __name__ == "__main__":
    main()
