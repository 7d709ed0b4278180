"""The free parameters of a script, and the script with them fixed.

A free parameter is a top-level `param NAME = <distribution>` whose bounds are literals:
`Range`, `DiscreteRange`, `Uniform`/`Options` over numbers, `Normal` and
`TruncatedNormal`, and VerifAI's `VerifaiRange`, `VerifaiDiscreteRange`, `VerifaiOptions`
and `VerifaiParameter.withPrior(...)`. Every `OPT_*` parameter and every VerifAI
parameter counts, whatever its values; other parameters only when numeric (a weather
choice is no criticality knob). Fixing replaces the expression by the value and keeps the
old one as a comment, so the concrete script says what was searched.
"""

from __future__ import annotations

import ast
import io
import re
import tokenize
from dataclasses import dataclass, field
from enum import StrEnum

from arise.errors import AriseError

ParamValue = float | int | str | bool

#: Spread of a `Normal(mean, sd)` searched as a range: mean +- this many sd.
NORMAL_SPREAD = 2.0
#: Decimals a continuous value keeps: the fixed script holds exactly what was run.
DECIMALS = 4

# Possessive spaces and a greedy value that ends at its last non-space: linear on a line
# of any length (a lazy value before `\s*$` backtracked quadratically on inner spaces).
_PARAM_LINE = re.compile(r"^param\s+([A-Za-z_]\w*)\s*+=\s*+(.*\S)")
_CONSTANT_LINE = re.compile(r"^([A-Za-z_]\w*)\s*+=\s*+(.*\S)")


class ParamKind(StrEnum):
    """How a free parameter's values are laid out."""

    RANGE = "range"  # a real interval
    DISCRETE = "discrete"  # an integer interval
    OPTIONS = "options"  # a finite list of values


@dataclass(frozen=True)
class FreeParam:
    name: str
    kind: ParamKind
    line: int  # 1-based line of its `param` statement
    expression: str  # as written, e.g. "Range(9, 12)"
    low: float = 0.0
    high: float = 0.0
    options: tuple[ParamValue, ...] = ()
    verifai: bool = False

    def value_at(self, number: float) -> ParamValue:
        """The value at `number` on this parameter's axis (an option's index for options),
        as a plain Python value: a numpy scalar would reach the script as `np.float64(..)`."""
        if self.kind is ParamKind.RANGE:
            return round(float(number), DECIMALS)
        if self.kind is ParamKind.DISCRETE:
            return int(round(float(number)))
        return self.options[int(round(float(number)))]

    def describe(self) -> str:
        if self.kind is ParamKind.OPTIONS:
            return "{" + ", ".join(repr(o) for o in self.options) + "}"
        return f"[{self.low:g}, {self.high:g}]"


@dataclass
class _Parsed:
    kind: ParamKind
    low: float = 0.0
    high: float = 0.0
    options: list[ParamValue] = field(default_factory=list)
    verifai: bool = False


class _NotLiteral(AriseError):
    """An argument that is not a literal we can read without running the script (caught
    here: such a param is simply not searched)."""


def _code_part(line: str) -> str:
    """The line without a trailing comment (a '#' inside a string stays)."""
    if "#" not in line:
        return line
    try:
        for token in tokenize.generate_tokens(io.StringIO(line).readline):
            if token.type == tokenize.COMMENT:
                return line[: token.start[1]]
    except (tokenize.TokenError, SyntaxError):
        pass
    return line


def _literal(node: ast.AST, constants: dict[str, object]) -> object:
    if isinstance(node, ast.Constant):
        return node.value
    if isinstance(node, ast.Name) and node.id in constants:
        return constants[node.id]
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
        value = _literal(node.operand, constants)
        if isinstance(value, int | float) and not isinstance(value, bool):
            return -value if isinstance(node.op, ast.USub) else value
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add | ast.Sub | ast.Mult | ast.Div):
        left, right = _literal(node.left, constants), _literal(node.right, constants)
        if all(isinstance(v, int | float) and not isinstance(v, bool) for v in (left, right)):
            assert isinstance(left, int | float) and isinstance(right, int | float)
            if isinstance(node.op, ast.Add):
                return left + right
            if isinstance(node.op, ast.Sub):
                return left - right
            if isinstance(node.op, ast.Mult):
                return left * right
            if right != 0:
                return left / right
    if isinstance(node, ast.List | ast.Tuple):
        return [_literal(e, constants) for e in node.elts]
    if isinstance(node, ast.Dict) and all(k is not None for k in node.keys):
        return {
            _literal(k, constants): _literal(v, constants)
            for k, v in zip(node.keys, node.values, strict=True)
            if k is not None
        }
    raise _NotLiteral


def _arguments(call: ast.Call, constants: dict[str, object]) -> list[object]:
    values: list[object] = []
    for argument in call.args:
        if isinstance(argument, ast.Starred):
            spread = _literal(argument.value, constants)
            if not isinstance(spread, list):
                raise _NotLiteral
            values.extend(spread)
        else:
            values.append(_literal(argument, constants))
    return values


def _number(value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise _NotLiteral
    return float(value)


def _callee(call: ast.Call) -> str:
    func = call.func
    if isinstance(func, ast.Name):
        return func.id
    if isinstance(func, ast.Attribute) and isinstance(func.value, ast.Name):
        return f"{func.value.id}.{func.attr}"
    return ""


def _option_values(values: list[object]) -> list[ParamValue]:
    if len(values) == 1 and isinstance(values[0], list | dict):
        values = list(values[0])  # Options([...]) or Options({value: weight})
    options: list[ParamValue] = []
    for value in values:
        if not isinstance(value, int | float | str | bool):
            raise _NotLiteral
        options.append(value)
    if not options:
        raise _NotLiteral
    return options


def _parse(node: ast.AST, constants: dict[str, object]) -> _Parsed:
    if not isinstance(node, ast.Call):
        raise _NotLiteral
    name = _callee(node)
    if name == "VerifaiParameter.withPrior" and node.args:
        inner = _parse(node.args[0], constants)
        inner.verifai = True
        return inner
    args = _arguments(node, constants)
    verifai = name.startswith("Verifai")
    if name in ("Range", "VerifaiRange") and len(args) >= 2:
        low, high = sorted((_number(args[0]), _number(args[1])))
        return _Parsed(ParamKind.RANGE, low, high, verifai=verifai)
    if name in ("DiscreteRange", "VerifaiDiscreteRange") and len(args) >= 2:
        low, high = sorted((_number(args[0]), _number(args[1])))
        return _Parsed(ParamKind.DISCRETE, int(low), int(high), verifai=verifai)
    if name == "Normal" and len(args) == 2:
        mean, spread = _number(args[0]), abs(_number(args[1])) * NORMAL_SPREAD
        return _Parsed(ParamKind.RANGE, mean - spread, mean + spread)
    if name == "TruncatedNormal" and len(args) == 4:
        low, high = sorted((_number(args[2]), _number(args[3])))
        return _Parsed(ParamKind.RANGE, low, high)
    if name in ("Uniform", "Options", "VerifaiOptions"):
        return _Parsed(ParamKind.OPTIONS, options=_option_values(args), verifai=verifai)
    raise _NotLiteral


def _constants(lines: list[str]) -> dict[str, object]:
    """Top-level `NAME = literal` assignments, for bounds written as names."""
    found: dict[str, object] = {}
    for line in lines:
        match = _CONSTANT_LINE.match(_code_part(line))
        if not match:
            continue
        try:
            found[match.group(1)] = _literal(ast.parse(match.group(2), mode="eval").body, found)
        except (SyntaxError, _NotLiteral):
            continue
    return found


def _wanted(name: str, parsed: _Parsed) -> bool:
    if name.startswith("OPT_") or parsed.verifai:
        return True
    if parsed.kind is ParamKind.OPTIONS:
        return all(isinstance(o, int | float) and not isinstance(o, bool) for o in parsed.options)
    return True


def find_free_params(text: str) -> list[FreeParam]:
    """The script's free parameters, in the order it declares them."""
    lines = text.splitlines()
    constants = _constants(lines)
    found: dict[str, FreeParam] = {}
    for number, line in enumerate(lines, start=1):
        match = _PARAM_LINE.match(_code_part(line).rstrip())
        if not match:
            continue
        name, expression = match.group(1), match.group(2)
        try:
            parsed = _parse(ast.parse(expression, mode="eval").body, constants)
        except (SyntaxError, _NotLiteral, ValueError):
            found.pop(name, None)  # a later plain assignment overrides an earlier range
            continue
        if not _wanted(name, parsed):
            continue
        if parsed.kind is not ParamKind.OPTIONS and parsed.low == parsed.high:
            continue
        found[name] = FreeParam(
            name=name,
            kind=parsed.kind,
            line=number,
            expression=expression,
            low=parsed.low,
            high=parsed.high,
            options=tuple(parsed.options),
            verifai=parsed.verifai,
        )
    return list(found.values())


def literal(value: ParamValue) -> str:
    """A value as Scenic source."""
    if isinstance(value, float):
        return repr(round(value, DECIMALS))
    return repr(value)


def fix_params(text: str, params: list[FreeParam], values: dict[str, ParamValue]) -> str:
    """The script with each free parameter set to its value (the old expression kept in
    a comment on the same line)."""
    lines = text.splitlines(keepends=True)
    for param in params:
        if param.name not in values:
            continue
        index = param.line - 1
        ending = "\n" if lines[index].endswith("\n") else ""
        lines[index] = (
            f"param {param.name} = {literal(values[param.name])}  "
            f"# searched in {param.expression}{ending}"
        )
    return "".join(lines)
