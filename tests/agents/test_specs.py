"""Agent names: a bad one is one line in the parent, before any worker starts."""

from __future__ import annotations

from pathlib import Path

import pytest

from arise.agents import AgentError, check_agent_spec
from arise.agents.builtin import IdmAgent
from arise.agents.loader import SpecKind, load_agent_factory
from arise.agents.types import (
    Agent,
    BuiltinAgent,
    Control,
    EgoRoute,
    LightState,
    SignalKind,
    SignalTrace,
)
from arise.validate.api import check
from arise.validate.types import CheckOptions, Simulator

DATA = Path(__file__).parents[1] / "data"
SCRIPT = DATA / "agents" / "pedestrian_crossing.scenic"


@pytest.mark.parametrize(
    ("name", "words"),
    [
        ("speedy", "unknown agent 'speedy'"),
        ("missing_agent.py:Mine", "no such file"),
        (f"{DATA / 'agents' / 'user_agent.py'}:9lives", "not a class name"),
        ("agent.txt:Mine", "must be a .py file"),
        ("two words", "is not an agent name"),
    ],
)
def test_a_bad_agent_name_is_one_line_before_any_worker(name: str, words: str) -> None:
    with pytest.raises(AgentError) as caught:
        check(SCRIPT, CheckOptions(agent=name))  # no pool: it would have to start one
    message = str(caught.value)
    assert words in message
    assert "\n" not in message


def test_an_agent_in_carla_mode_without_carlas_agents_is_a_clear_error() -> None:
    with pytest.raises(AgentError, match="CARLA's own agents"):
        check(SCRIPT, CheckOptions(agent="idm", simulator=Simulator.CARLA))


def test_names_resolve_to_their_kind() -> None:
    assert check_agent_spec(None).scripted
    assert check_agent_spec("idm").builtin is BuiltinAgent.IDM
    spec = check_agent_spec(str(DATA / "agents" / "user_agent.py") + ":SteadyAgent")
    assert spec.kind is SpecKind.FILE and spec.needs_preload
    assert spec.text.startswith("/") and spec.text.endswith(":SteadyAgent")


def test_a_user_file_loads_into_an_agent() -> None:
    spec = check_agent_spec(str(DATA / "agents" / "user_agent.py") + ":SteadyAgent")
    agent = load_agent_factory(spec)()
    assert isinstance(agent, Agent)
    assert load_agent_factory(check_agent_spec("idm")) is IdmAgent
    with pytest.raises(AgentError, match="has no 'Nobody'"):
        load_agent_factory(check_agent_spec(str(DATA / "agents" / "user_agent.py") + ":Nobody"))


def test_control_is_clamped_and_a_nan_is_the_agents_fault() -> None:
    assert Control(throttle=2.0, brake=-1.0, steer=-3.0).clamped() == Control(1.0, 0.0, -1.0)
    with pytest.raises(ValueError, match="not finite"):
        Control(throttle=float("nan")).clamped()


def test_trace_types_are_strict_and_a_signal_tells_its_state() -> None:
    signal = SignalTrace(
        id="j/r",
        kind=SignalKind.TRAFFIC_LIGHT,
        stop_line=((0.0, 0.0), (3.5, 0.0)),
        states=[(0, LightState.GREEN), (100, LightState.YELLOW), (130, LightState.RED)],
    )
    assert signal.state_at(99) is LightState.GREEN
    assert signal.state_at(130) is LightState.RED
    with pytest.raises(ValueError):
        EgoRoute(waypoints=[(0.0, float("inf"))], target_speed=5)
    with pytest.raises(ValueError):
        EgoRoute(waypoints=[(0.0, 0.0)], target_speed=5, extra=1)  # type: ignore[call-arg]
