"""Runs on disk: one folder per job under the runs folder, so a restart loses nothing.

A run folder holds what `arise generate` writes (scenario.scenic, report.json, attempts/,
replay and export files) plus the server's own `job.json` (the job's state) and
`events.jsonl` (its progress events, for a page opened after the run). Files are only
ever served from a run's own folder: the id and the file name are checked, and the
resolved path must stay inside it.
"""

from __future__ import annotations

import io
import json
import re
import secrets
import time
import zipfile
from pathlib import Path
from typing import Any

from arise.generate.outputs import write_atomic
from arise.serve.errors import NotFound
from arise.serve.jobs import FINISHED, Job, JobState

JOB_FILE = "job.json"
EVENTS_FILE = "events.jsonl"
#: The files of the download, in the zip's order (the map's .xodr is added by pattern).
BUNDLE = ("scenario.scenic", "scenario.xosc", "report.json", "replay.html")
_ID = re.compile(r"^\d{8}-\d{6}-[0-9a-f]{6}$")
_FILE = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]{0,120}$")
INTERRUPTED = "the server stopped before this job finished; submit it again"


def new_id() -> str:
    """Sortable by time, unguessable enough to share one folder: 20261123-043512-a1b2c3."""
    return time.strftime("%Y%m%d-%H%M%S") + "-" + secrets.token_hex(3)


def safe_file(folder: Path, name: str) -> Path:
    """The plain file `name` directly in `folder`, or NotFound (no paths, no dot files,
    no symlinks, nothing that resolves outside the folder)."""
    if not _FILE.match(name):
        raise NotFound(f"no file {name!r} in this run")
    path = folder / name
    if path.is_symlink() or not path.is_file():
        raise NotFound(f"no file {name!r} in this run")
    if not path.resolve().is_relative_to(folder.resolve()):
        raise NotFound(f"no file {name!r} in this run")
    return path


class RunStore:
    """The folder of every run; ids are checked before a path is made of them."""

    def __init__(self, root: Path) -> None:
        self.root = Path(root)
        self.root.mkdir(parents=True, exist_ok=True)

    def folder(self, run_id: str, create: bool = False) -> Path:
        if not _ID.match(run_id):
            raise NotFound(f"no run {run_id!r}")
        folder = self.root / run_id
        if create:
            folder.mkdir(parents=True, exist_ok=True)
        elif not folder.is_dir():
            raise NotFound(f"no run {run_id!r}")
        return folder

    def save_job(self, job: Job) -> None:
        folder = self.folder(job.id, create=True)
        write_atomic(folder / JOB_FILE, json.dumps(job.as_dict(), indent=2) + "\n")

    def append_event(self, job: Job, event: dict[str, Any]) -> None:
        folder = self.folder(job.id, create=True)
        with (folder / EVENTS_FILE).open("a", encoding="utf-8") as out:
            out.write(json.dumps(event, default=str) + "\n")

    def load_jobs(self) -> list[Job]:
        """Every job on disk, oldest first. A job that was queued or running when the
        server stopped is failed (and saved so), with a message saying so."""
        jobs: list[Job] = []
        for folder in sorted(self.root.iterdir()):
            if not _ID.match(folder.name) or not (folder / JOB_FILE).is_file():
                continue
            try:
                job = Job.from_dict(json.loads((folder / JOB_FILE).read_text("utf-8")))
            except (OSError, ValueError, KeyError, TypeError):
                continue  # a half-written or foreign file: not one of our runs
            if job.id != folder.name:
                continue
            job.events = self._events(folder)
            if job.state not in FINISHED:
                job.move(JobState.FAILED, INTERRUPTED)
                self.save_job(job)
            jobs.append(job)
        return jobs

    @staticmethod
    def _events(folder: Path) -> list[dict[str, Any]]:
        path = folder / EVENTS_FILE
        if not path.is_file():
            return []
        events = []
        for line in path.read_text("utf-8").splitlines():
            try:
                events.append(json.loads(line))
            except ValueError:
                continue  # the last line of a server that was killed mid-write
        return events

    def file(self, run_id: str, name: str) -> Path:
        return safe_file(self.folder(run_id), name)

    def bundle(self, run_id: str) -> list[Path]:
        """The download's files that exist: script, OpenSCENARIO, map, report, replay."""
        folder = self.folder(run_id)
        found = [folder / name for name in BUNDLE if (folder / name).is_file()]
        found += sorted(p for p in folder.glob("*.xodr") if p.is_file() and not p.is_symlink())
        return found

    def zip_bytes(self, run_id: str) -> bytes:
        files = self.bundle(run_id)
        if not files:
            raise NotFound(f"run {run_id} has no files to download yet")
        buffer = io.BytesIO()
        with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
            for path in files:
                archive.write(path, arcname=f"{run_id}/{path.name}")
        return buffer.getvalue()
