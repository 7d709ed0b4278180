"""What one benchmark run leaves behind: plain data shared by the runner, store and report.

A row is read from the run's report (`Generation.report()`, what report.json holds), so a
bench row and a report.json never disagree.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any

from arise.generate.options import Mode
from arise.generate.run import AttemptKind, RunStatus

MESSAGE_CHARS = 500  # a diagnostic's message is cut to this in the attempts table


@dataclass(frozen=True)
class BenchTask:
    """One generation to do; the key decides whether a resumed benchmark skips it."""

    prompt_id: str
    category: str
    description: str
    mode: Mode
    temperature: float
    run_index: int
    truth: str | None = None  # canonical JSON of the prompt's hand-written truth

    def __post_init__(self) -> None:
        object.__setattr__(self, "mode", Mode(self.mode))  # also when read as text

    @property
    def key(self) -> tuple[str, Mode, float, int]:
        return (self.prompt_id, self.mode, round(self.temperature, 4), self.run_index)

    def label(self) -> str:
        return f"{self.prompt_id}/{self.mode}-t{self.temperature:g}-r{self.run_index}"


@dataclass(frozen=True)
class AttemptRecord:
    index: int
    kind: AttemptKind
    ok: bool
    stage: str | None = None
    error_type: str | None = None
    message: str | None = None
    section: str | None = None
    check_seconds: float = 0.0
    llm_calls: int = 0
    tokens: int = 0

    def __post_init__(self) -> None:
        object.__setattr__(self, "kind", AttemptKind(self.kind))  # also when read as text

    @classmethod
    def from_report(cls, attempt: dict[str, Any]) -> AttemptRecord:
        """From one item of a report's "attempts"."""
        diagnostic = attempt.get("diagnostic") or {}
        llm = attempt.get("llm") or {}
        message = diagnostic.get("message")
        return cls(
            index=attempt["index"],
            kind=attempt["kind"],
            ok=attempt["ok"],
            stage=diagnostic.get("stage"),
            error_type=diagnostic.get("error_type"),
            message=message[:MESSAGE_CHARS] if message is not None else None,
            section=diagnostic.get("section"),
            check_seconds=attempt["check_seconds"],
            llm_calls=llm.get("calls", 0),
            tokens=llm.get("prompt_tokens", 0) + llm.get("completion_tokens", 0),
        )


@dataclass
class RunRecord:
    """A finished run (a success, a failure, a refusal or a provider error)."""

    task: BenchTask
    status: RunStatus
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
    # The confinement label of the final check (`sandbox.label`), None if none ran.
    sandbox: str | None = None
    # Facts read from the trace against the prompt's hand-written truth (evaluate.fidelity).
    fidelity: dict[str, Any] | None = None
    # The semantic gate's verdict on the final script ("off", "passed", "contradicts",
    # "not_reached") and the seconds of attempts made only because of it.
    gate: str = "off"
    gate_seconds: float = 0.0
    # The executed script driven by `--agent` (an `arise.drive.records.DriveRecord` as JSON:
    # its status, SafeBench's metrics and its collision replay), None when not driven.
    driving: dict[str, Any] | None = None

    def __post_init__(self) -> None:
        self.status = RunStatus(self.status)  # also when read as text

    @property
    def ok(self) -> bool:
        return self.status is RunStatus.EXECUTED

    @property
    def tokens(self) -> int:
        return self.prompt_tokens + self.completion_tokens

    @property
    def scs(self) -> float | None:
        value = (self.judge or {}).get("scs")
        return float(value) if isinstance(value, int | float) else None

    @property
    def fidelity_score(self) -> float | None:
        value = (self.fidelity or {}).get("score")
        return float(value) if isinstance(value, int | float) else None

    @property
    def gate_on(self) -> bool:
        return self.gate != "off"

    @property
    def conformity_score(self) -> float | None:
        value = (self.conformity or {}).get("score")
        return float(value) if isinstance(value, int | float) else None

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_report(
        cls,
        task: BenchTask,
        report: dict[str, Any],
        *,
        out_dir: str | None,
        criticality: dict[str, Any] | None,
    ) -> RunRecord:
        """The row of a run from its report (see `Generation.report`)."""
        llm = report.get("llm") or {}
        gate = report.get("semantic_gate") or {}
        return cls(
            task=task,
            status=report["status"],
            first_pass_ok=report["first_pass_ok"],
            repairs=report["repairs"],
            llm_calls=llm.get("calls", 0),
            prompt_tokens=llm.get("prompt_tokens", 0),
            completion_tokens=llm.get("completion_tokens", 0),
            seconds=report["seconds"],
            message=report["message"],
            out_dir=out_dir,
            spec=report["spec"],
            conformity=report["conformity"],
            criticality=criticality,
            attempts=[AttemptRecord.from_report(a) for a in report["attempts"]],
            sandbox=_sandbox_label(report.get("sandbox")),
            gate=gate.get("verdict", "off"),
            gate_seconds=gate.get("seconds", 0.0),
        )

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> RunRecord:
        values = dict(data)
        values["task"] = BenchTask(**values["task"])
        values["attempts"] = [AttemptRecord(**a) for a in values.get("attempts", [])]
        return cls(**values)


def _sandbox_label(sandbox: Any) -> str | None:
    if not isinstance(sandbox, dict):
        return None
    from arise.validate.types import SandboxReport

    return SandboxReport.model_validate(sandbox).label
