"""What a name in a script IS: the object behind it, judged by identity, not by spelling.

The gate (`arise.validate.gate`) walks a script's syntax tree; for every name it can
resolve (imports, attributes of modules, and the names a script sees without importing
anything: builtins, Scenic's language, the world model) this module finds the real object
and says whether a script may touch it:

- a module only when the module itself is on the allow-list (or a package on the way to
  one, like `scenic`), whatever name leads to it (`roads.enum`, `regions.scenic`);
- a function or class only when it comes from an allowed module's list, from Scenic (not
  its compiler, `scenic.syntax`, apart from the language it exports to scripts) or from
  arise's world model;
- never a few that run code, open files or walk attributes named by strings (`eval`,
  `open`, `type`, `operator.attrgetter`, `string.Formatter`, `typing.get_type_hints`,
  Scenic's `model` loader and its file recorders).

Allowed modules are imported here (the worker has imported them already). Scenic's own
`.scenic` modules (world models, behaviors) can only be imported while Scenic compiles, so
the names they import are read from their source text instead.
"""

from __future__ import annotations

import ast
import builtins
import functools
import importlib
import inspect
import io
import sys
import textwrap
import tokenize
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import BuiltinFunctionType, FunctionType, MethodType, ModuleType
from typing import Any

from arise.validate.allowlist import (
    AMBIENT_MODELS,
    MODULE_NAMES,
    module_allowed,
    path_components,
)


class _Unknown:
    """A value the gate cannot know before the script runs (judged by its name only)."""

    def __repr__(self) -> str:
        return "UNKNOWN"


UNKNOWN: Any = _Unknown()
Values = tuple[Any, ...]


@dataclass(frozen=True)
class ScenicSource:
    """A `.scenic` module read from its text: the names its imports bind. Names it
    defines itself (classes, behaviors, constants) are Scenic's own and absent here."""

    name: str
    names: Mapping[str, Values] = field(default_factory=dict)


def is_module(value: object) -> bool:
    return isinstance(value, ModuleType | ScenicSource)


def module_name(value: object) -> str:
    return value.name if isinstance(value, ScenicSource) else str(getattr(value, "__name__", ""))


# --- finding modules ----------------------------------------------------------------------
_reading: set[str] = set()


@functools.cache
def module_named(name: str) -> ModuleType | ScenicSource | None:
    """The module of that name (imported if need be), or None when it cannot be loaded.
    Called only for allowed modules, packages on the way to them and the imports of
    Scenic's own modules: trusted code."""
    loaded = sys.modules.get(name)
    if loaded is not None:
        return loaded
    source = _scenic_source(name)
    if source is not None:
        return _read_scenic_module(name, source)
    try:
        return importlib.import_module(name)
    except Exception:  # noqa: BLE001  (a module that cannot load cannot be used either)
        return None


def _scenic_source(name: str) -> Path | None:
    parent, _, last = name.rpartition(".")
    if not parent:
        return None
    package = module_named(parent)
    for folder in getattr(package, "__path__", None) or []:
        for suffix in (".scenic", ".sc"):
            candidate = Path(folder) / f"{last}{suffix}"
            if candidate.is_file():
                return candidate
    return None


def member(module: object, attribute: str) -> Values:
    """What `module.attribute` can be (UNKNOWN: not knowable, e.g. defined by a `.scenic`
    module itself)."""
    if isinstance(module, ScenicSource):
        return module.names.get(attribute, (UNKNOWN,))
    if not isinstance(module, ModuleType):
        return (UNKNOWN,)
    submodule = f"{module.__name__}.{attribute}"
    if module_allowed(submodule) or path_components(submodule):
        loaded = module_named(submodule)
        if loaded is not None:
            return (loaded,)
    if attribute in vars(module):
        return (vars(module)[attribute],)
    try:
        return (getattr(module, attribute),)  # a lazily loaded attribute (numpy's)
    except Exception:  # noqa: BLE001  (absent: the script fails on it by itself)
        return (UNKNOWN,)


def exports(module: object) -> dict[str, Values]:
    """The names `from module import *` binds, and what each can be."""
    if isinstance(module, ScenicSource):
        return {k: v for k, v in module.names.items() if not k.startswith("_")}
    if not isinstance(module, ModuleType):
        return {}
    listed = getattr(module, "__all__", None)
    names = (
        [str(n) for n in listed]
        if isinstance(listed, list | tuple)
        else [n for n in vars(module) if not n.startswith("_")]
    )
    return {name: member(module, name) for name in names}


def class_attribute(value: object, attribute: str) -> Values:
    """`Class.attribute` found without running any code, for classes of Scenic or arise's
    world model (others are judged by the attribute's name only)."""
    if not isinstance(value, type) or not _trusted_callable_origin(value.__module__):
        return (UNKNOWN,)
    found = inspect.getattr_static(value, attribute, UNKNOWN)
    if isinstance(found, staticmethod | classmethod):
        found = found.__func__
    return (found,)


# --- reading Scenic's own modules -----------------------------------------------------------
#: Block headers under which an import still binds a module-level name.
_MODULE_LEVEL_BLOCKS = frozenset(
    {"if", "elif", "else", "try", "except", "finally", "with", "for", "while"}
)


def _read_scenic_module(name: str, path: Path) -> ScenicSource:
    if name in _reading:  # an import cycle: the names of the outer read are not needed
        return ScenicSource(name)
    _reading.add(name)
    try:
        names: dict[str, Values] = {}
        for statement in module_level_imports(path.read_text(encoding="utf-8")):
            for bound, values in _import_bindings(statement, name).items():
                names[bound] = names.get(bound, ()) + values
        return ScenicSource(name, names)
    finally:
        _reading.discard(name)


def module_level_imports(text: str) -> Iterator[ast.Import | ast.ImportFrom]:
    """The import statements of a Scenic source that bind module-level names (also inside
    `try`/`if` blocks, not inside definitions), parsed as Python."""
    lines = text.splitlines(keepends=True)
    blocks: list[str] = []
    header: str | None = None
    first: tokenize.TokenInfo | None = None
    last: tokenize.TokenInfo | None = None
    for token in tokenize.generate_tokens(io.StringIO(text).readline):
        if token.type == tokenize.INDENT:
            blocks.append(header or "")
        elif token.type == tokenize.DEDENT:
            blocks.pop()
        elif token.type in (tokenize.NEWLINE, tokenize.ENDMARKER):
            if first is not None and last is not None:
                if first.string in ("import", "from") and all(
                    b in _MODULE_LEVEL_BLOCKS for b in blocks
                ):
                    segment = textwrap.dedent("".join(lines[first.start[0] - 1 : token.end[0]]))
                    yield from (
                        node
                        for node in ast.parse(segment).body
                        if isinstance(node, ast.Import | ast.ImportFrom)
                    )
                header = first.string if last.string == ":" else None
            first = last = None
        elif token.type not in (tokenize.NL, tokenize.COMMENT, tokenize.ENCODING):
            first = first or token
            last = token


def _absolute(module: str | None, level: int, importer: str) -> str:
    if not level:
        return module or ""
    base = importer.rsplit(".", level)[0]
    return f"{base}.{module}" if module else base


def _import_bindings(statement: ast.Import | ast.ImportFrom, importer: str) -> dict[str, Values]:
    """The names an import statement binds and what each can be."""
    bound: dict[str, Values] = {}
    if isinstance(statement, ast.Import):
        for alias in statement.names:
            target = alias.name if alias.asname else alias.name.split(".")[0]
            loaded = module_named(target)
            bound[alias.asname or target] = (loaded if loaded is not None else UNKNOWN,)
        return bound
    source = module_named(_absolute(statement.module, statement.level, importer))
    if source is None:
        return {alias.asname or alias.name: (UNKNOWN,) for alias in statement.names}
    for alias in statement.names:
        if alias.name == "*":
            bound.update(exports(source))
        else:
            bound[alias.asname or alias.name] = member(source, alias.name)
    return bound


# --- what a script sees without importing anything --------------------------------------------
@functools.cache
def _language() -> dict[str, Values]:
    """Builtins and Scenic's language (`scenic.syntax.veneer.__all__`)."""
    from scenic.syntax import veneer

    names: dict[str, Values] = {name: (value,) for name, value in vars(builtins).items()}
    for name in veneer.__all__:
        names[name] = (getattr(veneer, name),)
    return names


@functools.cache
def _world_models() -> dict[str, Values]:
    """The names every world model we know gives a script (`model X` binds them)."""
    names: dict[str, Values] = {}
    for model in AMBIENT_MODELS:
        for name, values in exports(module_named(model)).items():
            names[name] = names.get(name, ()) + values
    return names


def language_names(name: str) -> Values:
    return _language().get(name, ())


def model_names(name: str) -> Values:
    return _world_models().get(name, ())


# --- the verdict ------------------------------------------------------------------------------
_BUILTIN_REASONS = {
    "eval": "runs code",
    "exec": "runs code",
    "compile": "builds code",
    "open": "opens files",
    "__import__": "imports modules",
    "vars": "lists an object's internals",
    "globals": "lists the interpreter's globals",
    "locals": "lists a frame's locals",
    "dir": "lists what an object hides",
    "breakpoint": "starts the debugger",
    "input": "reads the terminal",
    "help": "starts the help system",
    "memoryview": "reads raw memory",
    "type": "builds classes and reaches their internals",
    "object": "reaches every class of the interpreter",
    "super": "reaches class internals",
    "classmethod": "builds class internals",
    "staticmethod": "builds class internals",
    "property": "builds class internals",
    "exit": "ends the process",
    "quit": "ends the process",
    "copyright": "reads files",
    "credits": "reads files",
    "license": "reads files",
}
_ATTRIBUTE_BUILTINS = ("getattr", "setattr", "delattr", "hasattr")
_HARMLESS_TYPING = (
    "Any",
    "Optional",
    "Union",
    "List",
    "Tuple",
    "Dict",
    "Set",
    "FrozenSet",
    "Sequence",
    "Mapping",
    "Iterable",
    "Callable",
)


@dataclass
class _Tables:
    denied: dict[int, tuple[object, str]] = field(default_factory=dict)
    allowed: dict[int, object] = field(default_factory=dict)
    attribute_builtins: dict[int, str] = field(default_factory=dict)

    def deny(self, value: object, reason: str) -> None:
        self.denied[id(value)] = (value, reason)

    def allow(self, value: object) -> None:
        if not is_module(value):
            self.allowed[id(value)] = value


@functools.cache
def _tables() -> _Tables:
    import operator
    import string
    import typing

    from scenic.core import sensors
    from scenic.syntax import veneer

    tables = _Tables()
    for name, reason in _BUILTIN_REASONS.items():
        if name in vars(builtins):
            tables.deny(vars(builtins)[name], f"the builtin '{name}', which {reason}")
    for name in _ATTRIBUTE_BUILTINS:
        tables.attribute_builtins[id(vars(builtins)[name])] = name
    walks = "which walks attributes named by strings"
    tables.deny(operator.attrgetter, f"'operator.attrgetter', {walks}")
    tables.deny(operator.methodcaller, f"'operator.methodcaller', {walks}")
    tables.deny(string.Formatter, f"'string.Formatter', {walks}")
    tables.deny(typing.get_type_hints, "'typing.get_type_hints', which evaluates strings as code")
    tables.deny(typing.ForwardRef, "'typing.ForwardRef', which evaluates strings as code")
    tables.deny(veneer.model, "Scenic's model loader, which imports any module by name")
    tables.deny(veneer.With, "Scenic's `with` specifier by a string; write `with name value`")
    tables.deny(sensors.File, "Scenic's recorder to files")
    tables.deny(sensors.Files, "Scenic's recorder to files")
    # The curated lists of the allowed modules, and Scenic's language.
    for module, names in MODULE_NAMES.items():
        loaded = module_named(module)
        if loaded is None:
            continue
        for name in names if names is not None else exports(loaded):
            for value in member(loaded, name):
                tables.allow(value)
    for name in _HARMLESS_TYPING:
        tables.allow(getattr(typing, name))
    for name in veneer.__all__:
        value = getattr(veneer, name)
        if id(value) not in tables.denied:
            tables.allow(value)
    return tables


def warm() -> None:
    """Import and read everything the verdicts need (in the worker, before it forks, so
    that each check only walks its own script)."""
    _tables()
    _language()
    _world_models()


def attribute_builtin(value: object) -> str | None:
    """'getattr' (or setattr, delattr, hasattr) when the value is that builtin."""
    return _tables().attribute_builtins.get(id(value))


def problem(value: object, depth: int = 0) -> str | None:
    """Why a script may not touch this object (a noun phrase), or None."""
    if value is UNKNOWN:
        return None
    if is_module(value):
        name = module_name(value)
        if module_allowed(name) or path_components(name):
            return None
        return f"the module '{name}'"
    tables = _tables()
    if id(value) in tables.denied:
        return tables.denied[id(value)][1]
    if id(value) in tables.allowed or id(value) in tables.attribute_builtins:
        return None
    if isinstance(value, tuple | list | set | frozenset | dict):
        return _container_problem(value, depth)
    origin = _origin(value)
    if callable(value):
        if _trusted_callable_origin(origin):
            return None
    elif _trusted_data_origin(origin):
        return None
    what = getattr(value, "__qualname__", None) or type(value).__qualname__
    return f"'{what}' of module '{origin}', which is not on the allow-list"


def _container_problem(value: Any, depth: int) -> str | None:
    if depth >= 3:
        return None if len(value) == 0 else "a nested container the gate cannot inspect"
    items = list(value.items()) if isinstance(value, dict) else list(value)
    if len(items) > 256:
        return "a container too large for the gate to inspect"
    for item in items:
        for part in item if isinstance(value, dict) else (item,):
            reason = problem(part, depth + 1)
            if reason:
                return f"a container holding {reason}"
    return None


def _origin(value: object) -> str:
    """The module that defines a function or class (for an instance: its class's)."""
    try:
        if isinstance(value, type | FunctionType | BuiltinFunctionType | MethodType):
            origin = getattr(value, "__module__", None)
            owner = getattr(value, "__self__", None)
            if origin is None and owner is not None and not is_module(owner):
                return _origin(owner)
            return str(origin)
        return str(type(value).__module__)
    except Exception:  # noqa: BLE001  (an object that hides where it comes from is refused)
        return "<unknown>"


def _trusted_callable_origin(origin: str) -> bool:
    """Functions and classes from here are allowed unless denied above."""
    return (
        origin == "builtins"
        or (origin.startswith("scenic.") and not origin.startswith("scenic.syntax"))
        or origin.startswith("arise.validate.worldmodel")
    )


def _trusted_data_origin(origin: str) -> bool:
    """Instances of classes from here are data (an array, a lane, a region)."""
    top = origin.split(".")[0]
    return _trusted_callable_origin(origin) or top in {m.split(".")[0] for m in MODULE_NAMES}
