"""Record real calls into a JSONL cassette and replay them without the model.

Line 1 is metadata (which provider and model made the recording, its capabilities); every
other line is one call: the request key, the request, the reply. The key is a hash of the
normalised request only, so a cassette recorded through any provider replays the same.
Secrets (API keys from the environment, key-shaped strings) are scrubbed before writing.
"""

from __future__ import annotations

import json
import os
import re
import threading
import time
from dataclasses import asdict, replace
from pathlib import Path
from typing import Any

from arise.llm.base import BaseProvider, Wrapper
from arise.llm.types import (
    Capabilities,
    Completion,
    LLMError,
    ReplayMiss,
    Request,
    Usage,
)

FORMAT_VERSION = 1
SCRUBBED = "[scrubbed]"

_SECRET_PATTERNS = (
    re.compile(r"sk-ant-[A-Za-z0-9_\-]{16,}"),
    re.compile(r"sk-[A-Za-z0-9_\-]{16,}"),
    re.compile(r"AIza[0-9A-Za-z_\-]{30,}"),
    re.compile(r"(?i)bearer\s+[A-Za-z0-9_\-\.=]{12,}"),
)
_SECRET_ENV = re.compile(r"(API_KEY|TOKEN|SECRET|PASSWORD)$")


def _env_secrets() -> list[str]:
    return sorted(
        (v for k, v in os.environ.items() if _SECRET_ENV.search(k) and len(v) >= 8),
        key=len,
        reverse=True,
    )


def scrub(value: Any, secrets: list[str] | None = None) -> Any:
    """Replace secrets anywhere in a JSON-like value."""
    secrets = _env_secrets() if secrets is None else secrets
    if isinstance(value, str):
        for secret in secrets:
            value = value.replace(secret, SCRUBBED)
        for pattern in _SECRET_PATTERNS:
            value = pattern.sub(SCRUBBED, value)
        return value
    if isinstance(value, dict):
        return {k: scrub(v, secrets) for k, v in value.items()}
    if isinstance(value, list):
        return [scrub(v, secrets) for v in value]
    return value


def cassette_key(request: Request, run_index: int = 0) -> str:
    if request.temperature > 0 and request.seed is None:
        return request.key(run=run_index)
    return request.key()


def read_cassette(path: Path) -> tuple[dict[str, Any], dict[str, dict[str, Any]]]:
    """Return (metadata, key -> entry). A missing or malformed file is a clear error."""
    if not path.is_file():
        raise LLMError(f"replay: cassette {path} does not exist; record one with --record {path}")
    meta: dict[str, Any] = {}
    entries: dict[str, dict[str, Any]] = {}
    with path.open(encoding="utf-8") as fh:
        for number, line in enumerate(fh, start=1):
            if not line.strip():
                continue
            try:
                item = json.loads(line)
            except json.JSONDecodeError as exc:
                raise LLMError(f"replay: {path}:{number} is not JSON ({exc.msg})") from exc
            if "cassette" in item:
                meta = item
            else:
                entries[item["key"]] = item
    return meta, entries


class RecordingProvider(Wrapper):
    """Passes calls through and appends each new (request, reply) to the cassette."""

    def __init__(self, inner: BaseProvider, path: Path, run_index: int = 0, note: str = "") -> None:
        super().__init__(inner)
        self.path = Path(path)
        self.run_index = run_index
        self._lock = threading.Lock()
        self._known: set[str] = set()
        if self.path.is_file():
            _, entries = read_cassette(self.path)
            self._known = set(entries)
        else:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            meta = {
                "cassette": FORMAT_VERSION,
                "provider": self.name,
                "model": self.model,
                "capabilities": asdict(self.capabilities),
                "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
                "note": note,
            }
            self._append(scrub(meta))

    def _append(self, item: dict[str, Any]) -> None:
        with self._lock, self.path.open("a", encoding="utf-8") as fh:
            fh.write(json.dumps(item, ensure_ascii=False, sort_keys=True) + "\n")

    def send(self, request: Request) -> Completion:
        reply = self.inner.send(request)
        key = cassette_key(request, self.run_index)
        if key not in self._known:
            self._known.add(key)
            self._append(
                scrub(
                    {
                        "key": key,
                        "provider": self.name,
                        "model": reply.model,
                        "request": request.as_dict(),
                        "response": reply.as_record(),
                    }
                )
            )
        return reply


class ReplayProvider(BaseProvider):
    """Answers only from a cassette; an unknown request is an error that names its key."""

    def __init__(self, path: Path, run_index: int = 0) -> None:
        self.path = Path(path)
        self.run_index = run_index
        meta, self._entries = read_cassette(self.path)
        self.name = "replay"
        self.model = str(meta.get("model", "recorded"))
        caps = meta.get("capabilities") or {}
        fields = Capabilities.__dataclass_fields__
        self.capabilities = Capabilities(**{k: v for k, v in caps.items() if k in fields})
        self.recorded_by = str(meta.get("provider", ""))

    def send(self, request: Request) -> Completion:
        started = time.perf_counter()
        key = cassette_key(request, self.run_index)
        entry = self._entries.get(key)
        if entry is None:
            raise ReplayMiss(key, str(self.path), request)
        original = Completion.from_record(entry["response"])
        elapsed = time.perf_counter() - started
        # Report the recorded token counts (they describe the request), but not its seconds.
        recorded = original.usage
        return replace(
            original,
            usage=Usage(
                calls=1,
                prompt_tokens=recorded.prompt_tokens,
                completion_tokens=recorded.completion_tokens,
                seconds=elapsed,
            ),
            latency=elapsed,
            provider=self.name,
            details={
                **original.details,
                "replayed_from": str(self.path),
                "recorded_latency": original.latency,
            },
        )
