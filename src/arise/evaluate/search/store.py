"""The search database: one row per search and one per finished trial, in SQLite.

A trial is written the moment it finishes, so a search killed at any point loses only
the trials that were running; the same command resumes. Several searches (samplers,
objectives, seeds, scripts) share one file; `sqlite3 search.sqlite 'select * from
trials'` reads it.
"""

from __future__ import annotations

import json
import sqlite3
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from arise.evaluate.search.errors import SearchError
from arise.evaluate.search.objective import TrialOutcome
from arise.evaluate.search.space import ParamValue

SCHEMA = """
CREATE TABLE IF NOT EXISTS searches (
    key TEXT PRIMARY KEY, script TEXT NOT NULL, script_sha256 TEXT NOT NULL,
    sampler TEXT NOT NULL, objective TEXT NOT NULL, seed INTEGER NOT NULL,
    batch INTEGER NOT NULL, params TEXT NOT NULL, created_at TEXT NOT NULL, agent TEXT
);
CREATE TABLE IF NOT EXISTS trials (
    search TEXT NOT NULL REFERENCES searches(key) ON DELETE CASCADE,
    idx INTEGER NOT NULL, params TEXT NOT NULL, ok INTEGER NOT NULL, value REAL,
    collision INTEGER NOT NULL, min_ttc REAL, min_distance REAL, message TEXT,
    seconds REAL NOT NULL, finished_at TEXT NOT NULL, metrics TEXT,
    PRIMARY KEY (search, idx)
);
"""
#: Columns added since the first schema, added to an older database when it is opened:
#: the agent in the ego's seat (none: the script drove) and a trial's driving metrics.
ADDED_COLUMNS = (("searches", "agent", "TEXT"), ("trials", "metrics", "TEXT"))


@dataclass(frozen=True)
class TrialRecord:
    """A finished trial: its index (from 0), the values it ran with and its outcome."""

    index: int
    values: dict[str, ParamValue]
    outcome: TrialOutcome


@dataclass(frozen=True)
class SearchRow:
    key: str
    script: str
    script_sha256: str
    sampler: str
    objective: str
    seed: int
    batch: int
    params: list[dict[str, Any]]
    agent: str | None = None


class SearchStore:
    def __init__(self, path: Path):
        self.path = path
        path.parent.mkdir(parents=True, exist_ok=True)
        try:
            self._db = sqlite3.connect(path, check_same_thread=False)
            self._db.execute("PRAGMA foreign_keys = ON")
            self._db.executescript(SCHEMA)
            self._add_columns()
        except sqlite3.DatabaseError as error:
            raise SearchError(f"{path}: not a search database ({error})") from error

    def _add_columns(self) -> None:
        for table, column, kind in ADDED_COLUMNS:
            present = {row[1] for row in self._db.execute(f"PRAGMA table_info({table})")}
            if column not in present:
                with self._db:
                    self._db.execute(f"ALTER TABLE {table} ADD COLUMN {column} {kind}")

    def search(self, key: str) -> SearchRow | None:
        row = self._db.execute(
            "SELECT key, script, script_sha256, sampler, objective, seed, batch, params, agent "
            "FROM searches WHERE key = ?",
            (key,),
        ).fetchone()
        if row is None:
            return None
        key, script, digest, sampler, objective, seed, batch, params, agent = row
        return SearchRow(
            key, script, digest, sampler, objective, seed, batch, json.loads(params), agent
        )

    def searches(self) -> list[SearchRow]:
        keys = [k for (k,) in self._db.execute("SELECT key FROM searches ORDER BY created_at")]
        return [row for key in keys if (row := self.search(key)) is not None]

    def add_search(self, row: SearchRow) -> None:
        with self._db:
            self._db.execute(
                "INSERT OR IGNORE INTO searches (key, script, script_sha256, sampler, objective, "
                "seed, batch, params, created_at, agent) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                (
                    row.key,
                    row.script,
                    row.script_sha256,
                    row.sampler,
                    row.objective,
                    row.seed,
                    row.batch,
                    json.dumps(row.params),
                    datetime.now(UTC).isoformat(timespec="seconds"),
                    row.agent,
                ),
            )

    def save(self, key: str, record: TrialRecord) -> None:
        result = record.outcome
        with self._db:
            self._db.execute(
                "INSERT OR REPLACE INTO trials (search, idx, params, ok, value, collision, "
                "min_ttc, min_distance, message, seconds, finished_at, metrics) "
                "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                (
                    key,
                    record.index,
                    json.dumps(record.values),
                    int(result.ok),
                    result.value,
                    int(result.collision),
                    result.min_ttc,
                    result.min_distance,
                    result.message,
                    result.seconds,
                    datetime.now(UTC).isoformat(timespec="seconds"),
                    None if result.metrics is None else json.dumps(result.metrics),
                ),
            )

    def trials(self, key: str) -> dict[int, TrialRecord]:
        rows = self._db.execute(
            "SELECT idx, params, ok, value, collision, min_ttc, min_distance, message, seconds, "
            "metrics FROM trials WHERE search = ? ORDER BY idx",
            (key,),
        )
        return {
            idx: TrialRecord(
                index=idx,
                values=json.loads(params),
                outcome=TrialOutcome(
                    ok=bool(ok),
                    value=value,
                    collision=bool(collision),
                    min_ttc=min_ttc,
                    min_distance=min_distance,
                    message=message,
                    seconds=seconds,
                    metrics=None if metrics is None else json.loads(metrics),
                ),
            )
            for idx, params, ok, value, collision, min_ttc, min_distance, message, seconds, metrics in rows
        }

    def close(self) -> None:
        self._db.close()

    def __enter__(self) -> SearchStore:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
