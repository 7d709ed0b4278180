"""Runs on disk: one folder per job under the runs folder, so a restart loses nothing.

A run folder holds what `arise generate` writes (scenario.scenic, report.json, attempts/,
replay and export files) plus the server's own `job.json` (the job's state) and
`events.jsonl` (its progress events, for a page opened after the run).

A run folder may come from elsewhere (a user was handed it), so what it holds is untrusted
input. Every read goes through `safefs`: a run folder that is a symbolic link is refused
(not listed, 404); inside a run, links, special files, hard links and oversized files are
skipped (not listed, 404, left out of the zip with a note in SKIPPED.txt). The records
read back (job.json, events.jsonl) are bounded and validated.
"""

from __future__ import annotations

import contextlib
import io
import json
import logging
import os
import re
import secrets
import stat
import time
import zipfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import BinaryIO

from arise.generate.outputs import write_atomic
from arise.serve.errors import NotFound, ServeError
from arise.serve.events import JobEvent, event_json, read_event
from arise.serve.jobs import FINISHED, Job, JobState
from arise.serve.safefs import EntryKind, Folder, Refused, parse_json

log = logging.getLogger("arise.serve")

JOB_FILE = "job.json"
EVENTS_FILE = "events.jsonl"
SKIPPED_FILE = "SKIPPED.txt"
#: The files of the download, in the zip's order (the map's .xodr is added by pattern).
BUNDLE = ("scenario.scenic", "scenario.xosc", "report.json", "replay.html")
_ID = re.compile(r"^\d{8}-\d{6}-[0-9a-f]{6}$")
_FILE = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]{0,120}$")
INTERRUPTED = "the server stopped before this job finished; submit it again"
#: Bounds on what is read from a run folder.
MAX_FILE_BYTES = 64 * 1024 * 1024  # one served or zipped file (a replay GIF is far less)
MAX_ZIP_BYTES = 256 * 1024 * 1024  # every file of one download together
MAX_JOB_BYTES = 1024 * 1024
MAX_EVENTS_BYTES = 16 * 1024 * 1024
MAX_EVENTS = 20_000


def new_id() -> str:
    """Sortable by time, unguessable enough to share one folder: 20261123-043512-a1b2c3."""
    return time.strftime("%Y%m%d-%H%M%S") + "-" + secrets.token_hex(3)


def check_name(name: str) -> str:
    """A plain file name (no paths, no dot files), or NotFound."""
    if not _FILE.match(name):
        raise NotFound(f"no file {name!r} in this run")
    return name


@dataclass
class Bundle:
    """The download's files that are there to read, and those skipped (with why)."""

    names: list[str] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)


def bundle_of(folder: Folder) -> Bundle:
    """Script, OpenSCENARIO, report, replay and the map's .xodr: regular files only."""
    found = Bundle()
    kinds = dict(folder.entries())
    wanted = [name for name in BUNDLE if name in kinds]
    wanted += sorted(n for n in kinds if n.endswith(".xodr") and _FILE.match(n))
    for name in wanted:
        kind = kinds[name]
        if kind is EntryKind.REGULAR:
            found.names.append(name)
        else:
            found.skipped.append(f"{name}: a {kind.value}, not served")
    return found


class RunStore:
    """The folder of every run; ids are checked before a path is made of them."""

    def __init__(self, root: Path, *, root_may_link: bool = True) -> None:
        self.root = Path(root)
        if not root_may_link and self.root.is_symlink():
            raise ServeError(f"{self.root} is a symbolic link; remove it and start again")
        self.root.mkdir(parents=True, exist_ok=True)

    def _checked_id(self, run_id: str) -> str:
        if not _ID.match(run_id):
            raise NotFound(f"no run {run_id!r}")
        return run_id

    def folder(self, run_id: str, create: bool = False) -> Path:
        """The run's folder as a path (for the generator to write in): a real folder,
        never a link. `create` makes it when missing."""
        folder = self.root / self._checked_id(run_id)
        if create:
            with contextlib.suppress(FileExistsError):  # checked just below
                folder.mkdir()
        try:
            mode = os.lstat(folder).st_mode
        except FileNotFoundError:
            raise NotFound(f"no run {run_id!r}") from None
        if not stat.S_ISDIR(mode):
            raise Refused(f"run {run_id!r} is not a folder (a symbolic link?)")
        return folder

    def open(self, run_id: str) -> Folder:
        """The run's folder, opened without following a link (see `safefs`)."""
        return Folder.open(self.root, self._checked_id(run_id))

    def save_job(self, job: Job) -> None:
        folder = self.folder(job.id, create=True)
        write_atomic(folder / JOB_FILE, json.dumps(job.as_dict(), indent=2) + "\n")

    def append_event(self, job: Job, event: JobEvent) -> None:
        """Append to the run's events.jsonl; one that is a link is left alone (the job
        keeps its events in memory, and a restart will not read that file)."""
        self.folder(job.id, create=True)
        with self.open(job.id) as folder:
            try:
                folder.append_text(EVENTS_FILE, event_json(event) + "\n")
            except Refused as refusal:
                log.warning("event of job %s not saved: %s", job.id, refusal)

    def load_jobs(self) -> list[Job]:
        """Every job on disk, oldest first. A job that was queued or running when the
        server stopped is failed (and saved so), with a message saying so."""
        jobs: list[Job] = []
        with Folder.open(self.root) as root:
            entries = sorted(root.entries())
        for name, kind in entries:
            if not _ID.match(name):
                continue
            if kind is not EntryKind.DIRECTORY:
                log.warning("run %s skipped: it is a %s, not a folder", name, kind.value)
                continue
            job = self._load_job(name)
            if job is None:
                continue
            if job.state not in FINISHED:
                job.move(JobState.FAILED, INTERRUPTED)
                self.save_job(job)
            jobs.append(job)
        return jobs

    def _load_job(self, run_id: str) -> Job | None:
        try:
            with self.open(run_id) as folder:
                text = folder.read_text(JOB_FILE, MAX_JOB_BYTES)
                if text is None:
                    return None
                job = Job.from_dict(parse_json(text))
                if job.id != run_id:
                    return None
                job.events = self._events(folder)
        except (NotFound, ValueError, KeyError, TypeError):
            return None  # a half-written, foreign or linked record: not one of our runs
        return job

    @staticmethod
    def _events(folder: Folder) -> list[JobEvent]:
        text = folder.read_text(EVENTS_FILE, MAX_EVENTS_BYTES)
        if text is None:
            return []
        # Each line typed, or skipped: the last line of a server killed mid-write, or one
        # that is not one of our events (a run folder anyone may hand over).
        read = (read_event(line) for line in text.splitlines()[:MAX_EVENTS])
        return [event for event in read if event is not None]

    def file(self, run_id: str, name: str) -> tuple[BinaryIO, int]:
        """One file of the run's own folder, opened, and its size (`Refused`: 404)."""
        check_name(name)
        with self.open(run_id) as folder:
            return folder.open_file(name, MAX_FILE_BYTES)

    def zip_bytes(self, run_id: str) -> bytes:
        """The download: the bundle's regular files, each and all size-bounded; what was
        left out is named in SKIPPED.txt."""
        with self.open(run_id) as folder:
            found = bundle_of(folder)
            buffer = io.BytesIO()
            added = 0
            total = 0
            with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
                for name in found.names:
                    try:
                        data = folder.read(name, min(MAX_FILE_BYTES, MAX_ZIP_BYTES - total))
                    except Refused as refusal:
                        found.skipped.append(f"{name}: {refusal}")
                        continue
                    total += len(data)
                    archive.writestr(_entry(f"{run_id}/{name}"), data)
                    added += 1
                if found.skipped:
                    log.warning("download of run %s: skipped %s", run_id, found.skipped)
                    note = "Left out of this download:\n" + "".join(
                        f"- {line}\n" for line in found.skipped
                    )
                    archive.writestr(_entry(f"{run_id}/{SKIPPED_FILE}"), note)
        if not added:
            raise NotFound(f"run {run_id} has no files to download yet")
        return buffer.getvalue()


def _entry(name: str) -> zipfile.ZipInfo:
    """A plain file entry (rw-r--r--, dated now), whatever the file on disk was."""
    info = zipfile.ZipInfo(name, date_time=time.localtime()[:6])
    info.compress_type = zipfile.ZIP_DEFLATED
    info.external_attr = 0o100644 << 16
    return info
