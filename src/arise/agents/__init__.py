"""Driving agents that take the ego's seat: the typed interface, the built-in drivers and
the loader for a user's own (docs/agents.md)."""
