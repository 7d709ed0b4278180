"""The agent a drive names, checked in the parent before any run (`arise.agents`'s
`check_agent_spec`: nothing of the user's code is imported here), and its short label."""

from __future__ import annotations

from pathlib import Path

from arise.agents import check_agent_spec
from arise.drive.sources import safe_part


def resolve_agent(name: str) -> str:
    """The agent as the worker is told it (a file agent's path made absolute); AgentError,
    one line, for a name that cannot be an agent."""
    return check_agent_spec(name).text


def agent_label(agent: str) -> str:
    """Short form for tables and folder names: `agent.py:MyAgent` for a file agent."""
    if ":" in agent:
        file, _, cls = agent.rpartition(":")
        return f"{Path(file).name}:{cls}"
    return agent


def agent_folder_part(agent: str) -> str:
    """The agent's label as part of a folder name (`agent.py-MyAgent`): a drive's replays
    and a run's search folder name it the same way."""
    return safe_part(agent_label(agent).replace(":", "-"), "agent")
