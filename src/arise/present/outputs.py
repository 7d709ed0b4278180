"""Every presentation of one executed run, written together: trace.json, the replay and
the OpenSCENARIO export. `arise generate` calls this for each run whose script ran."""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

from arise.present.replay import ReplayFiles, write_replay
from arise.present.source import TraceSource
from arise.present.tracefile import write_trace
from arise.present.xosc import EgoMode, ExportFiles, write_export


@dataclass
class RunFiles:
    trace: Path
    replay: ReplayFiles
    export: ExportFiles
    seconds: dict[str, float] = field(default_factory=dict)


def write_run_files(source: TraceSource, out_dir: Path, *, map_dir: str | None = None) -> RunFiles:
    """trace.json, replay.gif, replay.html, scenario.xosc and the map's .xodr in out_dir."""
    started = time.perf_counter()
    trace = write_trace(out_dir, source.saved())
    replay = write_replay(source, out_dir, map_dir=map_dir)
    replay_done = time.perf_counter()
    export = write_export(source, out_dir, EgoMode.REPLAY, map_dir=map_dir)
    finished = time.perf_counter()
    return RunFiles(
        trace=trace,
        replay=replay,
        export=export,
        seconds={
            "replay": round(replay_done - started, 3),
            "export": round(finished - replay_done, 3),
        },
    )
