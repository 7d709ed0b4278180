"""A scripted runner for the server's tests: it emits the pipeline's stages, writes a run
folder as the generator does, and ends as told; `hold` keeps each job at its first stage
until the test releases it, so queues and cancels can be watched without timing."""

from __future__ import annotations

import threading
from collections.abc import Callable
from pathlib import Path

from arise.generate.events import AttemptChecked, ProgressEvent, RunFinished, RunStage, StageStarted
from arise.generate.options import GenerateOptions
from arise.generate.outputs import write_attempt, write_report, write_script
from arise.generate.run import Attempt, AttemptKind, Generation, Outcome, RunStatus, unified_diff
from arise.validate.types import Diagnostic, Stage

FIRST = """# BEGIN HEADER
model scenic.simulators.carla.model
# END HEADER
# BEGIN BEHAVIOR
behavior AdversaryBehavior():
    do FollowLaneBehavior(target_speed=5)
# END BEHAVIOR
# BEGIN SPAWN
ego = new Car
adversary = new Car ahead of ego by 10, with behavior AdversaryBehavior
# END SPAWN
"""
#: The repaired script: one line of BEHAVIOR changed by a rule.
SECOND = FIRST.replace("target_speed=5", "target_speed=globalParameters.OPT_SPEED")


class ScriptedRunner:
    def __init__(self, status: RunStatus = RunStatus.EXECUTED, hold: bool = False) -> None:
        self.status = status
        self.hold = hold
        self.release = threading.Event()
        self.started = threading.Event()
        self.descriptions: list[str] = []
        self.closed = False
        self.crash: BaseException | None = None

    def generate(
        self,
        description: str,
        out_dir: Path | None = None,
        progress: Callable[[ProgressEvent], None] | None = None,
    ) -> Generation:
        assert out_dir is not None and progress is not None
        self.descriptions.append(description)
        run = Generation(description=description, options=GenerateOptions(), out_dir=out_dir)
        progress(StageStarted(RunStage.EXTRACT))
        self.started.set()
        if self.hold:
            assert self.release.wait(20), "the test never released the job"
        if self.crash is not None:
            raise self.crash
        progress(StageStarted(RunStage.RETRIEVE))
        progress(StageStarted(RunStage.ASSEMBLE))
        progress(StageStarted(RunStage.VALIDATE, attempt=0))
        failure = Diagnostic(
            stage=Stage.COMPILE, error_type="NameError", message="x", line=6, section="BEHAVIOR"
        )
        run.add_attempt(
            Attempt(0, AttemptKind.INITIAL, "assembled", FIRST, False, failure, "", 0.1)
        )
        write_attempt(out_dir, 0, FIRST)
        progress(AttemptChecked(0, AttemptKind.INITIAL, False, "assembled", failure.one_line()))
        progress(StageStarted(RunStage.REPAIR, attempt=1, error=failure.one_line()))
        ok = self.status is RunStatus.EXECUTED
        run.add_attempt(
            Attempt(
                1, AttemptKind.RULE, "param", SECOND, ok, None, unified_diff(FIRST, SECOND), 0.1
            )
        )
        write_attempt(out_dir, 1, SECOND)
        progress(AttemptChecked(1, AttemptKind.RULE, ok, "param"))
        run.end(Outcome(self.status, None if ok else "no script ran"))
        write_script(out_dir, SECOND, ok)
        write_report(out_dir, run.report())
        if ok:
            (out_dir / "replay.html").write_text("<p>replay</p>", encoding="utf-8")
            (out_dir / "scenario.xosc").write_text("<OpenSCENARIO/>", encoding="utf-8")
            (out_dir / "arise_straight.xodr").write_text("<OpenDRIVE/>", encoding="utf-8")
        progress(RunFinished(run.status, run.summary()))
        return run

    def close(self) -> None:
        self.closed = True
