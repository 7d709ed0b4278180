"""What one driven run leaves behind: plain, bounded data shared by the runner, the
store and the report (a database read back is validated like any other input)."""

from __future__ import annotations

from enum import StrEnum
from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field, StringConstraints

from arise.drive.sources import Scenario

Text = Annotated[str, StringConstraints(max_length=4096)]
# A count or flag stays an int (runs.csv shows `collision` as 0 or 1), a measure a float.
Metric = Annotated[int, Field(strict=True)] | Annotated[float, Field(allow_inf_nan=False)] | None
Metrics = Annotated[
    dict[Annotated[str, StringConstraints(pattern=r"^\w{1,64}$")], Metric], Field(max_length=64)
]


class DriveStatus(StrEnum):
    DRIVEN = "driven"  # the scenario ran with the agent in the ego's seat: it has metrics
    FAILED = "failed"  # it did not run (compile, sample or simulate failed): no metrics


class DriveTask(BaseModel):
    """One run to do: a scenario, the agent and the run's seed."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    scenario: Text
    category: Text
    script: Text
    digest: Annotated[str, StringConstraints(pattern=r"^[0-9a-f]{64}$")]
    agent: Text
    run_index: Annotated[int, Field(ge=0)]
    seed: int | None = None

    @classmethod
    def of(cls, scenario: Scenario, agent: str, run_index: int, seed: int | None) -> DriveTask:
        return cls(
            scenario=scenario.id,
            category=scenario.category,
            script=str(scenario.script),
            digest=scenario.digest,
            agent=agent,
            run_index=run_index,
            seed=seed,
        )

    @property
    def key(self) -> tuple[str, str, str, int | None]:
        """What a resumed drive skips: this script's text, this agent, this seed."""
        return (self.scenario, self.digest, self.agent, self.seed)

    def label(self) -> str:
        return f"{self.scenario}/r{self.run_index}"


class DriveRecord(BaseModel):
    """A finished run: its metrics (empty when it failed) and where its replay is."""

    model_config = ConfigDict(extra="forbid")

    task: DriveTask
    status: DriveStatus
    message: Text | None = None
    metrics: Metrics = Field(default_factory=dict)
    seconds: Annotated[float, Field(ge=0, allow_inf_nan=False)] = 0.0
    # The simulated time the run was given (steps x timestep): the overall score's TS term.
    timeout_s: Annotated[float, Field(ge=0, allow_inf_nan=False)] | None = None
    sandbox: Text | None = None
    map: Text | None = None
    # The collision's replay, relative to the drive's folder (collisions/<...>/replay.gif).
    replay: Text | None = None

    @property
    def driven(self) -> bool:
        return self.status is DriveStatus.DRIVEN

    @property
    def collided(self) -> bool:
        return bool(self.metrics.get("collision"))
