"""Which of a script's names are its own, so that the gate knows when a name can still be
the builtin or world-model object of that name.

A name is the script's own inside a function (or lambda, comprehension, behavior, monitor,
scenario) that binds it: Python never looks further for it there. At module level a name
is the script's own only after a statement that binds it unconditionally has run (and
nothing deletes it): before that, `dir` or `model` is still the builtin or Scenic's. This
is what lets a script call a variable `dir` without letting `x = open` through.
"""

from __future__ import annotations

import ast
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field

#: Scenic's definitions whose bodies are function scopes (Scenic keeps their locals apart).
SCENIC_FUNCTIONS = ("BehaviorDef", "MonitorDef", "ScenarioDef")
COMPREHENSIONS = (ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp)
FUNCTIONS = (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)


def is_function_scope(node: ast.AST) -> bool:
    return isinstance(node, FUNCTIONS + COMPREHENSIONS) or type(node).__name__ in SCENIC_FUNCTIONS


def is_scope(node: ast.AST) -> bool:
    return is_function_scope(node) or isinstance(node, ast.ClassDef)


def _defined_name(node: ast.AST) -> str | None:
    """The name a definition binds in the enclosing scope."""
    if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
        return node.name
    if type(node).__name__ in SCENIC_FUNCTIONS:
        return str(getattr(node, "name", "")) or None
    return None


def _argument_names(arguments: ast.arguments | None) -> set[str]:
    if arguments is None:
        return set()
    every = [*arguments.posonlyargs, *arguments.args, *arguments.kwonlyargs]
    every += [a for a in (arguments.vararg, arguments.kwarg) if a is not None]
    return {a.arg for a in every}


def inner_parts(node: ast.AST) -> list[ast.AST]:
    """The parts of a scope node that run inside the scope (defaults, decorators, bases and
    a comprehension's first iterable run outside it)."""
    if isinstance(node, ast.Lambda):
        return [node.body]
    if isinstance(node, COMPREHENSIONS):
        parts: list[ast.AST] = []
        for index, generator in enumerate(node.generators):
            parts += [generator.target, *generator.ifs]
            if index:
                parts.append(generator.iter)
        if isinstance(node, ast.DictComp):
            return [*parts, node.key, node.value]
        return [*parts, node.elt]
    if isinstance(node, ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
        return list(node.body)
    parts = []
    for name in ("header", "body", "setup", "compose"):
        value = getattr(node, name, None)
        parts += value if isinstance(value, list) else []
    return parts


def outer_parts(node: ast.AST) -> list[ast.AST]:
    """The parts of a scope node evaluated in the enclosing scope."""
    if isinstance(node, COMPREHENSIONS):
        return [node.generators[0].iter]
    if isinstance(node, ast.ClassDef):
        return [*node.decorator_list, *node.bases, *(k.value for k in node.keywords)]
    parts: list[ast.AST] = list(getattr(node, "decorator_list", []) or [])
    arguments = getattr(node, "args", None)
    if isinstance(arguments, ast.arguments):
        parts += [d for d in (*arguments.defaults, *arguments.kw_defaults) if d is not None]
        every = [*arguments.posonlyargs, *arguments.args, *arguments.kwonlyargs]
        every += [a for a in (arguments.vararg, arguments.kwarg) if a is not None]
        parts += [a.annotation for a in every if a.annotation is not None]
    returns = getattr(node, "returns", None)
    if returns is not None:
        parts.append(returns)
    return parts


def _walk(roots: Iterable[ast.AST], stop: Callable[[ast.AST], bool]) -> Iterator[ast.AST]:
    """Every node under `roots` that runs in the same scope: below a node for which `stop`
    holds, only its parts evaluated outside it (defaults, decorators, bases)."""
    pending = list(roots)
    while pending:
        node = pending.pop()
        yield node
        pending.extend(outer_parts(node) if stop(node) else ast.iter_child_nodes(node))


def _bindings(node: ast.AST) -> set[str]:
    """Names a single node binds in the scope it belongs to."""
    if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store | ast.Del):
        return {node.id}
    if isinstance(node, ast.Import | ast.ImportFrom):
        return {
            (alias.asname or alias.name.split(".")[0]) for alias in node.names if alias.name != "*"
        }
    if isinstance(node, ast.ExceptHandler | ast.MatchAs | ast.MatchStar) and node.name:
        return {node.name}
    if isinstance(node, ast.MatchMapping) and node.rest:
        return {node.rest}
    defined = _defined_name(node)
    return {defined} if defined else set()


def local_names(scope: ast.AST) -> frozenset[str]:
    """The names a function-like scope binds itself (its locals, not its `global`s)."""
    names: set[str] = set()
    declared_global: set[str] = set()
    if isinstance(scope, COMPREHENSIONS):
        for generator in scope.generators:
            names |= {n.id for n in ast.walk(generator.target) if isinstance(n, ast.Name)}
        return frozenset(names)
    names |= _argument_names(getattr(scope, "args", None))
    for node in _walk(inner_parts(scope), is_scope):
        if isinstance(node, ast.Global):
            declared_global.update(node.names)
        names |= _bindings(node)
        if isinstance(node, COMPREHENSIONS):  # `:=` in a comprehension binds out here
            names |= _walrus_targets(node)
    return frozenset(names - declared_global)


def _walrus_targets(comprehension: ast.AST) -> set[str]:
    def stop(node: ast.AST) -> bool:
        return is_scope(node) and not isinstance(node, COMPREHENSIONS)

    return {
        n.target.id
        for n in _walk(ast.iter_child_nodes(comprehension), stop)
        if isinstance(n, ast.NamedExpr) and isinstance(n.target, ast.Name)
    }


@dataclass
class ModuleBindings:
    """Module-level names: from which top-level statement each is surely the script's own."""

    own_from: dict[str, int] = field(default_factory=dict)
    deleted: set[str] = field(default_factory=set)

    def is_own(self, name: str, statement: int, after: int = -1) -> bool:
        """Is `name`, read during top-level statement `statement`, surely the script's,
        bound by a statement after statement `after` (the `model` line, which binds the
        world model's names when it runs)?"""
        if name in self.deleted or name not in self.own_from:
            return False
        return after < self.own_from[name] < statement


def module_bindings(tree: ast.AST) -> ModuleBindings:
    found = ModuleBindings()
    found.deleted = {
        n.id for n in ast.walk(tree) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Del)
    }
    for index, statement in enumerate(getattr(tree, "body", [])):
        for name in _unconditional(statement):
            found.own_from.setdefault(name, index)
    return found


def _unconditional(statement: ast.AST) -> set[str]:
    """Names a top-level statement always binds when it completes."""
    if isinstance(statement, ast.Assign):
        targets: list[ast.AST] = list(statement.targets)
    elif isinstance(statement, ast.AnnAssign | ast.AugAssign):
        has_value = not isinstance(statement, ast.AnnAssign) or statement.value is not None
        targets = [statement.target] if has_value else []
    elif isinstance(statement, ast.Import | ast.ImportFrom):
        return _bindings(statement)
    else:
        defined = _defined_name(statement)
        return {defined} if defined else set()
    return {
        n.id
        for target in targets
        for n in ast.walk(target)
        if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)
    }
