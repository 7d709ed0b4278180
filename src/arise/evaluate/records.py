"""What one benchmark run leaves behind: plain data shared by the runner, store and report."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any


@dataclass(frozen=True)
class BenchTask:
    """One generation to do; the key decides whether a resumed benchmark skips it."""

    prompt_id: str
    category: str
    description: str
    mode: str
    temperature: float
    run_index: int

    @property
    def key(self) -> tuple[str, str, float, int]:
        return (self.prompt_id, self.mode, round(self.temperature, 4), self.run_index)

    def label(self) -> str:
        return f"{self.prompt_id}/{self.mode}-t{self.temperature:g}-r{self.run_index}"


@dataclass(frozen=True)
class AttemptRecord:
    index: int
    kind: str
    ok: bool
    stage: str | None = None
    error_type: str | None = None
    message: str | None = None
    section: str | None = None
    check_seconds: float = 0.0
    llm_calls: int = 0
    tokens: int = 0


@dataclass
class RunRecord:
    """A finished run (a success, a failure, a refusal or a provider error)."""

    task: BenchTask
    status: str
    first_pass_ok: bool
    repairs: int
    llm_calls: int = 0
    prompt_tokens: int = 0
    completion_tokens: int = 0
    seconds: float = 0.0
    message: str | None = None
    out_dir: str | None = None
    spec: dict[str, Any] | None = None
    conformity: dict[str, Any] | None = None
    criticality: dict[str, Any] | None = None
    judge: dict[str, Any] | None = None
    attempts: list[AttemptRecord] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return self.status == "executed"

    @property
    def tokens(self) -> int:
        return self.prompt_tokens + self.completion_tokens

    @property
    def scs(self) -> float | None:
        value = (self.judge or {}).get("scs")
        return float(value) if isinstance(value, int | float) else None

    @property
    def conformity_score(self) -> float | None:
        value = (self.conformity or {}).get("score")
        return float(value) if isinstance(value, int | float) else None

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> RunRecord:
        values = dict(data)
        values["task"] = BenchTask(**values["task"])
        values["attempts"] = [AttemptRecord(**a) for a in values.get("attempts", [])]
        return cls(**values)
