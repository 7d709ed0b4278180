"""SQLite response cache: a re-run of the same request costs nothing and is identical.

The key is the provider, model, full request (messages, temperature, max tokens, schema,
stop, seed) and, for sampled calls (temperature > 0) without a seed, the run index, so
``--runs 10`` gives ten different samples while re-running the benchmark replays them.
"""

from __future__ import annotations

import json
import sqlite3
import threading
import time
from dataclasses import replace
from pathlib import Path

from arise.llm.base import BaseProvider, Wrapper
from arise.llm.types import Completion, Request, Usage
from arise.paths import cache_dir

_SCHEMA = """
CREATE TABLE IF NOT EXISTS responses (
    key TEXT PRIMARY KEY,
    provider TEXT NOT NULL,
    model TEXT NOT NULL,
    request TEXT NOT NULL,
    response TEXT NOT NULL,
    created REAL NOT NULL
)
"""


def default_cache_path() -> Path:
    return cache_dir() / "llm-cache.sqlite3"


def cache_key(provider: str, model: str, request: Request, run_index: int = 0) -> str:
    extra: dict[str, object] = {"provider": provider, "model": model}
    if request.temperature > 0 and request.seed is None:
        extra["run"] = run_index
    return request.key(**extra)


class ResponseCache:
    """A thin, process-safe store (WAL mode; each process opens its own connection)."""

    def __init__(self, path: Path | None = None) -> None:
        self.path = path or default_cache_path()
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._lock = threading.Lock()
        self._db = sqlite3.connect(self.path, timeout=30, check_same_thread=False)
        self._db.execute("PRAGMA journal_mode=WAL")
        self._db.execute(_SCHEMA)
        self._db.commit()

    def get(self, key: str) -> dict[str, object] | None:
        with self._lock:
            row = self._db.execute(
                "SELECT response FROM responses WHERE key = ?", (key,)
            ).fetchone()
        return json.loads(row[0]) if row else None

    def put(self, key: str, provider: str, model: str, request: Request, record: dict) -> None:
        with self._lock:
            self._db.execute(
                "INSERT OR REPLACE INTO responses VALUES (?, ?, ?, ?, ?, ?)",
                (
                    key,
                    provider,
                    model,
                    json.dumps(request.as_dict(), ensure_ascii=False),
                    json.dumps(record, ensure_ascii=False),
                    time.time(),
                ),
            )
            self._db.commit()

    def stats(self) -> dict[str, int]:
        with self._lock:
            (count,) = self._db.execute("SELECT COUNT(*) FROM responses").fetchone()
        size = self.path.stat().st_size if self.path.exists() else 0
        return {"entries": int(count), "bytes": size}

    def clear(self) -> int:
        with self._lock:
            cur = self._db.execute("DELETE FROM responses")
            self._db.commit()
            return cur.rowcount

    def close(self) -> None:
        with self._lock:
            self._db.close()


class CachedProvider(Wrapper):
    def __init__(self, inner: BaseProvider, cache: ResponseCache, run_index: int = 0) -> None:
        super().__init__(inner)
        self.cache = cache
        self.run_index = run_index
        self.hits = 0
        self.misses = 0

    def send(self, request: Request) -> Completion:
        started = time.perf_counter()
        key = cache_key(self.name, self.model, request, self.run_index)
        record = self.cache.get(key)
        if record is not None:
            self.hits += 1
            elapsed = time.perf_counter() - started
            original = Completion.from_record(record)
            return replace(
                original,
                usage=Usage(cached_calls=1, seconds=elapsed),
                latency=elapsed,
                cached=True,
                details={**original.details, "cache_key": key, "original_usage": record["usage"]},
            )
        self.misses += 1
        reply = self.inner.send(request)
        self.cache.put(key, self.name, self.model, request, reply.as_record())
        return reply

    def close(self) -> None:
        self.cache.close()
        super().close()
