"""Static gate: an allow-list of what a script may name, checked before any of it runs.

Generated scripts are untrusted code. This is the first, fast layer; the OS-level
confinement of the worker (`arise.validate.sandbox`) is the one that holds when this one
misses something. A deny-list cannot win here (allowed modules hand out `os` through
private attributes, numpy reaches libc, format strings walk attributes), so the gate
admits only what scenarios need:

- imports of a few modules (math, random, numpy's maths, itertools, functools,
  collections) and of Scenic's driving and simulator modules;
- attributes of those modules only from a list of public names (numpy without its I/O,
  `ctypeslib` or `lib`);
- no attribute that starts with `_`, except Scenic's documented non-rejecting accessors
  of road-network elements (`_laneToLeft`, `_laneSection`, ...), never on a module;
- no names or attributes that lead to the interpreter, files, processes or the network;
- no string annotations, no attribute or index access inside format strings;
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
from pathlib import PurePosixPath

from arise.validate.script_info import KNOWN_MODELS

# --- what a script may import, and which names of each module it may use ---------------
_MATH_NAMES = None  # every public name of math is pure arithmetic
_RANDOM_NAMES = frozenset(
    {
        "random",
        "uniform",
        "gauss",
        "normalvariate",
        "lognormvariate",
        "expovariate",
        "vonmisesvariate",
        "gammavariate",
        "betavariate",
        "paretovariate",
        "weibullvariate",
        "triangular",
        "choice",
        "choices",
        "sample",
        "shuffle",
        "randint",
        "randrange",
        "seed",
        "Random",
    }
)
_NUMPY_NAMES = frozenset(
    {
        "array",
        "asarray",
        "zeros",
        "ones",
        "full",
        "arange",
        "linspace",
        "eye",
        "pi",
        "e",
        "inf",
        "nan",
        "sqrt",
        "exp",
        "log",
        "log10",
        "log2",
        "sin",
        "cos",
        "tan",
        "arcsin",
        "arccos",
        "arctan",
        "arctan2",
        "hypot",
        "degrees",
        "radians",
        "deg2rad",
        "rad2deg",
        "abs",
        "absolute",
        "sign",
        "floor",
        "ceil",
        "round",
        "rint",
        "clip",
        "minimum",
        "maximum",
        "min",
        "max",
        "amin",
        "amax",
        "argmin",
        "argmax",
        "mean",
        "median",
        "std",
        "var",
        "sum",
        "prod",
        "cumsum",
        "diff",
        "dot",
        "cross",
        "outer",
        "interp",
        "where",
        "isclose",
        "allclose",
        "isnan",
        "isfinite",
        "sort",
        "argsort",
        "unique",
        "concatenate",
        "stack",
        "vstack",
        "hstack",
        "reshape",
        "transpose",
        "mod",
        "fmod",
        "power",
        "square",
        "cbrt",
        "percentile",
        "quantile",
        "all",
        "any",
        "count_nonzero",
        "float64",
        "float32",
        "int64",
        "int32",
        "random",
        "linalg",
    }
)
_NUMPY_RANDOM_NAMES = frozenset(
    {
        "rand",
        "randn",
        "random",
        "uniform",
        "normal",
        "choice",
        "randint",
        "seed",
        "shuffle",
        "permutation",
        "exponential",
        "poisson",
        "triangular",
        "beta",
        "gamma",
        "lognormal",
        "default_rng",
    }
)
_NUMPY_LINALG_NAMES = frozenset({"norm", "det", "inv", "solve", "eig", "eigvals"})
_ITERTOOLS_NAMES = frozenset(
    {
        "chain",
        "product",
        "permutations",
        "combinations",
        "cycle",
        "islice",
        "repeat",
        "accumulate",
        "pairwise",
        "zip_longest",
        "count",
    }
)
_FUNCTOOLS_NAMES = frozenset({"partial", "reduce", "lru_cache", "cache"})
_COLLECTIONS_NAMES = frozenset({"deque", "namedtuple", "OrderedDict", "defaultdict", "Counter"})

#: Module -> the names a script may use from it (None: every public name).
MODULE_NAMES: dict[str, frozenset[str] | None] = {
    "math": _MATH_NAMES,
    "random": _RANDOM_NAMES,
    "numpy": _NUMPY_NAMES,
    "numpy.random": _NUMPY_RANDOM_NAMES,
    "numpy.linalg": _NUMPY_LINALG_NAMES,
    "itertools": _ITERTOOLS_NAMES,
    "functools": _FUNCTOOLS_NAMES,
    "collections": _COLLECTIONS_NAMES,
}
#: Scenic modules a script may import from; their public names pass unless listed below.
SCENIC_MODULE_PREFIXES = (
    "scenic.simulators.carla",
    "scenic.simulators.newtonian",
    "scenic.domains.driving",
    "scenic.core.vectors",
    "scenic.core.regions",
    "scenic.core.distributions",
)
STAR_IMPORTABLE = frozenset({"math", "random"})

#: Scenic's documented non-rejecting accessors of road-network elements (roads.py says
#: to use `_laneToLeft` where `laneToLeft` would reject the sample). Data, not internals.
SCENIC_PRIVATE_ACCESSORS = frozenset(
    {
        "_laneToLeft",
        "_laneToRight",
        "_fasterLane",
        "_slowerLane",
        "_lane",
        "_laneSection",
        "_laneGroup",
        "_road",
        "_intersection",
        "_crossing",
        "_element",
        "_sidewalk",
        "_opposite",
    }
)

#: Names that lead to the interpreter, files, processes or the network: refused as bare
#: names and as attributes of anything (Scenic's modules re-export some of them).
DANGEROUS_NAMES = frozenset(
    {
        # modules
        "os",
        "sys",
        "subprocess",
        "shutil",
        "socket",
        "ctypes",
        "ctypeslib",
        "importlib",
        "builtins",
        "pickle",
        "marshal",
        "shelve",
        "dbm",
        "io",
        "pathlib",
        "tempfile",
        "glob",
        "signal",
        "threading",
        "multiprocessing",
        "asyncio",
        "selectors",
        "select",
        "mmap",
        "fcntl",
        "resource",
        "pty",
        "posix",
        "gc",
        "inspect",
        "code",
        "codeop",
        "runpy",
        "pkgutil",
        "zipimport",
        "urllib",
        "http",
        "ftplib",
        "smtplib",
        "webbrowser",
        "sqlite3",
        "zipfile",
        "tarfile",
        "gzip",
        "bz2",
        "lzma",
        "logging",
        "atexit",
        "faulthandler",
        "sysconfig",
        "linecache",
        "types",
        "ast",
        "dis",
        "veneer",
        "translator",
        "compiler",
        "syntax",
        "typing",
        "lib",
        "f2py",
        "distutils",
        "testing",
        "ma",
        "scipy",
        "arise",
        "pygame",
        "matplotlib",
        "trimesh",
        "shapely",
        "attr",
        "weakref",
        "warnings",
        "utils",
        "type_support",
        # functions and attributes that open files, run programs or evaluate code
        "open",
        "eval",
        "exec",
        "compile",
        "__import__",
        "globals",
        "locals",
        "vars",
        "breakpoint",
        "input",
        "exit",
        "quit",
        "help",
        "memoryview",
        "system",
        "popen",
        "spawn",
        "spawnv",
        "spawnl",
        "execv",
        "execve",
        "execl",
        "execlp",
        "fork",
        "forkpty",
        "kill",
        "modules",
        "load",
        "loads",
        "save",
        "savez",
        "savez_compressed",
        "savetxt",
        "loadtxt",
        "genfromtxt",
        "fromfile",
        "tofile",
        "dump",
        "dumps",
        "memmap",
        "DataSource",
        "fromregex",
        "get_type_hints",
        "mro",
        "format_map",
        "gi_frame",
        "gi_code",
        "cr_frame",
        "f_globals",
        "f_locals",
        "f_back",
        "f_builtins",
        "tb_frame",
        "tb_next",
        "func_globals",
        "func_code",
        "im_func",
        "co_code",
        "getattribute",
    }
)
#: Builtins refused as bare names only (as attributes they are ordinary data, e.g.
#: `maneuver.type`): they build classes or list what an object hides.
BARE_BUILTINS = frozenset(
    {"object", "type", "super", "classmethod", "staticmethod", "property", "dir"}
)
ATTRIBUTE_BUILTINS = frozenset({"getattr", "setattr", "delattr", "hasattr"})


@dataclass(frozen=True)
class Refusal:
    """One thing the gate refused, and where."""

    what: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"line {self.line}: {self.what}"


def module_allowed(name: str) -> bool:
    """May a script import this module?"""
    return name in MODULE_NAMES or any(
        name == prefix or name.startswith(prefix + ".") for prefix in SCENIC_MODULE_PREFIXES
    )


def _is_scenic(module: str) -> bool:
    return module.startswith("scenic.")


def _name_of_module_allowed(module: str, name: str) -> bool:
    if name.startswith("_") or name in DANGEROUS_NAMES:
        return False
    if _is_scenic(module):
        return True
    allowed = MODULE_NAMES.get(module, frozenset())
    return allowed is None or name in allowed


def _bad_attribute(name: str) -> str | None:
    """Why an attribute name is refused on any object, or None."""
    if name.startswith("_") and name not in SCENIC_PRIVATE_ACCESSORS:
        return f"attribute '.{name}' starts with '_' (private or interpreter internals)"
    if name in DANGEROUS_NAMES:
        return f"attribute '.{name}' reaches the interpreter, files, processes or the network"
    return None


def _format_fields_walk(template: str) -> bool:
    """True when a format string's fields access attributes or items ('{0.x}', '{a[k]}')."""
    try:
        fields = [f for _, f, _, _ in string.Formatter().parse(template) if f]
    except ValueError:
        return True  # a broken template is refused rather than guessed at
    return any("." in f or "[" in f for f in fields)


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


@dataclass
class _Walker(ast.NodeVisitor):
    refusals: list[Refusal] = field(default_factory=list)
    # Local names bound to modules by the script's own imports: alias -> module.
    modules: dict[str, str] = field(default_factory=dict)
    # Names the script binds itself (assignments, loops, arguments, definitions): its own
    # values, so a variable called `code` or `utils` is not the module of that name.
    bound: frozenset[str] = frozenset()
    # Name nodes that are called directly (`getattr(x, 'a')`): there the arguments are
    # checked; anywhere else `getattr` would be a value that checks nothing.
    called: set[int] = field(default_factory=set)

    def refuse(self, node: ast.AST, what: str) -> None:
        line = getattr(node, "lineno", 1) or 1
        column = (getattr(node, "col_offset", 0) or 0) + 1
        self.refusals.append(Refusal(what, line, column))

    # imports ------------------------------------------------------------------------
    def visit_Import(self, node: ast.Import) -> None:
        for alias in node.names:
            if not module_allowed(alias.name):
                self.refuse(node, f"import of module '{alias.name}' is not allowed")
            elif alias.asname:
                self.modules[alias.asname] = alias.name
            else:
                self.modules[alias.name.split(".")[0]] = alias.name.split(".")[0]

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
                if module not in STAR_IMPORTABLE and not _is_scenic(module):
                    self.refuse(
                        node, f"'from {module} import *' is not allowed; import the names you use"
                    )
            elif f"{module}.{alias.name}" in MODULE_NAMES:
                self.modules[alias.asname or alias.name] = f"{module}.{alias.name}"
            elif not _name_of_module_allowed(module, alias.name):
                self.refuse(node, f"name '{alias.name}' of module '{module}' is not allowed")

    # names and attributes ---------------------------------------------------------------
    def visit_Name(self, node: ast.Name) -> None:
        if node.id in ATTRIBUTE_BUILTINS and id(node) not in self.called:
            self.refuse(
                node,
                f"'{node.id}' may only be called with a literal attribute name, "
                "not passed around as a value",
            )
            return
        if node.id in self.modules or (node.id in self.bound and not node.id.startswith("_")):
            return
        if node.id.startswith("__"):
            self.refuse(node, f"name '{node.id}' is not allowed (interpreter internals)")
        elif node.id in DANGEROUS_NAMES or node.id in BARE_BUILTINS:
            self.refuse(
                node,
                f"name '{node.id}' is not allowed (it reaches the interpreter, "
                "files, processes or the network)",
            )

    def _module_chain(self, node: ast.Attribute) -> tuple[str, str] | None:
        """(module, attribute) when `node` reads an attribute of an imported module."""
        chain = [node.attr]
        value = node.value
        while isinstance(value, ast.Attribute):
            chain.insert(0, value.attr)
            value = value.value
        if not isinstance(value, ast.Name) or value.id not in self.modules:
            return None
        module = self.modules[value.id]
        for part in chain[:-1]:
            if f"{module}.{part}" in MODULE_NAMES or _is_scenic(module):
                module = f"{module}.{part}"
            else:
                return None  # an attribute of a value, checked on its own
        return module, chain[-1]

    def visit_Attribute(self, node: ast.Attribute) -> None:
        reason = _bad_attribute(node.attr)
        on_module = self._module_chain(node)
        if reason:
            self.refuse(node, reason)
        elif on_module is not None:
            module, name = on_module
            if f"{module}.{name}" not in MODULE_NAMES and not _name_of_module_allowed(module, name):
                self.refuse(
                    node,
                    f"'{module}.{name}' is not allowed (scripts may use only "
                    f"the maths of '{module}')",
                )
        if node.attr in SCENIC_PRIVATE_ACCESSORS and on_module is not None:
            self.refuse(node, f"attribute '.{node.attr}' of a module is not allowed")
        self.generic_visit(node)

    # calls ------------------------------------------------------------------------------
    def visit_Call(self, node: ast.Call) -> None:
        func = node.func
        if isinstance(func, ast.Name):
            self.called.add(id(func))
        if isinstance(func, ast.Name) and func.id in ATTRIBUTE_BUILTINS and len(node.args) < 2:
            self.refuse(node, f"'{func.id}' needs an object and a literal attribute name")
        if isinstance(func, ast.Name) and func.id in ATTRIBUTE_BUILTINS and len(node.args) >= 2:
            name = node.args[1]
            if not (isinstance(name, ast.Constant) and isinstance(name.value, str)):
                self.refuse(node, f"'{func.id}' with a computed attribute name is not allowed")
            else:
                reason = _bad_attribute(name.value)
                if reason:
                    self.refuse(node, f"'{func.id}': {reason}")
        if isinstance(func, ast.Attribute) and func.attr == "format":
            template = func.value
            if not (isinstance(template, ast.Constant) and isinstance(template.value, str)):
                self.refuse(node, "'.format' is allowed only on a string literal; use an f-string")
            elif _format_fields_walk(template.value):
                self.refuse(node, "format fields may not access attributes or items")
        if isinstance(func, ast.Name) and func.id == "localPath":
            self._check_path_argument(node)
        self.generic_visit(node)

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

    # annotations ------------------------------------------------------------------------
    def _check_annotation(self, annotation: ast.AST | None) -> None:
        if annotation is None:
            return
        for inner in ast.walk(annotation):
            if isinstance(inner, ast.Constant) and isinstance(inner.value, str):
                self.refuse(
                    inner, "string annotations are not allowed (they are evaluated as code)"
                )
                return

    def visit_AnnAssign(self, node: ast.AnnAssign) -> None:
        self._check_annotation(node.annotation)
        self.generic_visit(node)

    def visit_arg(self, node: ast.arg) -> None:
        self._check_annotation(node.annotation)
        self.generic_visit(node)

    def _visit_function(self, node: ast.FunctionDef | ast.AsyncFunctionDef) -> None:
        self._check_annotation(node.returns)
        self.generic_visit(node)

    visit_FunctionDef = _visit_function
    visit_AsyncFunctionDef = _visit_function

    # Scenic statements (their node classes come from Scenic's parser) ------------------
    def generic_visit(self, node: ast.AST) -> None:
        kind = type(node).__name__
        if kind == "Model":
            name = getattr(node, "name", "")
            if name not in KNOWN_MODELS:
                self.refuse(
                    node,
                    f"model '{name}' is not a world model we know "
                    f"({', '.join(sorted(KNOWN_MODELS))})",
                )
        elif kind == "Param":
            for element in getattr(node, "elts", []) or []:
                if getattr(element, "identifier", None) == "map":
                    self._check_map_param(node, getattr(element, "value", None))
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


def scan_tree(tree: ast.AST) -> list[Refusal]:
    """Refusals found in a parsed (Scenic or Python) syntax tree."""
    walker = _Walker(bound=_bound_names(tree))
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
