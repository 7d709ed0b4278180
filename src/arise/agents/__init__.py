"""Driving agents that take the ego's seat: the typed interface (`types`), the built-in
drivers (`builtin`) and the loader for a user's own (`loader`); docs/agents.md."""

from arise.agents.loader import AgentError, AgentSpec, check_agent_spec

__all__ = ["AgentError", "AgentSpec", "check_agent_spec"]
