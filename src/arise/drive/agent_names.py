"""The agent a drive names, checked in the parent before any run: a built-in name, an
entry point of the `arise.agents` group, or `path/to/agent.py:ClassName`.

Nothing of the user's code is imported here (the validation worker loads it); a name that
cannot be an agent is one line before the first run, not the same failure in every run.
"""

from __future__ import annotations

import re
from importlib.metadata import entry_points
from pathlib import Path

from arise.agents.types import BuiltinAgent
from arise.errors import AriseError

BUILT_IN = tuple(agent.value for agent in BuiltinAgent)
ENTRY_POINT_GROUP = "arise.agents"
_CLASS = re.compile(r"^[A-Za-z_]\w{0,127}$")


class AgentNameError(AriseError):
    """The agent cannot be found: unknown name, missing file, or not `FILE.py:Class`."""


def resolve_agent(name: str) -> str:
    """The agent as the worker is told it: a built-in or entry-point name as given, a
    file agent as `ABSOLUTE/PATH.py:Class` (the worker's folder is not the user's)."""
    name = name.strip()
    if name in BUILT_IN:
        return name
    if ":" in name:
        file, _, cls = name.rpartition(":")
        path = Path(file).expanduser()
        if path.suffix != ".py":
            raise AgentNameError(f"agent '{name}': the file must be a .py file (FILE.py:Class)")
        if not _CLASS.match(cls):
            raise AgentNameError(f"agent '{name}': '{cls}' is not a class name (FILE.py:Class)")
        if not path.is_file():
            raise AgentNameError(f"agent '{name}': no such file: {path}")
        return f"{path.resolve()}:{cls}"
    if name in {ep.name for ep in entry_points(group=ENTRY_POINT_GROUP)}:
        return name
    raise AgentNameError(
        f"unknown agent '{name}': use one of {', '.join(BUILT_IN)}, an entry point of the "
        f"'{ENTRY_POINT_GROUP}' group, or path/to/agent.py:ClassName"
    )


def agent_label(agent: str) -> str:
    """Short form for tables and folder names: `agent.py:MyAgent` for a file agent."""
    if ":" in agent:
        file, _, cls = agent.rpartition(":")
        return f"{Path(file).name}:{cls}"
    return agent
