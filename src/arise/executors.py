"""Where the bench, the drive and the search run their jobs: one choice for all three."""

from __future__ import annotations

from enum import StrEnum

from arise.errors import AriseError


class Executor(StrEnum):
    LOCAL = "local"  # this machine: processes or threads sharing a pool of confined workers
    RAY = "ray"  # one Ray actor per worker, each with its own confined process


class ExecutorUnavailable(AriseError):
    """The job cannot run on the executor asked for (unknown, or Ray is missing)."""


def parse_executor(text: str) -> Executor:
    """`--executor`'s value as an Executor; ExecutorUnavailable (one line) for any other."""
    try:
        return Executor(text.strip().lower())
    except ValueError:
        names = ", ".join(member.value for member in Executor)
        raise ExecutorUnavailable(f"--executor is one of {names} (got '{text}')") from None
