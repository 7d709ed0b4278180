"""Why a replay or an export could not be made, said so the user can act on it."""

from __future__ import annotations

from arise.errors import AriseError


class PresentError(AriseError):
    """A replay or an export could not be made."""


class RunNotFound(PresentError):
    """The path is neither a run folder (scenario.scenic + report.json) nor a script."""


class RunNotExecuted(PresentError):
    """The run's final script never executed, so there is no motion to show or export."""


class ScriptDidNotRun(PresentError):
    """Checking the script in the validator failed: its diagnostic is the message."""

    exit_code = 1  # as `arise check` exits for a script that fails


class ExportError(PresentError):
    """The trace cannot be written as OpenSCENARIO (e.g. no agents, no map file)."""
