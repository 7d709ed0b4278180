"""Loading the knowledge base: our entries plus any folders of the user's own.

A folder holds one file per component (`behavior.yaml`, ...) or one sub-folder per component
(`behavior/*.yaml`). A bad file is reported with its path, the entry and the field, and only
that file's entries are left out: one user's typo never hides the rest of the knowledge base.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

import yaml
from pydantic import ValidationError

from arise.errors import AriseError
from arise.kb.schema import COMPONENT_ORDER, Component, Entry

# libyaml's safe loader reads the same documents about ten times faster than the pure-Python
# one (about 1.1 s to 0.1 s for the shipped KB): time every `arise generate` pays.
YamlLoader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)

ENV_VAR = "ARISE_KB_DIR"
SUFFIXES = (".yaml", ".yml")


class KBError(AriseError):
    """A knowledge-base file that cannot be used, with where exactly it went wrong."""

    def __init__(self, file: str, message: str, entry: str | None = None, field: str | None = None):
        self.file, self.entry, self.field, self.message = file, entry, field, message
        where = [file]
        if entry is not None:
            where.append(f"entry {entry}")
        if field is not None:
            where.append(f"field '{field}'")
        super().__init__(": ".join([*where, message]))


@dataclass
class KnowledgeBase:
    """All entries by id, in load order, and what could not be loaded."""

    entries: dict[str, Entry] = field(default_factory=dict)
    problems: list[KBError] = field(default_factory=list)
    sources: list[Path] = field(default_factory=list)

    def __len__(self) -> int:
        return len(self.entries)

    def __iter__(self) -> Iterator[Entry]:
        return iter(self.entries.values())

    def __contains__(self, entry_id: object) -> bool:
        return entry_id in self.entries

    def get(self, entry_id: str) -> Entry:
        try:
            return self.entries[entry_id]
        except KeyError:
            raise KeyError(f"no knowledge-base entry {entry_id!r}") from None

    def of(self, component: Component | str) -> list[Entry]:
        """The entries of one component, in load order."""
        wanted = Component(component)
        return [entry for entry in self.entries.values() if entry.component is wanted]

    def counts(self) -> dict[str, int]:
        return {c.value: len(self.of(c)) for c in COMPONENT_ORDER}


def builtin_dir() -> Path:
    """Our own entries, shipped inside the package."""
    return Path(str(resources.files("arise.kb") / "data"))


def user_dirs(extra: Iterable[str | os.PathLike[str]] = ()) -> list[Path]:
    """Folders named on the command line, then those in ARISE_KB_DIR (path-separated)."""
    found = [Path(p) for p in extra]
    env = os.environ.get(ENV_VAR, "")
    found += [Path(p) for p in env.split(os.pathsep) if p.strip()]
    return found


def _component_files(folder: Path) -> tuple[list[tuple[Component, Path]], list[KBError]]:
    """(component, file) pairs of a folder, and complaints about what does not fit."""
    names = {c.value: c for c in COMPONENT_ORDER}
    pairs: list[tuple[Component, Path]] = []
    problems: list[KBError] = []
    for path in sorted(folder.iterdir()):
        if path.name.startswith((".", "_")) or path.name.lower() == "readme.md":
            continue
        if path.is_dir() and path.name in names:
            pairs += [(names[path.name], p) for p in sorted(path.iterdir()) if p.suffix in SUFFIXES]
        elif path.is_file() and path.suffix in SUFFIXES and path.stem in names:
            pairs.append((names[path.stem], path))
        else:
            problems.append(
                KBError(
                    str(path),
                    "not a knowledge-base file: name files or "
                    f"folders after a component ({', '.join(names)})",
                )
            )
    return pairs, problems


def _raw_entries(path: Path, component: Component) -> list[Any]:
    """The list of raw entries in a file, or a KBError saying why there is none."""
    try:
        data = yaml.load(path.read_text(encoding="utf-8"), Loader=YamlLoader)
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        line = f" at line {mark.line + 1}" if mark is not None else ""
        raise KBError(
            str(path), f"not valid YAML{line}: {getattr(error, 'problem', None) or error}"
        ) from None
    except (OSError, UnicodeDecodeError) as error:
        raise KBError(str(path), f"cannot read: {error}") from None
    if isinstance(data, dict) and "entries" in data:
        declared = data.get("component")
        if declared is not None and declared != component.value:
            raise KBError(
                str(path),
                f"says component {declared!r} but its name says {component.value!r}",
                field="component",
            )
        data = data["entries"]
    elif isinstance(data, dict):
        data = [data]
    if not isinstance(data, list):
        raise KBError(str(path), "expected a list of entries (or a mapping with 'entries:')")
    return data


def _entry_label(raw: Any, index: int) -> str:
    if isinstance(raw, dict) and isinstance(raw.get("id"), str):
        return f"'{raw['id']}' (#{index + 1})"
    return f"#{index + 1}"


def load_file(path: Path, component: Component) -> list[Entry]:
    """Every entry of one file, or a KBError naming the file, entry and field at fault."""
    entries = []
    for index, raw in enumerate(_raw_entries(path, component)):
        label = _entry_label(raw, index)
        if not isinstance(raw, dict):
            raise KBError(str(path), "an entry must be a mapping of fields", entry=label)
        declared = raw.get("component", component.value)
        if declared != component.value:
            raise KBError(
                str(path),
                f"is {declared!r} in a {component.value!r} file",
                entry=label,
                field="component",
            )
        try:
            entries.append(
                Entry.model_validate({**raw, "component": component.value, "source": str(path)})
            )
        except ValidationError as error:
            first = error.errors()[0]
            where = ".".join(str(part) for part in first["loc"]) or None
            more = (
                f" (and {error.error_count() - 1} more problems)" if error.error_count() > 1 else ""
            )
            raise KBError(str(path), first["msg"] + more, entry=label, field=where) from None
    return entries


def load_folder(folder: Path, kb: KnowledgeBase) -> None:
    """Add one folder's entries to `kb`; bad files go to `kb.problems`, whole."""
    if not folder.is_dir():
        kb.problems.append(KBError(str(folder), "no such knowledge-base folder"))
        return
    kb.sources.append(folder)
    pairs, problems = _component_files(folder)
    kb.problems += problems
    for component, path in pairs:
        try:
            entries = load_file(path, component)
        except KBError as error:
            kb.problems.append(error)
            continue
        seen: dict[str, str] = {}
        clash = None
        for entry in entries:
            if entry.id in kb.entries or entry.id in seen:
                first = kb.entries[entry.id].source if entry.id in kb.entries else str(path)
                clash = KBError(
                    str(path),
                    f"duplicate id (already defined in {first})",
                    entry=f"'{entry.id}'",
                    field="id",
                )
                break
            seen[entry.id] = str(path)
        if clash is not None:
            kb.problems.append(clash)
            continue
        kb.entries.update((entry.id, entry) for entry in entries)


def load_kb(
    extra_dirs: Sequence[str | os.PathLike[str]] = (), *, builtin: bool = True, strict: bool = False
) -> KnowledgeBase:
    """Our entries (unless builtin=False), then the user's folders in order.

    With strict=True the first problem is raised instead of recorded.
    """
    kb = KnowledgeBase()
    folders = ([builtin_dir()] if builtin else []) + user_dirs(extra_dirs)
    for folder in folders:
        load_folder(folder, kb)
    if strict and kb.problems:
        raise kb.problems[0]
    return kb
