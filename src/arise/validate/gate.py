"""Static gate: refuse scripts that reach outside the scenario before any of it runs.

Generated scripts are untrusted code. Scenic scripts may contain arbitrary Python, so we
walk the parsed script and refuse imports outside an allow-list, builtins that open
files or evaluate code, and dunder attribute access (the usual sandbox escapes).
Scenic's own constructs (`model`, `param`, `localPath`, `require`, ...) stay allowed.
"""

from __future__ import annotations

import ast
import io
import re
import tokenize
from dataclasses import dataclass

ALLOWED_MODULE_ROOTS = frozenset({
    "math", "random", "itertools", "functools", "collections", "enum", "typing",
    "dataclasses", "statistics", "numpy", "shapely", "trimesh",
})
ALLOWED_SCENIC_PREFIXES = ("scenic.simulators", "scenic.domains", "scenic.core")

FORBIDDEN_NAMES = {
    "open": "opens files",
    "eval": "evaluates arbitrary code",
    "exec": "evaluates arbitrary code",
    "compile": "compiles arbitrary code",
    "__import__": "imports modules dynamically",
    "globals": "reaches the interpreter's namespaces",
    "locals": "reaches the interpreter's namespaces",
    "vars": "reaches the interpreter's namespaces",
    "breakpoint": "starts a debugger",
    "input": "reads from the terminal",
    "exit": "ends the process",
    "quit": "ends the process",
    "help": "starts an interactive helper",
    "memoryview": "reads raw memory",
    "__builtins__": "reaches the builtins",
    "importlib": "imports modules dynamically",
}
ALLOWED_DUNDERS = frozenset({"__init__", "__name__", "__class__.__name__"})
FRAME_ATTRIBUTES = frozenset({
    "f_globals", "f_locals", "f_back", "f_builtins", "gi_frame", "gi_code", "cr_frame",
    "tb_frame", "tb_next", "func_globals",
})
ATTRIBUTE_BUILTINS = {"getattr", "setattr", "delattr", "hasattr"}


@dataclass(frozen=True)
class Refusal:
    """One thing the gate refused, and where."""

    what: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"line {self.line}: {self.what}"


def module_allowed(name: str) -> bool:
    root = name.split(".", 1)[0]
    if root == "scenic":
        return name == "scenic" or name.startswith(ALLOWED_SCENIC_PREFIXES)
    return root in ALLOWED_MODULE_ROOTS


def _is_dunder(name: str) -> bool:
    return name.startswith("__") and name.endswith("__") and name not in ALLOWED_DUNDERS


class _Walker(ast.NodeVisitor):
    def __init__(self) -> None:
        self.refusals: list[Refusal] = []

    def refuse(self, node: ast.AST, what: str) -> None:
        line = getattr(node, "lineno", 1) or 1
        column = (getattr(node, "col_offset", 0) or 0) + 1
        self.refusals.append(Refusal(what, line, column))

    def visit_Import(self, node: ast.Import) -> None:
        for alias in node.names:
            if not module_allowed(alias.name):
                self.refuse(node, f"import of module '{alias.name}' is not allowed")
        self.generic_visit(node)

    def visit_ImportFrom(self, node: ast.ImportFrom) -> None:
        if node.level:
            self.refuse(node, "relative imports are not allowed")
        elif node.module is None or not module_allowed(node.module):
            self.refuse(node, f"import from module '{node.module}' is not allowed")
        self.generic_visit(node)

    def visit_Name(self, node: ast.Name) -> None:
        if node.id in FORBIDDEN_NAMES:
            self.refuse(node, f"'{node.id}' is not allowed (it {FORBIDDEN_NAMES[node.id]})")
        elif _is_dunder(node.id):
            self.refuse(node, f"dunder name '{node.id}' is not allowed")

    def visit_Attribute(self, node: ast.Attribute) -> None:
        if _is_dunder(node.attr):
            self.refuse(node, f"dunder attribute '.{node.attr}' is not allowed")
        elif node.attr in FRAME_ATTRIBUTES:
            self.refuse(node, f"frame attribute '.{node.attr}' is not allowed")
        self.generic_visit(node)

    def visit_Call(self, node: ast.Call) -> None:
        func = node.func
        if isinstance(func, ast.Name) and func.id in ATTRIBUTE_BUILTINS and len(node.args) >= 2:
            name = node.args[1]
            if not (isinstance(name, ast.Constant) and isinstance(name.value, str)):
                self.refuse(node, f"'{func.id}' with a computed attribute name is not allowed")
            elif name.value.startswith("_"):
                self.refuse(node, f"'{func.id}' on private attribute '{name.value}' is not allowed")
        self.generic_visit(node)

    def generic_visit(self, node: ast.AST) -> None:
        # Scenic's `model X` statement imports X: hold it to the same allow-list.
        if type(node).__name__ == "Model":
            name = getattr(node, "name", "")
            if isinstance(name, str) and not module_allowed(name):
                self.refuse(node, f"model '{name}' is not an allowed world model")
        super().generic_visit(node)


def scan_tree(tree: ast.AST) -> list[Refusal]:
    """Refusals found in a parsed (Scenic or Python) syntax tree."""
    walker = _Walker()
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
                refusals.append(Refusal(f"import of module '{module}' is not allowed", number,
                                        line.index(module) + 1 if module in line else 1))
    tokens: list[tokenize.TokenInfo] = []
    try:
        for token in tokenize.generate_tokens(io.StringIO(text).readline):
            tokens.append(token)
    except (tokenize.TokenError, IndentationError, SyntaxError):
        pass  # keep the tokens read before the error
    for previous, token in zip([None, *tokens], tokens, strict=False):
        if token.type != tokenize.NAME:
            continue
        after_dot = previous is not None and previous.string == "."
        if not after_dot and token.string in FORBIDDEN_NAMES:
            refusals.append(Refusal(f"'{token.string}' is not allowed "
                                    f"(it {FORBIDDEN_NAMES[token.string]})",
                                    token.start[0], token.start[1] + 1))
        elif _is_dunder(token.string):
            refusals.append(Refusal(f"dunder name '{token.string}' is not allowed",
                                    token.start[0], token.start[1] + 1))
    return sorted(refusals, key=lambda r: (r.line, r.column))
