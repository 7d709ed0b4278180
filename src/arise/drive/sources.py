"""What `arise drive` drives: the scenarios of a script, a folder, a run folder or a
prompt file, as a list of scripts with an id and a category each.

A folder or run folder may come from anyone (docs/security.md): it is walked without
following links, only regular `.scenic` files within the size limit are taken, a run
folder counts only when its report says its script executed, and nothing in it is run
here (the scripts run in the confined validator). What is left out is said, one line each.

A scenario's id is its path below the folder (`straight_obstacle/so-1`); its category is
the first part of that id when there are several (a script straight in the folder is
`uncategorised`). A prompt file is generated first into `OUT/scenarios/<category>/<id>/`,
so its scenarios get their categories the same way.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import stat
from dataclasses import dataclass, field
from enum import StrEnum
from pathlib import Path

from pydantic import ValidationError

from arise.errors import AriseError
from arise.limits import MAX_REPORT_FILE_BYTES, MAX_RUN_SCRIPT_BYTES
from arise.present.source import EXECUTED, FAILED_MARKER, RUN_REPORT, RUN_SCRIPT, RunReport
from arise.present.untrusted import UntrustedFileError, read_json, read_text

UNCATEGORISED = "uncategorised"
SCRIPT_SUFFIX = ".scenic"
PROMPT_SUFFIXES = (".jsonl", ".txt")
#: A folder deeper than this, or holding more scripts, is not walked further.
MAX_DEPTH = 6
MAX_SCRIPTS = 5000


class SourceKind(StrEnum):
    """What the user handed to `arise drive`."""

    SCRIPT = "script"
    FOLDER = "folder"
    RUN_DIR = "run-dir"
    PROMPTS = "prompts"


class DriveSourceError(AriseError):
    """Nothing to drive: a path that does not exist, a file of another kind, an empty
    folder, an unreadable prompt file."""


@dataclass(frozen=True)
class Scenario:
    """One script to drive. `digest` names its text: an edited script is driven again."""

    id: str
    category: str
    script: Path
    digest: str


@dataclass
class Scenarios:
    kind: SourceKind
    items: list[Scenario] = field(default_factory=list)
    #: What was left out, one line each (a link, a run that never executed, ...).
    skipped: list[str] = field(default_factory=list)


def source_kind(path: Path) -> SourceKind:
    """The kind of `path` (DriveSourceError for a path that is none of them)."""
    if path.is_dir():
        return SourceKind.RUN_DIR if is_run_folder(path) else SourceKind.FOLDER
    if path.is_file():
        if path.suffix == SCRIPT_SUFFIX:
            return SourceKind.SCRIPT
        if path.suffix.lower() in PROMPT_SUFFIXES:
            return SourceKind.PROMPTS
        raise DriveSourceError(
            f"{path} is not a Scenic script (.scenic), a prompt file (.jsonl, .txt), "
            "a folder nor a run folder"
        )
    raise DriveSourceError(
        f"{path} does not exist (give a .scenic script, a folder, a run folder or a prompt file)"
    )


def is_run_folder(folder: Path) -> bool:
    """A folder as `arise generate -o DIR` writes it (both files regular, no links)."""
    return _is_plain_file(folder / RUN_SCRIPT) and _is_plain_file(folder / RUN_REPORT)


def _is_plain_file(path: Path) -> bool:
    try:
        return stat.S_ISREG(path.lstat().st_mode)
    except OSError:
        return False


def digest_of(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def scenarios_of(path: Path) -> Scenarios:
    """The scenarios of a script, a folder or a run folder (a prompt file is generated
    first: `arise.drive.prompts`). DriveSourceError when there is none to drive."""
    kind = source_kind(path)
    found = Scenarios(kind)
    if kind is SourceKind.PROMPTS:
        raise DriveSourceError(f"{path} is a prompt file: generate its scripts first")
    if kind is SourceKind.SCRIPT:
        _add_script(found, path, path.stem, UNCATEGORISED)
    elif kind is SourceKind.RUN_DIR:
        _add_run(found, path, path.resolve().name or "run", UNCATEGORISED)
    else:
        _walk(found, path, (), 0)
    if not found.items:
        reasons = "; ".join(found.skipped[:3])
        raise DriveSourceError(
            f"{path} holds no script to drive" + (f" ({reasons})" if reasons else "")
        )
    return found


def _category(parts: tuple[str, ...]) -> str:
    return parts[0] if len(parts) > 1 else UNCATEGORISED


def _walk(found: Scenarios, folder: Path, parts: tuple[str, ...], depth: int) -> None:
    if depth > MAX_DEPTH:
        found.skipped.append(f"{folder}: deeper than {MAX_DEPTH} folders; not walked")
        return
    try:
        entries = sorted(os.scandir(folder), key=lambda entry: entry.name)
    except OSError as error:
        found.skipped.append(f"{folder}: cannot be listed ({error.strerror or error})")
        return
    for entry in entries:
        if len(found.items) >= MAX_SCRIPTS:
            found.skipped.append(f"{folder}: more than {MAX_SCRIPTS} scripts; the rest left out")
            return
        if entry.name.startswith("."):
            continue
        path = Path(entry.path)
        if entry.is_symlink():
            if entry.name.endswith(SCRIPT_SUFFIX) or entry.is_dir():
                found.skipped.append(f"{path}: a symbolic link; not followed")
            continue
        if entry.is_dir(follow_symlinks=False):
            here = (*parts, entry.name)
            if is_run_folder(path):
                _add_run(found, path, "/".join(here), _category(here))
            else:
                _walk(found, path, here, depth + 1)
        elif entry.name.endswith(SCRIPT_SUFFIX) and entry.is_file(follow_symlinks=False):
            here = (*parts, entry.name[: -len(SCRIPT_SUFFIX)])
            _add_script(found, path, "/".join(here), _category(here))


def _add_script(found: Scenarios, path: Path, ident: str, category: str) -> None:
    try:
        text = read_text(path, MAX_RUN_SCRIPT_BYTES)
    except (OSError, UntrustedFileError) as error:
        found.skipped.append(
            str(error) if isinstance(error, UntrustedFileError) else f"{path}: {error}"
        )
        return
    found.items.append(Scenario(ident, category, path, digest_of(text)))


def _add_run(found: Scenarios, folder: Path, ident: str, category: str) -> None:
    """A run folder's script, when its run executed (a failed run has nothing to drive)."""
    report = folder / RUN_REPORT
    try:
        data = read_json(report, MAX_REPORT_FILE_BYTES)
        status = RunReport.model_validate(data).status if isinstance(data, dict) else None
    except (OSError, UntrustedFileError, ValidationError) as error:
        reason = str(error).splitlines()[0] if str(error) else type(error).__name__
        found.skipped.append(f"{report}: not a run report ({reason[:200]})")
        return
    script = folder / RUN_SCRIPT
    try:
        text = read_text(script, MAX_RUN_SCRIPT_BYTES)
    except (OSError, UntrustedFileError) as error:
        found.skipped.append(f"{script}: {error}")
        return
    if status != EXECUTED or text.startswith(FAILED_MARKER):
        found.skipped.append(f"{folder}: its script never executed (status: {status})")
        return
    found.items.append(Scenario(ident, category, script, digest_of(text)))


# -- prompt files --------------------------------------------------------------------------


@dataclass(frozen=True)
class Prompt:
    id: str
    category: str
    description: str

    @property
    def folder(self) -> str:
        """Where its run goes below OUT/scenarios: `<category>/<id>`."""
        return f"{self.category}/{self.id}"


_UNSAFE = re.compile(r"[^\w.-]+")


def safe_part(text: str, fallback: str) -> str:
    """A folder name made of `text` (no separators, no dot files, bounded)."""
    part = _UNSAFE.sub("-", text.strip()).strip("-.")[:64]
    return part or fallback


def read_prompts(path: Path) -> list[Prompt]:
    """The prompts of a .jsonl file ({"description", "id"?, "category"?} per line, as
    benchmarks/data/dev_prompts.jsonl) or a .txt file (a description per line, or
    `category<TAB>description`); blank lines and `#` lines are skipped."""
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError) as error:
        raise DriveSourceError(f"{path}: cannot read it ({error})") from None
    prompts: list[Prompt] = []
    for number, line in enumerate(lines, 1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        if path.suffix.lower() == ".jsonl":
            try:
                row = json.loads(line)
            except json.JSONDecodeError as error:
                raise DriveSourceError(f"{path}:{number}: not JSON ({error.msg})") from None
            if not isinstance(row, dict):
                raise DriveSourceError(f"{path}:{number}: expected an object per line")
            description, ident, category = (
                row.get("description"),
                row.get("id"),
                row.get("category"),
            )
        else:
            category, _, description = line.rpartition("\t")
            ident = None
        if not isinstance(description, str) or not description.strip():
            raise DriveSourceError(f"{path}:{number}: no description")
        prompts.append(
            Prompt(
                id=safe_part(str(ident or ""), f"p{len(prompts) + 1:03d}"),
                category=safe_part(str(category or ""), UNCATEGORISED),
                description=description.strip(),
            )
        )
    if not prompts:
        raise DriveSourceError(f"{path}: no prompts in it")
    seen: set[str] = set()
    for prompt in prompts:
        if prompt.folder in seen:
            raise DriveSourceError(f"{path}: the id '{prompt.id}' is used twice")
        seen.add(prompt.folder)
    return prompts
