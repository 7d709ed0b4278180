"""Agent names: checked in the parent, loaded in the validation worker.

A name is a built-in (`scripted`, `idm`, `cautious`, `blind`), `path/to/agent.py:ClassName`,
or the name of an entry point in the group `arise.agents`. `check_agent_spec` runs in the
parent before any worker starts: it reads no user code (a file must exist and the class
name be an identifier; an entry point must be declared), so a typo is one line, at once.
`load_agent_factory` runs in the worker before it confines itself (the user's agent is
trusted code the script must not be able to reach; docs/security.md) and imports it.
"""

from __future__ import annotations

import hashlib
import importlib.util
import re
import sys
from collections.abc import Callable
from dataclasses import dataclass
from enum import StrEnum
from importlib.metadata import entry_points
from pathlib import Path

from arise.agents.types import Agent, BuiltinAgent
from arise.errors import AriseError

ENTRY_POINT_GROUP = "arise.agents"
_IDENTIFIER = re.compile(r"^[A-Za-z_]\w{0,127}$")
_ENTRY_NAME = re.compile(r"^[A-Za-z_][\w.\-]{0,127}$")
NAMES_HINT = (
    "use scripted, idm, cautious, blind, FILE.py:ClassName, "
    f"or the name of an entry point in the group '{ENTRY_POINT_GROUP}'"
)


class AgentError(AriseError):
    """An agent that cannot be used: an unknown name, a missing file or class, or a
    class that is not an agent."""


class SpecKind(StrEnum):
    BUILTIN = "builtin"
    FILE = "file"
    ENTRY_POINT = "entry_point"


@dataclass(frozen=True)
class AgentSpec:
    """A checked agent name. `text` is the canonical form the worker gets (a file's path
    made absolute: the worker runs in a scratch folder of its own)."""

    kind: SpecKind
    text: str
    builtin: BuiltinAgent | None = None
    path: Path | None = None
    class_name: str | None = None

    @property
    def scripted(self) -> bool:
        return self.builtin is BuiltinAgent.SCRIPTED

    @property
    def needs_preload(self) -> bool:
        """User code: imported by a worker before it is confined, never after."""
        return self.kind is not SpecKind.BUILTIN


def check_agent_spec(name: str | None) -> AgentSpec:
    """The agent a name selects, checked without importing anything; AgentError (one
    line) when it cannot be one. None is the script's own behavior (`scripted`)."""
    text = (name or BuiltinAgent.SCRIPTED.value).strip()
    if text in {agent.value for agent in BuiltinAgent}:
        return AgentSpec(SpecKind.BUILTIN, text, builtin=BuiltinAgent(text))
    if ":" in text:
        file_part, _, class_name = text.rpartition(":")
        if not file_part.endswith(".py"):
            raise AgentError(f"agent '{text}': the part before ':' must be a .py file")
        if not _IDENTIFIER.match(class_name):
            raise AgentError(
                f"agent '{text}': '{class_name}' is not a class name (a Python identifier)"
            )
        path = Path(file_part).expanduser()
        if not path.is_file():
            raise AgentError(f"agent '{text}': no such file: {path}")
        path = path.resolve()
        return AgentSpec(SpecKind.FILE, f"{path}:{class_name}", path=path, class_name=class_name)
    if _ENTRY_NAME.match(text):
        if not any(point.name == text for point in entry_points(group=ENTRY_POINT_GROUP)):
            raise AgentError(f"unknown agent '{text}': {NAMES_HINT}")
        return AgentSpec(SpecKind.ENTRY_POINT, text)
    raise AgentError(f"agent '{text[:100]}' is not an agent name: {NAMES_HINT}")


AgentFactory = Callable[[], Agent]


def load_agent_factory(spec: AgentSpec) -> AgentFactory:
    """What makes one agent per simulation: a built-in's class, or the user's, imported
    now. AgentError when the file does not import, the class is missing or it has no
    `reset` and `act`."""
    if spec.kind is SpecKind.BUILTIN:
        from arise.agents.builtin import BUILTIN_AGENTS

        if spec.builtin is None or spec.builtin not in BUILTIN_AGENTS:
            raise AgentError(f"agent '{spec.text}' is the script's own behavior, not a class")
        return BUILTIN_AGENTS[spec.builtin]
    loaded: object
    if spec.kind is SpecKind.FILE:
        assert spec.path is not None and spec.class_name is not None
        module = _import_file(spec.path)
        if not hasattr(module, spec.class_name):
            raise AgentError(f"agent '{spec.text}': {spec.path.name} has no '{spec.class_name}'")
        loaded = getattr(module, spec.class_name)
    else:
        points = [p for p in entry_points(group=ENTRY_POINT_GROUP) if p.name == spec.text]
        if not points:
            raise AgentError(f"unknown agent '{spec.text}': {NAMES_HINT}")
        try:
            loaded = points[0].load()
        except Exception as error:  # noqa: BLE001  (the user's package: say what broke)
            raise AgentError(
                f"agent '{spec.text}' did not load: {type(error).__name__}: {error}"
            ) from None
    if not isinstance(loaded, type) or not all(
        callable(getattr(loaded, method, None)) for method in ("reset", "act")
    ):
        raise AgentError(
            f"agent '{spec.text}' is not a class with reset(route) and act(observation)"
        )
    return loaded


def _import_file(path: Path) -> object:
    """The user's file as a module of its own name (so two agents never collide)."""
    digest = hashlib.sha256(str(path).encode()).hexdigest()[:12]
    name = f"arise_user_agent_{digest}"
    if name in sys.modules:
        return sys.modules[name]
    module_spec = importlib.util.spec_from_file_location(name, path)
    if module_spec is None or module_spec.loader is None:
        raise AgentError(f"agent file {path} cannot be imported")
    module = importlib.util.module_from_spec(module_spec)
    sys.modules[name] = module
    try:
        module_spec.loader.exec_module(module)
    except Exception as error:  # noqa: BLE001  (the user's code: say what broke)
        del sys.modules[name]
        raise AgentError(
            f"agent file {path.name} did not import: {type(error).__name__}: {error}"
        ) from None
    return module


def make_agent(factory: AgentFactory, spec_text: str) -> Agent:
    """One fresh agent; its constructor's failure is the agent's, said as such."""
    try:
        agent = factory()
    except Exception as error:  # noqa: BLE001
        raise AgentError(
            f"agent '{spec_text}' could not be made: {type(error).__name__}: {error}"
        ) from None
    return agent
