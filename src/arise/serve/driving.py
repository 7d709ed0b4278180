"""The agent pick of the page: which driving agents a checked script can be driven by,
and the metrics shown beside its replay.

The server offers the built-in agents only: a name from a web request must never make
the server import a file (`path/to/agent.py:Class` is for `arise drive` on one's own
machine). The metrics are computed in the check process, like the rest of the view.
"""

from __future__ import annotations

from typing import Any

from arise.agents.types import BuiltinAgent
from arise.drive.measure import measure
from arise.drive.report import TABLE
from arise.errors import AriseError
from arise.serve.errors import BadInput
from arise.validate.types import CheckResult

#: What each built-in is, for the page's list (docs/agents.md has the details).
AGENT_NOTES = {
    BuiltinAgent.SCRIPTED: "the script's own ego behavior: the reference",
    BuiltinAgent.IDM: "Intelligent Driver Model with pure-pursuit steering; stops for red "
    "lights, stop lines and actors in its path",
    BuiltinAgent.CAUTIOUS: "the world model's lane follower with emergency braking",
    BuiltinAgent.BLIND: "keeps its route and speed and reacts to nothing",
}


def agent_choices() -> list[dict[str, str]]:
    return [{"name": agent.value, "note": AGENT_NOTES[agent]} for agent in BuiltinAgent]


def admit_agent(name: str | None) -> str | None:
    """The agent a check asked for (None: the script as it is, no metrics); BadInput for a
    name the server does not offer."""
    if name is None or not name.strip():
        return None
    if name.strip() not in {agent.value for agent in BuiltinAgent}:
        offered = ", ".join(agent.value for agent in BuiltinAgent)
        raise BadInput(f"unknown agent '{name.strip()[:64]}': the server offers {offered}")
    return name.strip()


def driving_view(result: CheckResult, agent: str, steps: int) -> dict[str, Any]:
    """The metrics of a check that ran with `agent`, as the page's table."""
    assert result.simulation is not None
    view: dict[str, Any] = {"agent": agent, "metrics": [], "error": None}
    try:
        metrics = measure(result, steps * result.simulation.timestep)
    except AriseError as error:
        view["error"] = f"no metrics: {error}"
        return view
    view["collision"] = bool(metrics.get("collision"))
    view["metrics"] = [
        {
            "label": column.label,
            "metric": column.metric,
            "meaning": column.meaning,
            "value": metrics.get(column.metric),
        }
        for column in TABLE
    ]
    return view
