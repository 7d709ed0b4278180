"""Turn whatever went wrong in a check into a Diagnostic: stage, type, line, section, hint.

Scenic reports most semantic errors as plain Python exceptions whose script line is only
in the traceback, some errors at line 1 (the map, the model, the ego), and unsatisfiable
requirements without any line. This module recovers the real place and cause.
"""

from __future__ import annotations

import difflib
import re
import traceback
from collections import Counter
from collections.abc import Iterable
from pathlib import Path
from types import TracebackType
from typing import TypedDict

from arise.limits import MAX_NOTE, MAX_REJECTIONS
from arise.sections import section_of_line
from arise.validate.script_info import ScriptInfo
from arise.validate.types import Diagnostic, Rejection, Stage

_REQUIREMENT_LINE = re.compile(r"requirement on line (\d+)")
_NAME_ERROR = re.compile(r"name '(\w+)' is not defined")
_BLUEPRINT = re.compile(r"""blueprint ['"]?([\w.\-]+)['"]?""")


def excerpt(text: str, line: int | None, context: int = 2, column: int | None = None) -> str | None:
    """A few numbered lines around `line`, the guilty one marked with '>'."""
    if line is None:
        return None
    lines = text.splitlines()
    if not 1 <= line <= len(lines):
        return None
    start, stop = max(1, line - context), min(len(lines), line + context)
    width = len(str(stop))
    out = []
    for number in range(start, stop + 1):
        mark = ">" if number == line else " "
        out.append(f"{mark} {number:>{width}} | {lines[number - 1]}")
        if number == line and column is not None and column > 0:
            out.append(" " * (width + 5 + column - 1) + "^")
    return "\n".join(out)


class Location(TypedDict):
    """Where in the script a diagnostic points: the fields it shares with `Diagnostic`."""

    line: int | None
    column: int | None
    section: str | None
    excerpt: str | None


def locate(text: str, line: int | None, column: int | None = None) -> Location:
    """The section and excerpt fields for a line of the script."""
    return {
        "line": line,
        "column": column,
        "section": section_of_line(text, line),
        "excerpt": excerpt(text, line, column=column),
    }


def _script_frame(tb: TracebackType | None, script_path: str) -> tuple[int | None, int | None]:
    """Line and column of the deepest traceback frame that is in the script itself."""
    line: int | None = None
    column: int | None = None
    target = str(Path(script_path).resolve())
    for frame in traceback.extract_tb(tb):
        try:
            same = str(Path(frame.filename).resolve()) == target
        except (OSError, ValueError):
            same = False
        if same:
            line = frame.lineno
            colno = getattr(frame, "colno", None)
            column = colno + 1 if colno is not None else None
    return line, column


def _deepest_frame_file(tb: TracebackType | None) -> str:
    frames = traceback.extract_tb(tb)
    return frames[-1].filename if frames else ""


_SCENIC2_OBJECT = re.compile(
    r"(?:^|=)\s*(?!new\b)([A-Z]\w*)\s+(?:at|on|in|with|following|ahead\s+of|behind|left\s+of|"
    r"right\s+of|offset\s+by|facing|beyond|visible|contained\s+in)\b"
)


def looks_like_scenic2(code_line: str | None) -> bool:
    """An object created without `new`, as Scenic 2 allowed."""
    return bool(code_line and _SCENIC2_OBJECT.search(code_line.split("#", 1)[0]))


def hint_for(
    error_type: str, message: str, vocabulary: Iterable[str] = (), code_line: str | None = None
) -> str | None:
    """A short, concrete suggestion for errors we recognise."""
    if (
        "forgot 'new'" in message
        or 'forgot "new"' in message
        or (error_type in ("ScenicParseError", "SyntaxError") and looks_like_scenic2(code_line))
    ):
        return (
            "Scenic 3 creates objects with `new`: write `x = new Car ...`, "
            "not `x = Car ...` (Scenic 2 syntax)."
        )
    name = _NAME_ERROR.search(message)
    if name:
        close = difflib.get_close_matches(name.group(1), list(vocabulary), n=3, cutoff=0.75)
        if close:
            return f"'{name.group(1)}' is not defined; did you mean {', '.join(close)}?"
        return (
            f"'{name.group(1)}' is not defined: declare it (e.g. "
            f"`param {name.group(1)} = ...` and read it via globalParameters) or use a "
            "name the CARLA model provides."
        )
    if "from inside guard or interrupt condition" in message:
        return (
            "Scenic 3.1 cannot evaluate visibility (`can see`, withinDistanceToAnyObjs) "
            "inside an interrupt condition; use withinDistanceToObjsInLane or a distance test."
        )
    if "OfflineCarlaSimulation" in message or "carlaActor" in message:
        return (
            "the script uses CARLA's own Python API (simulation().world, carlaActor, ...), "
            "which only a real CARLA server provides: run with --simulator carla."
        )
    if error_type == "UnknownBlueprintError":
        return (
            "use a blueprint of the installed CARLA version "
            "(`arise blueprints` lists them), or leave the blueprint out for a random one."
        )
    if error_type == "SpecifierError":
        return (
            "two specifiers conflict or one needs a property no other specifier gives; "
            "give each property (position, heading, ...) once."
        )
    if error_type in ("IndentationError", "TabError"):
        return "fix the indentation of this block (4 spaces per level, no tabs)."
    if error_type == "MemoryError":
        return "the script allocates more memory than the check allows."
    if error_type == "StuckBehaviorWarning":
        return "a behavior loops without `take` or `wait`; add `wait` inside the loop."
    if "ego object not yet assigned" in message or "did not specify an ego" in message:
        return "define the ego first: `ego = new Car ...`, before anything that refers to it."
    if error_type == "WeatherError":
        return "use a CARLA weather preset name (e.g. 'ClearNoon') or a dict of its parameters."
    return _verifai_hint(error_type, message)


#: VerifAI sampler types that run offline with the verifai extra ('bo' also needs GPyOpt).
VERIFAI_SAMPLERS = ("random", "halton", "ce", "mab", "grid", "bo")


def _verifai_hint(error_type: str, message: str) -> str | None:
    """Scripts in VerifAI's style need the `verifai` extra, and one of its sampler names."""
    if error_type == "ModuleNotFoundError" and "'verifai'" in message:
        return (
            "the script declares VerifAI parameters (VerifaiRange, VerifaiOptions, ...); "
            "install VerifAI without its extra dependencies: "
            "`pip install --no-deps verifai==2.2.0 dill` (docs/search.md)."
        )
    if "unknown sampler type" in message or "Unknown VerifAI sampler type" in message:
        return "set `param verifaiSamplerType` to one of " + ", ".join(
            f"'{name}'" for name in VERIFAI_SAMPLERS
        )
    if "requires GPyOpt" in message:
        return (
            "VerifAI's Bayesian optimisation needs GPyOpt and GPy (`pip install GPyOpt GPy`); "
            "or use `param verifaiSamplerType = 'ce'`, the cross-entropy sampler."
        )
    return None


def from_exception(
    exc: BaseException,
    stage: Stage,
    text: str,
    script_path: str,
    info: ScriptInfo,
    vocabulary: Iterable[str] = (),
) -> Diagnostic:
    """Diagnostic for an exception raised while compiling, sampling or simulating."""
    error_type = type(exc).__name__
    message = str(exc) or error_type
    line: int | None
    column: int | None
    if (
        hasattr(exc, "lineno")
        and isinstance(getattr(exc, "lineno", None), int)
        and (
            getattr(exc, "filename", None) in (None, script_path, "<string>")
            or str(getattr(exc, "filename", "")).endswith(Path(script_path).name)
        )
    ):
        line = exc.lineno
        offset = getattr(exc, "offset", None)
        column = offset if isinstance(offset, int) else None
        message = getattr(exc, "msg", None) or message
    else:
        line, column = _script_frame(exc.__traceback__, script_path)

    deepest = _deepest_frame_file(exc.__traceback__)
    hint: str | None = None
    # Scenic blames line 1 for the map, the model and the ego line; find the real cause.
    if line in (None, 1):
        if isinstance(exc, FileNotFoundError) or ("roads.py" in deepest and ".xodr" in message):
            line, column = info.map_line, None
            hint = "the map file could not be read; name a known town or pass --map-dir."
        elif isinstance(exc, ModuleNotFoundError) and info.model_line:
            line, column = info.model_line, None
            hint = (
                f"world model '{info.model}' cannot be imported; use "
                "`model scenic.simulators.carla.model`."
            )
        elif info.ego_line and (line == 1 or "ego" in message.lower()):
            # Scenic reports errors of the `ego = new ...` statement at line 1.
            line, column = info.ego_line, None
    if line is None and stage is Stage.COMPILE and "model" in message.lower() and info.model_line:
        line = info.model_line
    if line is None and _verifai_hint(error_type, message) and "verifai" not in message:
        line = info.param_lines.get("verifaiSamplerType")
    if line is None and error_type == "WeatherError":
        line = info.param_lines.get("weather")
    if line is None and error_type == "UnknownBlueprintError":
        wanted = _BLUEPRINT.search(message)
        if wanted:
            line = _first_line_containing(text, wanted.group(1))
    lines = text.splitlines()
    code_line = lines[line - 1] if line and 0 < line <= len(lines) else None
    return Diagnostic(
        stage=stage,
        error_type=error_type,
        message=message.strip().splitlines()[0] if message.strip() else error_type,
        hint=hint or hint_for(error_type, message, vocabulary, code_line),
        **locate(text, line, column),
    )


def _first_line_containing(text: str, needle: str) -> int | None:
    for number, line in enumerate(text.splitlines(), start=1):
        if needle in line:
            return number
    return None


_WORD = re.compile(r"\w+")
_INTERSECTS = " intersects "
_UNNAMED = "unnamed "


def _word_before(text: str, end: int) -> str:
    start = end
    while start > 0 and (text[start - 1].isalnum() or text[start - 1] == "_"):
        start -= 1
    return text[start:end]


def _word_after(text: str, start: int) -> str:
    if text.startswith(_UNNAMED, start) and (word := _WORD.match(text, start + len(_UNNAMED))):
        return word.group()
    word = _WORD.match(text, start)
    return word.group() if word else ""


def _overlapping_objects(reason: str) -> tuple[str, str] | None:
    """The two objects of Scenic's "[unnamed] A intersects [unnamed] B", found with string
    scans: a regular expression for it backtracks quadratically on a long word."""
    position = 0
    while (at := reason.find(_INTERSECTS, position)) >= 0:
        left, right = _word_before(reason, at), _word_after(reason, at + len(_INTERSECTS))
        if left and right:
            return left, right
        position = at + 1
    return None


def _creation_line(text: str, reason: str) -> int | None:
    """For an overlap rejection, the line creating the later of the two objects."""
    objects = _overlapping_objects(reason)
    if objects is None:
        return None
    created = re.compile(rf"\bnew\s+({objects[0]}|{objects[1]})\b")
    found = None
    for number, line in enumerate(text.splitlines(), start=1):
        if created.search(line):
            found = number
    return found


def rejections_from_log(log: str, text: str) -> list[Rejection]:
    """Count the reasons Scenic printed for rejected samples (verbosity 2)."""
    reasons: Counter[str] = Counter()
    for match in re.finditer(
        r"Rejected (?:sample|simulation) [\w.]+ (?:at time step \d+ )?"
        r"because(?: of)?:? (.+)",
        log,
    ):
        reasons[match.group(1).strip()] += 1
    lines = text.splitlines()
    found = []
    for reason, count in reasons.most_common(MAX_REJECTIONS):
        reason = reason[:MAX_NOTE]  # a requirement's text can be a whole script line
        line_match = _REQUIREMENT_LINE.search(reason)
        line = int(line_match.group(1)) if line_match else _creation_line(text, reason)
        code = lines[line - 1].strip()[:MAX_NOTE] if line and 0 < line <= len(lines) else None
        found.append(
            Rejection(
                reason=reason,
                count=count,
                line=line,
                section=section_of_line(text, line),
                code=code,
            )
        )
    return found


def rejection_diagnostic(
    stage: Stage, message: str, rejections: list[Rejection], text: str, attempts: int
) -> Diagnostic:
    """Name the requirement(s) that threw away the samples or simulations."""
    top = rejections[0] if rejections else None
    if top is not None and top.line is not None and "intersects" in top.reason:
        hint = (
            f"objects overlap at spawn in {top.count} of {attempts} tries ({top.reason}); "
            f"place the object created on line {top.line} farther from the others."
        )
    elif top is not None and top.line is not None:
        hint = (
            f"the requirement on line {top.line} rejected {top.count} of {attempts} "
            f"tries: `{top.code}`; loosen it or change the placement it constrains."
        )
    elif top is not None and "empty domain" in top.reason:
        hint = (
            "a Uniform(...) chose from an empty list: nothing on this map matches the "
            "filter (e.g. no such maneuver or lane); widen the filter or use another map."
        )
    elif top is not None:
        hint = (
            f"most tries were rejected because {top.reason} ({top.count} of {attempts}); "
            "check the placement of the objects involved (overlap, off-road, not in a lane)."
        )
    else:
        hint = "no sample satisfied the requirements; loosen them."
    fields = locate(text, top.line if top else None)
    return Diagnostic(
        stage=stage,
        error_type="RejectionException",
        message=message,
        hint=hint,
        rejections=rejections,
        **fields,
    )
