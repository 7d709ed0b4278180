"""Static gate: an allow-list of what a script may name, checked before any of it runs.

Generated scripts are untrusted code. This is the first, fast layer; the OS-level
confinement of the worker (`arise.validate.sandbox`) is the one that holds when this one
misses something. A deny-list of spellings cannot win here (allowed modules hand out `os`
and `builtins` under other names, numpy reaches libc, format strings walk attributes), so
the gate allow-lists what each name IS (`arise.validate.identity`):

- imports of a few modules (math, random, numpy's maths, itertools, functools,
  collections) and of Scenic's driving and simulator modules;
- every name it can resolve (an import, an attribute of a module, an alias, a builtin or a
  world-model name) is looked up as the real object, and passes only when that object is
  on the allow-list: a module only if that module is allowed (its attributes then checked
  against its own list, whatever name reached it), no `eval`, `open`, `type`,
  `operator.attrgetter`, `string.Formatter`, Scenic's `model` loader, ...;
- a module may only be used as `module.name`: never aliased (`n = numpy`), passed or
  stored, so no value the gate cannot follow is ever a module;
- `getattr`/`setattr`/`delattr`/`hasattr` only called by name with a literal attribute
  name; no attribute that starts with `_` (except Scenic's documented non-rejecting
  accessors of road-network elements, never on a module), nor any whose name leads to the
  interpreter, files, processes or the network (the floor for run-time values);
- `.format` only called at once on a string literal whose fields do not walk attributes
  or items; no string annotations;
- `model` only a world model we know; `param map` and `localPath` only relative `.xodr`
  paths (the map itself is then chosen by name from the maps we know).
"""

from __future__ import annotations

import ast
import io
import re
import string
import tokenize
from dataclasses import dataclass, field
from importlib.machinery import BuiltinImporter, FrozenImporter, PathFinder
from pathlib import PurePosixPath

from arise.validate import identity
from arise.validate.allowlist import (
    ATTRIBUTE_BUILTINS,
    BARE_BUILTINS,
    DANGEROUS_NAMES,
    MODULE_NAMES,
    SCENIC_INJECTED_NAMES,
    SCENIC_PRIVATE_ACCESSORS,
    STAR_IMPORTABLE,
    is_scenic,
    module_allowed,
    name_of_module_allowed,
    path_components,
)
from arise.validate.identity import UNKNOWN, Values
from arise.validate.scopes import (
    ModuleBindings,
    inner_parts,
    is_function_scope,
    is_scope,
    local_names,
    module_bindings,
    outer_parts,
)
from arise.validate.script_info import KNOWN_MODELS

__all__ = [
    "Refusal",
    "model_refusal",
    "module_allowed",
    "module_exists",
    "scan_tokens",
    "scan_tree",
    "warm",
]


@dataclass(frozen=True)
class Refusal:
    """One thing the gate refused, and where."""

    what: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"line {self.line}: {self.what}"


def warm() -> None:
    """Load what the gate resolves names against (the worker calls this before forking)."""
    identity.warm()


def model_refusal(name: str, line: int, column: int) -> Refusal | None:
    """A `model` line naming anything but a world model we know is refused before any
    import: Scenic (or a lookup of the module) would import it, running its code."""
    if name in KNOWN_MODELS:
        return None
    known = ", ".join(sorted(KNOWN_MODELS))
    return Refusal(f"model '{name}' is not a world model we know ({known})", line, column)


def module_exists(name: str) -> bool:
    """Is there a module of that name? Found without importing anything: looking up
    `a.b` with `importlib.util.find_spec` imports (runs) `a` first, and `a` can be the
    script itself (the worker writes it to a folder on `sys.path`)."""
    parts = name.split(".")
    if not all(part.isidentifier() for part in parts):
        return False
    try:
        spec = None
        for finder in (BuiltinImporter, FrozenImporter, PathFinder):
            spec = finder.find_spec(parts[0])
            if spec is not None:
                break
        for depth in range(2, len(parts) + 1):
            locations = spec.submodule_search_locations if spec is not None else None
            if not locations:
                return False
            spec = PathFinder.find_spec(".".join(parts[:depth]), list(locations))
        return spec is not None
    except (ImportError, ValueError, OSError):
        return False


def _bad_attribute(name: str) -> str | None:
    """Why an attribute name is refused on any object, or None."""
    if name.startswith("_") and name not in SCENIC_PRIVATE_ACCESSORS:
        return f"attribute '.{name}' starts with '_' (private or interpreter internals)"
    if name in ATTRIBUTE_BUILTINS:
        return f"attribute '.{name}' is not allowed: call {name}(obj, 'name') by its own name"
    if name in DANGEROUS_NAMES:
        return f"attribute '.{name}' reaches the interpreter, files, processes or the network"
    return None


def _format_fields_walk(template: str, depth: int = 0) -> bool:
    """True when a format string's fields access attributes or items ('{0.x}', '{a[k]}'),
    also in a field nested in a format spec ('{0:{1.x}}', which str.format expands too)."""
    try:
        parsed = list(string.Formatter().parse(template))
    except ValueError:
        return True  # a broken template is refused rather than guessed at
    for _, name, spec, _ in parsed:
        if name and ("." in name or "[" in name):
            return True
        if spec and "{" in spec and (depth >= 2 or _format_fields_walk(spec, depth + 1)):
            return True
    return False


def _path_problem(value: str) -> str | None:
    path = PurePosixPath(value.replace("\\", "/"))
    if path.is_absolute() or re.match(r"^[A-Za-z]:", value) or value.startswith("~"):
        return f"path '{value}' is absolute; name a map, e.g. 'maps/Town05.xodr'"
    if path.suffix != ".xodr":
        return f"path '{value}' is not an OpenDRIVE map (.xodr)"
    return None


def _static_string(node: ast.AST) -> str | None:
    """The text of a string literal or an f-string over plain names ('{Town}'), else None."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.JoinedStr):
        parts = []
        for value in node.values:
            if isinstance(value, ast.Constant) and isinstance(value.value, str):
                parts.append(value.value)
            elif (
                isinstance(value, ast.FormattedValue)
                and isinstance(value.value, ast.Name)
                and value.format_spec is None
            ):
                parts.append("{" + value.value.id + "}")
            else:
                return None
        return "".join(parts)
    return None


def _dotted(node: ast.AST) -> str:
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        return f"{_dotted(node.value)}.{node.attr}"
    return "(...)"


def _module_attribute_allowed(module: str, name: str) -> bool:
    """May a script read `name` of this module (or package on the way to allowed ones)?"""
    if module_allowed(module):
        return name_of_module_allowed(module, name)
    return name in path_components(module)


def _what_of(module: str) -> str:
    """What a script may use of an allowed module or a package on the way to them."""
    if module in MODULE_NAMES:
        return f"scripts may use only the maths of '{module}'"
    if module_allowed(module):
        return f"scripts may use only the public names of '{module}'"
    leads = ", ".join(sorted(f"'{module}.{c}'" for c in path_components(module)))
    return f"of '{module}', scripts may use only {leads}"


@dataclass
class _Walker(ast.NodeVisitor):
    # Names the script binds anywhere (assignments, loops, arguments, definitions): the
    # floor refuses a dangerous spelling only when it cannot be the script's own value.
    bound: frozenset[str]
    # What each name bound by an import (anywhere in the script) can be.
    imported: dict[str, Values]
    # The names of each star import, with the top-level statement that binds them.
    stars: list[tuple[int, dict[str, Values]]]
    # From which top-level statement a module-level name is surely the script's own.
    module_level: ModuleBindings
    # The top-level statement of the `model` line (-1: none, the model comes first).
    model_statement: int
    parents: dict[int, ast.AST]
    refusals: list[Refusal] = field(default_factory=list)
    refused: set[int] = field(default_factory=set)
    # Locals of the enclosing function-like scopes, innermost last.
    scopes: list[frozenset[str]] = field(default_factory=list)
    statement: int = 0
    memo: dict[int, Values] = field(default_factory=dict)
    # Nodes the walker makes itself (kept alive: `memo` and `parents` key nodes by id).
    made: list[ast.AST] = field(default_factory=list)

    def refuse(self, node: ast.AST, what: str) -> None:
        line = getattr(node, "lineno", 1) or 1
        column = (getattr(node, "col_offset", 0) or 0) + 1
        refusal = Refusal(what, line, column)
        if refusal not in self.refusals:
            self.refusals.append(refusal)
        self.refused.add(id(node))

    # structure ----------------------------------------------------------------------------
    def visit_Module(self, node: ast.Module) -> None:
        for index, statement in enumerate(node.body):
            self.statement = index
            self.visit(statement)

    def visit(self, node: ast.AST) -> None:
        if is_scope(node):
            self._visit_scope(node)
        else:
            super().visit(node)

    def _visit_scope(self, node: ast.AST) -> None:
        self._check_signature(node)
        for part in outer_parts(node):
            self.visit(part)
        function = is_function_scope(node)
        if function:
            self.scopes.append(local_names(node))
        try:
            for part in inner_parts(node):
                self.visit(part)
        finally:
            if function:
                self.scopes.pop()

    def _parent(self, node: ast.AST) -> ast.AST | None:
        return self.parents.get(id(node))

    def _is_attribute_base(self, node: ast.AST) -> bool:
        parent = self._parent(node)
        return isinstance(parent, ast.Attribute) and parent.value is node

    def _is_called(self, node: ast.AST) -> bool:
        parent = self._parent(node)
        return isinstance(parent, ast.Call) and parent.func is node

    # what a name or attribute is ----------------------------------------------------------
    def _name_values(self, node: ast.Name) -> Values:
        name = node.id
        values = list(self.imported.get(name, ()))
        if not any(name in scope for scope in self.scopes):
            for statement, names in self.stars:
                if name in names and not self.module_level.is_own(
                    name, self.statement, after=statement
                ):
                    values += names[name]
            if not self.module_level.is_own(name, self.statement, after=self.model_statement):
                values += identity.model_names(name)
            if not self.module_level.is_own(name, self.statement):
                values += identity.language_names(name)
        return tuple(v for v in values if v is not UNKNOWN)

    def values(self, node: ast.AST) -> Values:
        """The objects an expression can be, as far as the gate can know (else empty)."""
        if id(node) in self.memo:
            return self.memo[id(node)]
        found: list[object] = []
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load):
            found += self._name_values(node)
        elif isinstance(node, ast.Attribute):
            for base in self.values(node.value):
                if identity.is_module(base):
                    if _module_attribute_allowed(identity.module_name(base), node.attr):
                        found += identity.member(base, node.attr)
                else:
                    found += identity.class_attribute(base, node.attr)
        result = tuple(v for v in found if v is not UNKNOWN)
        self.memo[id(node)] = result
        return result

    def _judge(self, node: ast.AST, path: str, values: Values) -> None:
        """Refuse what a name or attribute resolves to, or where a module or getattr is
        used: a module only as `module.name`, getattr only called by its own name."""
        for value in values:
            reason = identity.problem(value)
            if reason:
                self.refuse(node, f"'{path}' is {reason}; scripts may not use it")
                return
        modules = [identity.module_name(v) for v in values if identity.is_module(v)]
        if modules and not self._is_attribute_base(node):
            self.refuse(
                node,
                f"the module '{modules[0]}' may only be used as '{path}.<name>' (a module "
                f"is never aliased, passed or stored; use `import {modules[0]} as name`)",
            )
            return
        family = [n for n in map(identity.attribute_builtin, values) if n]
        if family and not (isinstance(node, ast.Name) and self._is_called(node)):
            self.refuse(
                node,
                f"'{family[0]}' may only be called with a literal attribute name, "
                "not passed around as a value",
            )

    # imports ------------------------------------------------------------------------------
    def visit_Import(self, node: ast.Import) -> None:
        for alias in node.names:
            if not module_allowed(alias.name):
                self.refuse(node, f"import of module '{alias.name}' is not allowed")

    def visit_ImportFrom(self, node: ast.ImportFrom) -> None:
        module = node.module or ""
        if node.level:
            self.refuse(node, "relative imports are not allowed")
            return
        if not module_allowed(module):
            self.refuse(node, f"import from module '{module}' is not allowed")
            return
        for alias in node.names:
            if alias.name == "*":
                if module not in STAR_IMPORTABLE and not is_scenic(module):
                    self.refuse(
                        node, f"'from {module} import *' is not allowed; import the names you use"
                    )
                continue
            if not name_of_module_allowed(module, alias.name):
                self.refuse(node, f"name '{alias.name}' of module '{module}' is not allowed")
                continue
            for value in identity.member(identity.module_named(module), alias.name):
                reason = identity.problem(value)
                if reason:
                    self.refuse(
                        node,
                        f"name '{alias.name}' of module '{module}' is {reason}; "
                        "scripts may not use it",
                    )
                    break

    # names and attributes -----------------------------------------------------------------
    def visit_Name(self, node: ast.Name) -> None:
        if not isinstance(node.ctx, ast.Load):
            return
        self._judge(node, node.id, self.values(node))
        if id(node) in self.refused:
            return
        name = node.id
        if name in ATTRIBUTE_BUILTINS and not self._is_called(node):
            self.refuse(
                node,
                f"'{name}' may only be called with a literal attribute name, "
                "not passed around as a value",
            )
        elif name.startswith("__"):
            self.refuse(node, f"name '{name}' is not allowed (interpreter internals)")
        elif name.startswith("_Scenic") or name in SCENIC_INJECTED_NAMES:
            if not self._own(name):
                self.refuse(node, f"name '{name}' is not allowed (Scenic's compiled internals)")
        elif name in self.imported or name in self.bound:
            return
        elif name.startswith("_") and name != "_":
            self.refuse(node, f"name '{name}' is not allowed (private or internals)")
        elif name in DANGEROUS_NAMES or name in BARE_BUILTINS:
            self.refuse(
                node,
                f"name '{name}' is not allowed (it reaches the interpreter, "
                "files, processes or the network)",
            )

    def _own(self, name: str) -> bool:
        """Is the name surely the script's own where it is read?"""
        return any(name in scope for scope in self.scopes) or self.module_level.is_own(
            name, self.statement
        )

    def visit_Attribute(self, node: ast.Attribute) -> None:
        reason = _bad_attribute(node.attr)
        if reason:
            self.refuse(node, reason)
        else:
            self._check_module_attribute(node)
        if node.attr == "format" and not self._is_called(node):
            self.refuse(
                node, "'.format' may only be called at once on a string literal; use an f-string"
            )
        self.generic_visit(node)

    def _check_module_attribute(self, node: ast.Attribute) -> None:
        modules = [
            identity.module_name(v)
            for v in self.values(node.value)
            if identity.is_module(v) and identity.problem(v) is None
        ]
        for module in modules:
            if node.attr in SCENIC_PRIVATE_ACCESSORS:
                self.refuse(node, f"attribute '.{node.attr}' of a module is not allowed")
                return
            if not _module_attribute_allowed(module, node.attr):
                self.refuse(node, f"'{module}.{node.attr}' is not allowed ({_what_of(module)})")
                return
        if modules and not isinstance(node.ctx, ast.Load):
            self.refuse(node, f"scripts may not change the module '{modules[0]}'")
            return
        if isinstance(node.ctx, ast.Load):
            self._judge(node, _dotted(node), self.values(node))

    # calls --------------------------------------------------------------------------------
    def visit_Call(self, node: ast.Call) -> None:
        func = node.func
        if isinstance(func, ast.Name) and (
            func.id in ATTRIBUTE_BUILTINS
            or any(identity.attribute_builtin(v) for v in self.values(func))
        ):
            self._check_attribute_builtin_call(node, func.id)
        if isinstance(func, ast.Attribute) and func.attr == "format":
            template = func.value
            if not (isinstance(template, ast.Constant) and isinstance(template.value, str)):
                self.refuse(node, "'.format' is allowed only on a string literal; use an f-string")
            elif _format_fields_walk(template.value):
                self.refuse(node, "format fields may not access attributes or items")
        if isinstance(func, ast.Name) and func.id == "localPath":
            self._check_path_argument(node)
        self.generic_visit(node)

    def _check_attribute_builtin_call(self, node: ast.Call, name: str) -> None:
        if len(node.args) < 2:
            self.refuse(node, f"'{name}' needs an object and a literal attribute name")
            return
        attribute = node.args[1]
        if not (isinstance(attribute, ast.Constant) and isinstance(attribute.value, str)):
            self.refuse(node, f"'{name}' with a computed attribute name is not allowed")
            return
        reason = _bad_attribute(attribute.value)
        if reason:
            self.refuse(node, f"'{name}': {reason}")
        elif attribute.value in ("format", "format_map"):
            self.refuse(node, f"'{name}(..., '{attribute.value}')' is not allowed; use an f-string")

    def _check_path_argument(self, node: ast.Call) -> None:
        value = _static_string(node.args[0]) if len(node.args) == 1 and not node.keywords else None
        if value is None:
            self.refuse(
                node, "localPath takes one literal map path, e.g. localPath(f'maps/{Town}.xodr')"
            )
            return
        problem = _path_problem(value)
        if problem:
            self.refuse(node, problem)

    # annotations --------------------------------------------------------------------------
    def _check_annotation(self, annotation: ast.AST | None) -> None:
        if annotation is None:
            return
        for inner in ast.walk(annotation):
            if isinstance(inner, ast.Constant) and isinstance(inner.value, str):
                self.refuse(
                    inner, "string annotations are not allowed (they are evaluated as code)"
                )
                return

    def _check_signature(self, node: ast.AST) -> None:
        arguments = getattr(node, "args", None)
        if isinstance(arguments, ast.arguments):
            every = [*arguments.posonlyargs, *arguments.args, *arguments.kwonlyargs]
            every += [a for a in (arguments.vararg, arguments.kwarg) if a is not None]
            for argument in every:
                self._check_annotation(argument.annotation)
        self._check_annotation(getattr(node, "returns", None))

    def visit_AnnAssign(self, node: ast.AnnAssign) -> None:
        self._check_annotation(node.annotation)
        self.generic_visit(node)

    # Scenic statements (their node classes come from Scenic's parser) --------------------
    def generic_visit(self, node: ast.AST) -> None:
        kind = type(node).__name__
        if kind == "Model":
            refusal = model_refusal(
                str(getattr(node, "name", "")),
                getattr(node, "lineno", 1) or 1,
                (getattr(node, "col_offset", 0) or 0) + 1,
            )
            if refusal is not None:
                self.refuse(node, refusal.what)
        elif kind == "Param":
            for element in getattr(node, "elts", []) or []:
                if getattr(element, "identifier", None) == "map":
                    self._check_map_param(node, getattr(element, "value", None))
        elif kind == "New":
            # `new Car` calls the class named `Car`: the name is judged like any other.
            name = ast.Name(id=str(getattr(node, "className", "")), ctx=ast.Load())
            ast.copy_location(name, node)
            self.made.append(name)
            self.parents[id(name)] = node
            self.visit_Name(name)
        elif kind in ("WithSpecifier", "PropertyDef"):
            prop = str(getattr(node, "prop", None) or getattr(node, "property", ""))
            if prop.startswith("_"):
                self.refuse(node, f"property '{prop}' starts with '_' (private or internals)")
        super().generic_visit(node)

    def _check_map_param(self, node: ast.AST, value: ast.AST | None) -> None:
        if (
            isinstance(value, ast.Call)
            and isinstance(value.func, ast.Name)
            and value.func.id == "localPath"
        ):
            return  # checked as a call
        text = _static_string(value) if value is not None else None
        if text is None and isinstance(value, ast.Name):
            return  # a name bound to a literal elsewhere (`Town`), resolved by the registry
        if text is None:
            self.refuse(node, "param map must be a literal map path or localPath(...)")
            return
        problem = _path_problem(text)
        if problem:
            self.refuse(node, problem)


def _bound_names(tree: ast.AST) -> frozenset[str]:
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            names.add(node.id)
        elif isinstance(node, ast.arg):
            names.add(node.arg)
        elif isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            names.add(node.name)
        elif type(node).__name__ in ("BehaviorDef", "MonitorDef", "ScenarioDef"):
            names.add(str(getattr(node, "name", "")))
    return frozenset(names)


def _imports(tree: ast.AST) -> dict[str, Values]:
    """What every name bound by an allowed import (not `*`) can be; refused imports bind
    nothing. Collected over the whole script: a name imported anywhere can be that."""
    bound: dict[str, list[object]] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if module_allowed(alias.name):
                    target = alias.name if alias.asname else alias.name.split(".")[0]
                    loaded = identity.module_named(target)
                    bound.setdefault(alias.asname or target, []).append(
                        loaded if loaded is not None else UNKNOWN
                    )
        elif isinstance(node, ast.ImportFrom) and not node.level:
            module = node.module or ""
            if not module_allowed(module):
                continue
            source = identity.module_named(module)
            for alias in node.names:
                if alias.name != "*" and name_of_module_allowed(module, alias.name):
                    bound.setdefault(alias.asname or alias.name, []).extend(
                        identity.member(source, alias.name) if source is not None else [UNKNOWN]
                    )
    return {name: tuple(values) for name, values in bound.items()}


def _star_imports(tree: ast.AST) -> list[tuple[int, dict[str, Values]]]:
    """The names each `from module import *` binds, with its top-level statement."""
    found = []
    for index, statement in enumerate(getattr(tree, "body", [])):
        for node in ast.walk(statement):
            if (
                isinstance(node, ast.ImportFrom)
                and not node.level
                and module_allowed(node.module or "")
                and any(alias.name == "*" for alias in node.names)
            ):
                found.append((index, identity.exports(identity.module_named(node.module or ""))))
    return found


def _parents(tree: ast.AST) -> dict[int, ast.AST]:
    return {id(child): node for node in ast.walk(tree) for child in ast.iter_child_nodes(node)}


def _model_statement(tree: ast.AST) -> int:
    for index, statement in enumerate(getattr(tree, "body", [])):
        if type(statement).__name__ == "Model":
            return index
    return -1


def scan_tree(tree: ast.AST) -> list[Refusal]:
    """Refusals found in a parsed (Scenic or Python) syntax tree."""
    walker = _Walker(
        bound=_bound_names(tree),
        imported=_imports(tree),
        stars=_star_imports(tree),
        module_level=module_bindings(tree),
        model_statement=_model_statement(tree),
        parents=_parents(tree),
    )
    walker.visit(tree)
    return sorted(walker.refusals, key=lambda r: (r.line, r.column))


_IMPORT_LINE = re.compile(r"^\s*(?:from\s+(\.*[\w.]*)\s+import|import\s+([\w.]+))")


def scan_tokens(text: str) -> list[Refusal]:
    """Fallback for text that does not parse: look at tokens and import lines only."""
    refusals: list[Refusal] = []
    for number, line in enumerate(text.splitlines(), start=1):
        match = _IMPORT_LINE.match(line)
        if match:
            module = match.group(1) or match.group(2) or ""
            if module.startswith(".") or not module_allowed(module):
                refusals.append(
                    Refusal(
                        f"import of module '{module}' is not allowed",
                        number,
                        line.index(module) + 1 if module in line else 1,
                    )
                )
    tokens: list[tokenize.TokenInfo] = []
    try:
        for token in tokenize.generate_tokens(io.StringIO(text).readline):
            tokens.append(token)
    except (tokenize.TokenError, IndentationError, SyntaxError):
        pass  # keep the tokens read before the error
    statements = {
        number
        for number, line in enumerate(text.splitlines(), start=1)
        if _IMPORT_LINE.match(line) or re.match(r"^\s*model\s", line)
    }
    for previous, token in zip([None, *tokens], tokens, strict=False):
        if token.type != tokenize.NAME or token.start[0] in statements:
            continue
        after_dot = previous is not None and previous.string == "."
        where = (token.start[0], token.start[1] + 1)
        if after_dot and _bad_attribute(token.string):
            refusals.append(Refusal(str(_bad_attribute(token.string)), *where))
        elif not after_dot and (
            token.string in DANGEROUS_NAMES | BARE_BUILTINS or token.string.startswith("__")
        ):
            refusals.append(Refusal(f"name '{token.string}' is not allowed", *where))
    return sorted(refusals, key=lambda r: (r.line, r.column))
