"""Proving a Scenic script executes: gate, compile, sample, simulate, diagnose."""

from arise.validate.api import check, check_text
from arise.validate.pool import WorkerPool
from arise.validate.types import CheckOptions, CheckResult, Diagnostic, Stage

__all__ = [
    "CheckOptions",
    "CheckResult",
    "Diagnostic",
    "Stage",
    "WorkerPool",
    "check",
    "check_text",
]
