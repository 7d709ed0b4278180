"""The drive database: one row per finished run, in SQLite, written as each run ends.

A run is one row written in one transaction, so a drive killed at any moment leaves only
whole runs behind and running the same command again does only the missing ones. Other
tools can read it (`sqlite3 drive.sqlite 'select scenario, agent, collision from runs'`);
the metrics of a run are JSON in `metrics`, as runs.csv has them in columns.
"""

from __future__ import annotations

import json
import sqlite3
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from arise.drive.records import DriveRecord
from arise.errors import AriseError

DATABASE = "drive.sqlite"

SCHEMA = """
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS runs (
    id INTEGER PRIMARY KEY,
    scenario TEXT NOT NULL, category TEXT NOT NULL, digest TEXT NOT NULL,
    agent TEXT NOT NULL, run_index INTEGER NOT NULL, seed INTEGER,
    status TEXT NOT NULL, collision INTEGER, message TEXT, metrics TEXT NOT NULL,
    record TEXT NOT NULL, finished_at TEXT NOT NULL,
    UNIQUE (scenario, digest, agent, seed)
);
"""


class DriveStoreError(AriseError):
    """The database cannot be opened, or is not a drive database this arise reads."""


class DriveStore:
    def __init__(self, path: Path):
        self.path = path
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            self._db = sqlite3.connect(path, check_same_thread=False)
            self._db.executescript(SCHEMA)
        except (sqlite3.DatabaseError, OSError) as error:
            raise DriveStoreError(f"{path}: not a drive database ({error})") from error

    def close(self) -> None:
        self._db.close()

    def __enter__(self) -> DriveStore:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def meta(self) -> dict[str, Any]:
        try:
            rows = list(self._db.execute("SELECT key, value FROM meta"))
            return {key: json.loads(value) for key, value in rows}
        except (sqlite3.DatabaseError, ValueError) as error:
            raise DriveStoreError(
                f"{self.path}: its meta table is not readable ({error})"
            ) from None

    def set_meta(self, **values: Any) -> None:
        with self._db:
            self._db.executemany(
                "INSERT OR REPLACE INTO meta VALUES (?, ?)",
                [(key, json.dumps(value)) for key, value in values.items()],
            )

    def done_keys(self) -> set[tuple[str, str, str, int | None]]:
        rows = self._db.execute("SELECT scenario, digest, agent, seed FROM runs")
        return {(s, d, a, seed) for s, d, a, seed in rows}

    def save(self, record: DriveRecord) -> None:
        """The run's row, replacing one of the same key (a run done again)."""
        task = record.task
        with self._db:
            self._db.execute(
                "INSERT OR REPLACE INTO runs (scenario, category, digest, agent, run_index, "
                "seed, status, collision, message, metrics, record, finished_at) "
                "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                (
                    task.scenario,
                    task.category,
                    task.digest,
                    task.agent,
                    task.run_index,
                    task.seed,
                    record.status.value,
                    int(record.collided) if record.driven else None,
                    record.message,
                    json.dumps(record.metrics),
                    record.model_dump_json(),
                    datetime.now(UTC).isoformat(timespec="seconds"),
                ),
            )

    def records(self) -> list[DriveRecord]:
        """Every run, in the order they finished; a row this arise cannot read is one line."""
        try:
            rows = list(self._db.execute("SELECT record FROM runs ORDER BY id"))
            return [DriveRecord.model_validate_json(text) for (text,) in rows]
        except (sqlite3.DatabaseError, ValidationError, ValueError) as error:
            first = str(error).splitlines()[0][:200]
            raise DriveStoreError(
                f"{self.path}: a run of it is not one this arise reads ({first})"
            ) from None
