"""Static rules every entry keeps, checked without running Scenic.

They catch what the validator cannot see from one composed script: Scenic 2 forms that
happen to parse, params read without being declared by the same snippet, an interface
(`defines`, `needs`, placeholders) that does not match the code, names the assembler
relies on, and an adversary whose move starts on the clock instead of from the ego.
"""

from __future__ import annotations

import ast
import re
from collections.abc import Iterable
from dataclasses import dataclass

from arise.kb.schema import PLACEHOLDER_PATTERN, Component, Entry
from arise.vocabulary import ACTOR_CLASSES, POINT_CLASSES, PROP_CLASSES

OBJECT_CLASSES = (*ACTOR_CLASSES, *POINT_CLASSES, "Prop", *PROP_CLASSES, r"\{\{ADVERSARY_CLASS\}\}")
SPECIFIERS = (
    "at",
    "on",
    "in",
    "ahead",
    "behind",
    "left",
    "right",
    "following",
    "facing",
    "with",
    "offset",
    "beyond",
    "visible",
    "not",
    "apparently",
    "contained",
)
# `Car at spot`, `ego = Car`, ... without `new`: Scenic 2 object creation.
SCENIC2_CREATION = re.compile(
    r"(?<![\w.])(?<!new )("
    + "|".join(OBJECT_CLASSES)
    + r")(?=\s+(?:"
    + "|".join(SPECIFIERS)
    + r")\b|\s*(?:,\s*with\b|$))",
    re.M,
)
SCENIC2_FORMS = {
    # `[^\S\n]*`, not `\s*`: indentation within the line; `\s*` ran on across blank lines
    # from every line start, quadratic in a snippet of many blank lines.
    re.compile(
        r"^[^\S\n]*import\s+scenic\.simulators\.carla\.(actions|behaviors)\b", re.M
    ): "imports CARLA actions/behaviors by hand (Scenic 2 style; the model brings them)",
    re.compile(r"^[^\S\n]*model\s", re.M): "has a `model` line: only the HEADER names the model",
    re.compile(r"^[^\S\n]*param\s+(map|carla_map)\b", re.M): "sets the map: only the HEADER does",
}
PARAM_DECL = re.compile(r"^[^\S\n]*param\s+([A-Za-z_]\w*)\s*=", re.M)
PARAM_READ = re.compile(r"\bglobalParameters\.([A-Za-z_]\w*)")
# An annotation ends at its line: `[^=]*` ran on to the end of the snippet from every
# line that starts `name:`, quadratic in a snippet of many such lines.
TOP_ASSIGN = re.compile(r"^([A-Za-z_]\w*)\s*(?::[^=\n]*)?=(?!=)", re.M)
TOP_DEF = re.compile(r"^(?:behavior|monitor|def|scenario)\s+([A-Za-z_]\w*)\s*\(", re.M)
ADVERSARY_BEHAVIOR = re.compile(r"^behavior\s+AdversaryBehavior\s*\(\s*\)\s*:", re.M)
ADVERSARY_OBJECT = re.compile(r"^adversary\s*=\s*new\s+\{\{ADVERSARY_CLASS\}\}", re.M)
# Every composed script has these, so entries may use them without listing them in needs.
ALWAYS_DEFINED = frozenset({"ego", "adversary", "AdversaryBehavior"})
USES_ADVERSARY_BEHAVIOR = re.compile(r"with\s+behavior\s+AdversaryBehavior\s*\(\s*\)")
#: Tags that declare a behavior without a move timed to the ego: it stands still
#: (`static`), or its move has no conflict with the ego by nature (`no_conflict`: a steady
#: cruise to be overtaken, a lead that leaves the lane to uncover something else).
UNTIMED_TAGS = frozenset({"static", "no_conflict"})
#: Actions and library behaviors that move an actor (Scenic's driving domain and CARLA's).
MOTION = re.compile(
    r"\bSet(?:Throttle|Speed|WalkingSpeed|WalkingDirection|Steer|Reverse|Velocity|Walk)Action\b"
    r"|\bdo\s+(?:FollowLane|FollowTrajectory|LaneChange|Autopilot|Crossing|WalkForward|Walk|"
    r"Turn|ConstantThrottle|AccelerateForward)Behavior\b|\bDriveAvoidingCollisions\b"
)
#: A move held for a time: `do X() for 3 seconds`, `... for globalParameters.OPT_N steps`.
CLOCK = re.compile(r"\bfor\s+[^:\n]+?\s+(?:seconds|steps)\s*$", re.M)
EGO = re.compile(r"(?<![\w.])ego\b")
TOP_BLOCK = re.compile(r"^(?:behavior|def)\s+([A-Za-z_]\w*)\s*\(", re.M)


@dataclass(frozen=True)
class LintProblem:
    entry: str
    message: str

    def __str__(self) -> str:
        return f"{self.entry}: {self.message}"


def _code_only(snippet: str) -> str:
    """The snippet without comments and string literals, so words in them do not count."""
    without_strings = re.sub(r"('[^'\n]*'|\"[^\"\n]*\")", "''", snippet)
    return re.sub(r"#[^\n]*", "", without_strings)


def top_level_names(snippet: str) -> set[str]:
    """Names the snippet defines at top level (assignments, behaviors, functions)."""
    code = _code_only(snippet)
    names = set(TOP_ASSIGN.findall(code)) | set(TOP_DEF.findall(code))
    return names - {"param"}


def _scenic2(entry: Entry) -> list[str]:
    code = _code_only(entry.snippet)
    found = []
    for match in SCENIC2_CREATION.finditer(code):
        line = code[: match.start()].count("\n") + 1
        found.append(
            f"Scenic 2 object creation without `new` at snippet line {line} ({match.group(1)})"
        )
    found += [
        message for pattern, message in SCENIC2_FORMS.items() if pattern.search(entry.snippet)
    ]
    return found


def _params(entry: Entry) -> list[str]:
    code = _code_only(entry.snippet)
    declared = PARAM_DECL.findall(code)
    found = []
    allowed_plain = {"weather"} if entry.component is Component.WEATHER else set()
    for name in declared:
        if name not in allowed_plain and not name.startswith("OPT_"):
            found.append(f"declares param {name}: tunables are named OPT_*")
    opt_declared = {name for name in declared if name.startswith("OPT_")}
    for name in sorted(set(PARAM_READ.findall(code)) - opt_declared):
        found.append(f"reads globalParameters.{name} but does not declare `param {name}`")
    for line in code.splitlines():
        if re.match(r"\s*require\b", line) and "globalParameters" in line:
            found.append(
                "a `require` condition reads globalParameters, which Scenic 3.1 "
                f"cannot resolve when it checks the scene: {line.strip()!r}"
            )
        if (
            re.search(r"(?<![\w.])OPT_[A-Z0-9_]+\b", line)
            and not line.lstrip().startswith("param ")
            and not re.search(r"globalParameters\.OPT_", line)
        ):
            found.append(f"reads an OPT_ param without globalParameters: {line.strip()!r}")
    if set(entry.params) != opt_declared:
        found.append(
            f"params: lists {sorted(entry.params)} but the snippet declares {sorted(opt_declared)}"
        )
    return found


def _interface(entry: Entry) -> list[str]:
    found = []
    code = _code_only(entry.snippet)
    names = top_level_names(entry.snippet)
    for name in entry.defines:
        if name not in names:
            found.append(f"defines: lists {name}, which the snippet does not define")
    undeclared = sorted(names - set(entry.defines))
    if undeclared:
        found.append(f"defines: the snippet also defines {', '.join(undeclared)}; list them")
    for name in entry.needs:
        if not re.search(rf"(?<![\w.]){re.escape(name)}\b", code):
            found.append(f"needs: lists {name}, which the snippet does not use")
    used = set(PLACEHOLDER_PATTERN.findall(entry.snippet))
    if used != set(entry.placeholders):
        found.append(
            f"placeholders: lists {sorted(entry.placeholders)} but the snippet uses {sorted(used)}"
        )
    if re.search(r"\{\{(?![A-Z][A-Z0-9_]*\}\})", entry.snippet):
        found.append("has a malformed {{placeholder}}")
    return found


def _assembler_names(entry: Entry) -> list[str]:
    found = []
    snippet = entry.snippet
    if entry.component is Component.BEHAVIOR:
        if not ADVERSARY_BEHAVIOR.search(snippet):
            found.append(
                "must define `behavior AdversaryBehavior():` (no parameters; read "
                "routes and lanes from the names in `needs`)"
            )
        if "AdversaryBehavior" not in entry.defines:
            found.append("defines: must list AdversaryBehavior")
    elif entry.component is Component.SPAWN:
        if not ADVERSARY_OBJECT.search(snippet):
            found.append("must create `adversary = new {{ADVERSARY_CLASS}} ...`")
        if not USES_ADVERSARY_BEHAVIOR.search(snippet):
            found.append("the adversary must get `with behavior AdversaryBehavior()`")
    elif entry.component is Component.GEOMETRY:
        for name in ("ego", "egoStart"):
            if name not in entry.defines:
                found.append(f"defines: a geometry entry must define {name}")
        if not re.search(r"^ego\s*=\s*new\s+Car\b", snippet, re.M):
            found.append("must create the ego as `ego = new Car ...`")
    elif entry.component is Component.WEATHER:
        found += _weather(snippet)
    if entry.component is not Component.BEHAVIOR and ADVERSARY_BEHAVIOR.search(snippet):
        found.append("only behavior entries define AdversaryBehavior")
    if entry.component not in (Component.GEOMETRY,) and "ego" in entry.defines:
        found.append("only geometry entries define ego")
    if entry.component is not Component.SPAWN and "adversary" in entry.defines:
        found.append("only spawn entries define adversary")
    if not entry.id.startswith(entry.component.value + "."):
        found.append(f"id should start with '{entry.component.value}.'")
    return found


def _weather(snippet: str) -> list[str]:
    from arise.validate.worldmodel.weather import WeatherError, check_weather

    match = re.match(r"^\s*param\s+weather\s*=\s*(.+?)\s*$", snippet.strip(), re.S)
    if not match:
        return ["a weather snippet is one line: `param weather = <preset or dict>`"]
    try:
        value = ast.literal_eval(match.group(1))
    except (ValueError, SyntaxError):
        return ["the weather value must be a preset name or a dict of numbers"]
    try:
        check_weather(value)
    except WeatherError as error:
        return [str(error)]
    from arise.kb.weather import weather_problems

    return weather_problems(snippet)


def _blocks(code: str) -> dict[str, list[str]]:
    """The body lines of each top-level behavior and function, by name."""
    found: dict[str, list[str]] = {}
    current: list[str] | None = None
    for line in code.splitlines():
        head = TOP_BLOCK.match(line)
        if head:
            current = found.setdefault(head.group(1), [])
        elif line and not line[0].isspace():
            current = None  # back at top level (a param, an assignment)
        elif current is not None and line.strip():
            current.append(line)
    return found


def _closure(blocks: dict[str, list[str]], direct: dict[str, bool]) -> dict[str, bool]:
    """`direct` spread to every block that calls (however deeply) a block where it holds."""
    result = dict(direct)
    changed = True
    while changed:
        changed = False
        for name, lines in blocks.items():
            if result[name]:
                continue
            calls = {other for other in blocks if other != name and _calls(lines, other)}
            if any(result[other] for other in calls):
                result[name] = changed = True
    return result


def _calls(lines: Iterable[str], name: str) -> bool:
    return any(re.search(rf"(?<![\w.]){re.escape(name)}\s*\(", line) for line in lines)


def _timing(entry: Entry) -> list[str]:
    """An adversary behavior must start its move from the ego's state, not from the clock:
    some line of AdversaryBehavior at or before its first move reads the ego (directly or
    through a helper of the snippet), and no `for N seconds` comes before one that does.
    Entries tagged with one of UNTIMED_TAGS are exempt."""
    if entry.component is not Component.BEHAVIOR or set(entry.tags) & UNTIMED_TAGS:
        return []
    blocks = _blocks(_code_only(entry.snippet))
    body = blocks.get("AdversaryBehavior")
    if body is None:
        return []  # _assembler_names reports it
    reads_ego = _closure(blocks, {n: any(EGO.search(x) for x in b) for n, b in blocks.items()})
    moves = _closure(blocks, {n: any(MOTION.search(x) for x in b) for n, b in blocks.items()})
    helpers = [name for name in blocks if name != "AdversaryBehavior"]
    seen_ego = False
    for line in body:
        here = bool(EGO.search(line)) or any(reads_ego[h] and _calls([line], h) for h in helpers)
        if CLOCK.search(line) and not seen_ego:
            return [
                "its move starts on the clock (`for ... seconds` before anything reads the "
                f"ego): {line.strip()!r}; start it from the ego's distance or time to the "
                "conflict point (docs/kb.md, Timing), or tag it static / no_conflict"
            ]
        moving = bool(MOTION.search(line)) or any(moves[h] and _calls([line], h) for h in helpers)
        if moving and not (seen_ego or here):
            return [
                f"its first move does not depend on the ego: {line.strip()!r}; start it from "
                "the ego's distance or time to the conflict point (docs/kb.md, Timing), or "
                "tag it static / no_conflict"
            ]
        if moving:
            return []
        seen_ego = seen_ego or here
    return []


def lint_entry(entry: Entry) -> list[LintProblem]:
    """Everything wrong with one entry on its own."""
    messages = _scenic2(entry) + _params(entry) + _interface(entry) + _assembler_names(entry)
    messages += _timing(entry)
    return [LintProblem(entry.id, message) for message in messages]


def lint_needs(entries: Iterable[Entry]) -> list[LintProblem]:
    """Names an entry uses that another entry defines but that it does not list in needs."""
    entries = list(entries)
    vocabulary: dict[str, str] = {}
    for entry in entries:
        for name in entry.defines:
            vocabulary.setdefault(name, entry.id)
    problems = []
    for entry in entries:
        code = _code_only(entry.snippet)
        own = set(entry.defines) | set(entry.needs) | ALWAYS_DEFINED
        for name in sorted(set(vocabulary) - own):
            if re.search(rf"(?<![\w.]){re.escape(name)}\b(?!\s*=[^=])", code):
                problems.append(
                    LintProblem(
                        entry.id,
                        f"uses {name} (defined by {vocabulary[name]}) without listing it in needs",
                    )
                )
    return problems


def lint_all(entries: Iterable[Entry]) -> list[LintProblem]:
    entries = list(entries)
    problems = [problem for entry in entries for problem in lint_entry(entry)]
    return problems + lint_needs(entries)
