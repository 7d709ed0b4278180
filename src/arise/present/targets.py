"""A run folder or a script, presented on request: what `arise replay` and `arise export` do.

The trace comes from the run's saved trace.json, or from checking the script again in the
confined validator (`load_trace`); it is saved beside what is drawn from it, so the next
request reads it instead of simulating again.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from arise.present.replay import ReplayFiles, write_replay
from arise.present.source import TraceSource, load_trace
from arise.present.tracefile import write_trace
from arise.present.xosc import EgoMode, ExportFiles, write_export


@dataclass(frozen=True)
class Replayed:
    source: TraceSource
    files: ReplayFiles


@dataclass(frozen=True)
class Exported:
    source: TraceSource
    files: ExportFiles


def out_dir(target: Path, out: Path | None) -> Path:
    """Where the files go: `out`, else the run folder, else a folder named after the script
    beside it."""
    if out is not None:
        return out
    return target if target.is_dir() else target.with_suffix("")


def replay_target(
    target: Path, out: Path | None = None, *, still: bool = False, map_dir: str | None = None
) -> Replayed:
    """replay.gif and replay.html (and scene.png with `still`) of a run folder or script."""
    source = load_trace(target, map_dir=map_dir)
    folder = out_dir(target, out)
    write_trace(folder, source.saved())
    return Replayed(source, write_replay(source, folder, still=still, map_dir=map_dir))


def export_target(
    target: Path,
    out: Path | None = None,
    ego: EgoMode = EgoMode.REPLAY,
    *,
    map_dir: str | None = None,
) -> Exported:
    """scenario.xosc (OpenSCENARIO 1.2) and the .xodr it references, of a run folder or
    script."""
    source = load_trace(target, map_dir=map_dir)
    folder = out_dir(target, out)
    write_trace(folder, source.saved())
    return Exported(source, write_export(source, folder, ego, map_dir=map_dir))
