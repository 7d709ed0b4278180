"""The benchmark database: one row per finished run and one per attempt, in SQLite.

A run and its attempts are written in one transaction when the run ends, so a benchmark
killed at any moment leaves only whole runs behind; resuming redoes the unfinished ones.
Other tools can read the tables directly (`sqlite3 bench.sqlite 'select * from runs'`).
"""

from __future__ import annotations

import json
import sqlite3
from collections.abc import Iterator
from contextlib import contextmanager
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from arise.errors import AriseError
from arise.evaluate.records import AttemptRecord, RunRecord
from arise.generate.options import Mode
from arise.generate.run import AttemptKind

SCHEMA = """
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS runs (
    id INTEGER PRIMARY KEY,
    prompt_id TEXT NOT NULL, category TEXT NOT NULL, description TEXT NOT NULL,
    mode TEXT NOT NULL, temperature REAL NOT NULL, run_index INTEGER NOT NULL,
    status TEXT NOT NULL, first_pass_ok INTEGER NOT NULL, repairs INTEGER NOT NULL,
    llm_calls INTEGER NOT NULL, prompt_tokens INTEGER NOT NULL,
    completion_tokens INTEGER NOT NULL, seconds REAL NOT NULL, message TEXT, out_dir TEXT,
    conformity REAL, scs REAL, collision INTEGER, min_distance REAL, min_ttc REAL,
    route_completion REAL, record TEXT NOT NULL, finished_at TEXT NOT NULL,
    gate TEXT, gate_seconds REAL,
    UNIQUE (prompt_id, mode, temperature, run_index)
);
CREATE TABLE IF NOT EXISTS attempts (
    run_id INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,
    idx INTEGER NOT NULL, kind TEXT NOT NULL, ok INTEGER NOT NULL, stage TEXT,
    error_type TEXT, message TEXT, section TEXT, check_seconds REAL NOT NULL,
    llm_calls INTEGER NOT NULL, tokens INTEGER NOT NULL,
    PRIMARY KEY (run_id, idx)
);
"""
# Columns added after the first release: (name, type), added to older databases on open.
ADDED_COLUMNS = [("gate", "TEXT"), ("gate_seconds", "REAL")]


class BenchStoreError(AriseError):
    """The database cannot be opened or is not an arise benchmark."""


class BenchStore:
    def __init__(self, path: Path):
        self.path = path
        path.parent.mkdir(parents=True, exist_ok=True)
        try:
            self._db = sqlite3.connect(path)
            self._db.execute("PRAGMA foreign_keys = ON")
            self._db.executescript(SCHEMA)
            self._add_columns()
        except sqlite3.DatabaseError as error:
            raise BenchStoreError(f"{path}: not a benchmark database ({error})") from error

    def _add_columns(self) -> None:
        """A database written before a column existed gets it (empty for its old runs)."""
        present = {row[1] for row in self._db.execute("PRAGMA table_info(runs)")}
        with self._db:
            for name, kind in ADDED_COLUMNS:
                if name not in present:
                    self._db.execute(f"ALTER TABLE runs ADD COLUMN {name} {kind}")

    def close(self) -> None:
        self._db.close()

    def __enter__(self) -> BenchStore:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- metadata: what the benchmark was started with --------------------------------------
    def meta(self) -> dict[str, Any]:
        return {
            key: json.loads(value) for key, value in self._db.execute("SELECT key, value FROM meta")
        }

    def set_meta(self, **values: Any) -> None:
        with self._db:
            self._db.executemany(
                "INSERT OR REPLACE INTO meta VALUES (?, ?)",
                [(k, json.dumps(v)) for k, v in values.items()],
            )

    # -- runs ----------------------------------------------------------------------------------
    def done_keys(self) -> set[tuple[str, Mode, float, int]]:
        rows = self._db.execute("SELECT prompt_id, mode, temperature, run_index FROM runs")
        with self._reading("runs"):
            return {(p, Mode(m), round(t, 4), r) for p, m, t, r in rows}

    def save(self, record: RunRecord) -> None:
        task, crit = record.task, record.criticality or {}
        with self._db:
            self._db.execute(
                "DELETE FROM runs WHERE prompt_id=? AND mode=? AND temperature=? AND run_index=?",
                (task.prompt_id, task.mode, task.temperature, task.run_index),
            )
            cursor = self._db.execute(
                "INSERT INTO runs (prompt_id, category, description, mode, temperature, "
                "run_index, status, first_pass_ok, repairs, llm_calls, prompt_tokens, "
                "completion_tokens, seconds, message, out_dir, conformity, scs, collision, "
                "min_distance, min_ttc, route_completion, record, finished_at, gate, "
                "gate_seconds) "
                "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                (
                    task.prompt_id,
                    task.category,
                    task.description,
                    task.mode,
                    task.temperature,
                    task.run_index,
                    record.status,
                    int(record.first_pass_ok),
                    record.repairs,
                    record.llm_calls,
                    record.prompt_tokens,
                    record.completion_tokens,
                    round(record.seconds, 3),
                    record.message,
                    record.out_dir,
                    record.conformity_score,
                    record.scs,
                    None if not crit else int(bool(crit.get("collision"))),
                    crit.get("min_distance"),
                    crit.get("min_ttc"),
                    crit.get("route_completion"),
                    json.dumps(record.as_dict()),
                    datetime.now(UTC).isoformat(timespec="seconds"),
                    record.gate,
                    round(record.gate_seconds, 3),
                ),
            )
            run_id = cursor.lastrowid
            self._db.executemany(
                "INSERT INTO attempts VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                [
                    (
                        run_id,
                        a.index,
                        a.kind,
                        int(a.ok),
                        a.stage,
                        a.error_type,
                        a.message,
                        a.section,
                        round(a.check_seconds, 3),
                        a.llm_calls,
                        a.tokens,
                    )
                    for a in record.attempts
                ],
            )

    def runs(self) -> list[RunRecord]:
        rows = self._db.execute("SELECT record FROM runs ORDER BY id")
        with self._reading("runs"):
            return [RunRecord.from_dict(json.loads(text)) for (text,) in rows]

    def attempts(self) -> list[AttemptRecord]:
        rows = self._db.execute(
            "SELECT idx, kind, ok, stage, error_type, message, section, check_seconds, "
            "llm_calls, tokens FROM attempts ORDER BY run_id, idx"
        )
        with self._reading("attempts"):
            return [
                AttemptRecord(i, AttemptKind(k), bool(o), s, e, m, sec, c, n, t)
                for i, k, o, s, e, m, sec, c, n, t in rows
            ]

    @contextmanager
    def _reading(self, table: str) -> Iterator[None]:
        """A row this version cannot read (an unknown mode, kind or status; a broken record)
        is one line naming the database, not a traceback."""
        try:
            yield
        except (ValueError, KeyError, TypeError) as error:
            raise BenchStoreError(
                f"{self.path}: a row of {table} is not one this arise reads ({error})"
            ) from error
