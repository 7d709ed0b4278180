"""Rule-based repairs for mechanical errors the validator recognises.

A small model fixes these badly (it re-writes Scenic 2, invents names); a rule fixes them
exactly and for free. Each rule looks at one Diagnostic and the script text and returns
the repaired text, or None when it does not apply.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Callable
from dataclasses import dataclass, field

from arise.validate.diagnostics import looks_like_scenic2
from arise.validate.types import Diagnostic, Stage
from arise.vocabulary import (
    ACTOR_CLASSES,
    POINT_CLASSES,
    PROP_CLASSES,
    WEATHER_PRESETS,
    ActorClass,
)

CLASS_NAMES = ACTOR_CLASSES + POINT_CLASSES + PROP_CLASSES


@dataclass
class RuleContext:
    """What a rule may need beyond the script: the spec's choices and known defaults."""

    adversary_class: ActorClass = ActorClass.CAR
    param_defaults: dict[str, str] = field(default_factory=dict)
    placeholders: dict[str, str] = field(default_factory=dict)
    relaxed_lines: dict[int, int] = field(default_factory=dict)  # line -> times relaxed


@dataclass(frozen=True)
class RuleFix:
    rule: str
    text: str
    note: str


Rule = Callable[[Diagnostic, str, RuleContext], RuleFix | None]

_SCENIC2 = re.compile(
    r"(?P<lead>(?:^|=|\(|,)\s*)(?P<cls>" + "|".join(CLASS_NAMES) + r")(?P<rest>\s+(?:at|on|in|with|"
    r"following|ahead\s+of|behind|left\s+of|right\s+of|offset\s+by|facing|beyond|visible|"
    r"contained\s+in)\b)"
)
_PLACEHOLDER = re.compile(r"\{\{\s*([A-Z_]+)\s*\}\}")
_OPT_NAME = re.compile(r"\b(OPT_[A-Z0-9_]+)\b")
_NUMBER = re.compile(r"(?<![\w.])(\d+(?:\.\d+)?)(?![\w.])")


def _lines(text: str) -> list[str]:
    return text.split("\n")


def fix_scenic2_new(diagnostic: Diagnostic, text: str, context: RuleContext) -> RuleFix | None:
    """Objects created without `new` (Scenic 2): add it on every such line."""
    if diagnostic.stage is not Stage.PARSE:
        return None
    lines = _lines(text)
    line = lines[diagnostic.line - 1] if diagnostic.line and diagnostic.line <= len(lines) else ""
    if not (looks_like_scenic2(line) or "forgot 'new'" in diagnostic.message):
        return None
    changed = 0
    for index, row in enumerate(lines):
        code, hash_, comment = row.partition("#")
        fixed = _SCENIC2.sub(
            lambda m: f"{m.group('lead')}new {m.group('cls')}{m.group('rest')}", code
        )
        fixed = re.sub(r"\bnew\s+new\b", "new", fixed)
        if fixed != code:
            lines[index] = fixed + hash_ + comment
            changed += 1
    if not changed:
        return None
    return RuleFix("scenic2_new", "\n".join(lines), f"added `new` on {changed} line(s)")


def fix_placeholders(diagnostic: Diagnostic, text: str, context: RuleContext) -> RuleFix | None:
    """A `{{NAME}}` placeholder left in the script: fill it from the spec."""
    values = {"ADVERSARY_CLASS": context.adversary_class, **context.placeholders}
    found = set(_PLACEHOLDER.findall(text))
    if not found or not found & set(values):
        return None
    fixed = _PLACEHOLDER.sub(lambda m: values.get(m.group(1), m.group(0)), text)
    return RuleFix("placeholder", fixed, f"filled placeholder(s) {', '.join(sorted(found))}")


def _default_for(name: str, context: RuleContext) -> str:
    # Another actor's copy of a parameter (OPT_ACTOR2_SPAWN_GAP) has the entry's default.
    own = re.sub(r"^OPT_ACTOR\d+_", "OPT_", name)
    for known in (name, own):
        if known in context.param_defaults:
            return context.param_defaults[known]
    upper = name.upper()
    if "SPEED" in upper:
        return "Range(5, 10)"
    if any(word in upper for word in ("DIST", "GAP", "AHEAD", "BEHIND", "OFFSET")):
        return "Range(10, 20)"
    if "ANGLE" in upper or "HEADING" in upper:
        return "Range(-10, 10)"
    if "BRAKE" in upper or "THROTTLE" in upper:
        return "Range(0.5, 1.0)"
    return "1"


def fix_undeclared_param(diagnostic: Diagnostic, text: str, context: RuleContext) -> RuleFix | None:
    """`globalParameters.OPT_X` read but never declared: declare it before its first use."""
    mentioned = _OPT_NAME.findall(diagnostic.message)
    if not mentioned:
        return None
    name = mentioned[0]
    if re.search(rf"^\s*param\s+{name}\s*=", text, re.M):
        return None
    lines = _lines(text)
    first_use = next((i for i, row in enumerate(lines) if name in row), None)
    if first_use is None:
        return None
    insert_at = first_use
    # Declare at top level, above the behavior or statement block that uses it.
    while insert_at > 0 and lines[insert_at].startswith((" ", "\t")):
        insert_at -= 1
    lines.insert(insert_at, f"param {name} = {_default_for(name, context)}")
    return RuleFix("undeclared_param", "\n".join(lines), f"declared param {name}")


def _replace_on_line(text: str, line: int | None, old: str, new: str) -> str | None:
    lines = _lines(text)
    if line and 0 < line <= len(lines) and re.search(rf"\b{re.escape(old)}\b", lines[line - 1]):
        lines[line - 1] = re.sub(rf"\b{re.escape(old)}\b", new, lines[line - 1])
        return "\n".join(lines)
    if re.search(rf"\b{re.escape(old)}\b", text):
        return re.sub(rf"\b{re.escape(old)}\b", new, text)
    return None


def fix_close_name(diagnostic: Diagnostic, text: str, context: RuleContext) -> RuleFix | None:
    """An undefined name with exactly one close valid name: use it."""
    if diagnostic.error_type != "NameError":
        return None
    match = re.search(r"name '(\w+)' is not defined", diagnostic.message)
    suggestion = re.search(r"did you mean ([\w]+)", diagnostic.hint or "")
    if not match or not suggestion or match.group(1).startswith("OPT_"):
        return None
    fixed = _replace_on_line(text, diagnostic.line, match.group(1), suggestion.group(1))
    if fixed is None:
        return None
    return RuleFix("close_name", fixed, f"{match.group(1)} -> {suggestion.group(1)}")


def _swap_literal(text: str, old: str, new: str) -> str:
    """Replace a string literal, in either quote style."""
    return text.replace(f"'{old}'", f"'{new}'").replace(f'"{old}"', f'"{new}"')


def fix_blueprint(diagnostic: Diagnostic, text: str, context: RuleContext) -> RuleFix | None:
    """An unknown CARLA blueprint: the closest valid one, or none (a random blueprint)."""
    if diagnostic.error_type != "UnknownBlueprintError":
        return None
    wanted = re.search(r"blueprint '([^']+)'", diagnostic.message)
    if not wanted:
        return None
    close = re.search(r"close valid ones: ([\w.\-]+)", diagnostic.message)
    old = wanted.group(1)
    if close:
        fixed = _swap_literal(text, old, close.group(1))
        return RuleFix("blueprint", fixed, f"blueprint {old} -> {close.group(1)}")
    # No close one: drop the `with blueprint ...` specifier so the model picks a valid one.
    fixed = re.sub(rf",\s*with blueprint\s+['\"]{re.escape(old)}['\"]", "", text)
    if fixed == text:
        return None
    return RuleFix("blueprint", fixed, f"removed unknown blueprint {old}")


def fix_weather(diagnostic: Diagnostic, text: str, context: RuleContext) -> RuleFix | None:
    if diagnostic.error_type != "WeatherError":
        return None
    wanted = re.search(r"preset '([^']+)'", diagnostic.message)
    if not wanted:
        return None
    close = difflib.get_close_matches(wanted.group(1), WEATHER_PRESETS, n=1, cutoff=0.0)
    preset = close[0] if close else "ClearNoon"
    fixed = _swap_literal(text, wanted.group(1), preset)
    return RuleFix("weather", fixed, f"weather {wanted.group(1)} -> {preset}")


def _relax_numbers(line: str, factor: float) -> str:
    """Move the numbers of a comparison towards what is easier to satisfy."""
    code = line.split("#", 1)[0]
    if ">" in code and "<" not in code:
        return _NUMBER.sub(lambda m: f"{float(m.group(1)) / factor:g}", line)
    if "<" in code and ">" not in code:
        return _NUMBER.sub(lambda m: f"{float(m.group(1)) * factor:g}", line)
    if "<=" in code or "<" in code:  # a <= x <= b: widen both ends
        numbers = _NUMBER.findall(code)
        if len(numbers) == 2:
            low, high = (float(n) for n in numbers)
            new = iter([f"{low / factor:g}", f"{high * factor:g}"])
            return _NUMBER.sub(lambda m: next(new), line, count=2)
    return line


def fix_tight_requirement(
    diagnostic: Diagnostic, text: str, context: RuleContext
) -> RuleFix | None:
    """A requirement that rejected most samples: relax its numbers, or drop it the third time."""
    if diagnostic.error_type != "RejectionException":
        return None
    guilty = next(
        (
            r
            for r in diagnostic.rejections
            if r.line and r.code and r.code.lstrip().startswith("require")
        ),
        None,
    )
    if guilty is None or guilty.line is None:
        return None
    lines = _lines(text)
    index = guilty.line - 1
    times = context.relaxed_lines.get(guilty.line, 0)
    context.relaxed_lines[guilty.line] = times + 1
    relaxed = _relax_numbers(lines[index], 1.5) if times < 2 else lines[index]
    if relaxed == lines[index]:
        indent = re.match(r"\s*", lines[index]).group(0)  # type: ignore[union-attr]
        lines[index] = f"{indent}pass  # arise: dropped over-tight `{lines[index].strip()}`"
        note = f"dropped requirement on line {guilty.line}"
    else:
        lines[index] = relaxed
        note = f"relaxed requirement on line {guilty.line}"
    return RuleFix("tight_requirement", "\n".join(lines), note)


def fix_overlap(diagnostic: Diagnostic, text: str, context: RuleContext) -> RuleFix | None:
    """Objects overlapping at spawn: push the later object farther (numbers on its line x1.5)."""
    if diagnostic.error_type != "RejectionException":
        return None
    overlap = next((r for r in diagnostic.rejections if "intersects" in r.reason and r.line), None)
    if overlap is None or overlap.line is None:
        return None
    lines = _lines(text)
    row = lines[overlap.line - 1]
    spaced = re.sub(
        r"\bby\s+(\d+(?:\.\d+)?)", lambda m: f"by {max(float(m.group(1)) * 1.5, 3):g}", row
    )
    if spaced == row:
        return None
    lines[overlap.line - 1] = spaced
    return RuleFix("overlap", "\n".join(lines), f"moved the object on line {overlap.line} apart")


def fix_forbidden_import(diagnostic: Diagnostic, text: str, context: RuleContext) -> RuleFix | None:
    """A refused import line: remove it (a scenario never needs it)."""
    if diagnostic.stage is not Stage.GATE or "import" not in diagnostic.message:
        return None
    lines = _lines(text)
    if not diagnostic.line or diagnostic.line > len(lines):
        return None
    row = lines[diagnostic.line - 1]
    if not re.match(r"\s*(import|from)\s", row):
        return None
    lines[diagnostic.line - 1] = f"# arise: removed refused `{row.strip()}`"
    return RuleFix("forbidden_import", "\n".join(lines), f"removed `{row.strip()}`")


RULES: tuple[Rule, ...] = (
    fix_placeholders,
    fix_scenic2_new,
    fix_undeclared_param,
    fix_close_name,
    fix_blueprint,
    fix_weather,
    fix_overlap,
    fix_tight_requirement,
    fix_forbidden_import,
)


def apply_rules(diagnostic: Diagnostic, text: str, context: RuleContext) -> RuleFix | None:
    """The first rule that changes the script, if any."""
    for rule in RULES:
        fix = rule(diagnostic, text, context)
        if fix is not None and fix.text != text:
            return fix
    return None
