"""Sections of an assembled script, marked by `# BEGIN NAME` / `# END NAME` comments.

The repair loop fixes one section at a time, so every diagnostic names the section its
line falls in.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

_BEGIN = re.compile(r"^\s*#\s*BEGIN\s+([A-Za-z_][\w-]*)\s*$")
_END = re.compile(r"^\s*#\s*END\s+([A-Za-z_][\w-]*)\s*$")


@dataclass(frozen=True)
class Section:
    name: str
    first_line: int  # line of the BEGIN marker, 1-based
    last_line: int  # line of the END marker (or last line of the file if unclosed)


def find_sections(text: str) -> list[Section]:
    """All marked sections, outermost first; unclosed sections run to the end of the file."""
    lines = text.splitlines()
    open_sections: list[tuple[str, int]] = []
    found: list[Section] = []
    for number, line in enumerate(lines, start=1):
        begin = _BEGIN.match(line)
        if begin:
            open_sections.append((begin.group(1).upper(), number))
            continue
        end = _END.match(line)
        if end:
            name = end.group(1).upper()
            for index in range(len(open_sections) - 1, -1, -1):
                if open_sections[index][0] == name:
                    _, start = open_sections.pop(index)
                    found.append(Section(name, start, number))
                    break
    found.extend(Section(name, start, len(lines)) for name, start in open_sections)
    return sorted(found, key=lambda s: (s.first_line, -s.last_line))


def section_of_line(text: str, line: int | None) -> str | None:
    """Name of the innermost section containing `line`, if any."""
    if line is None:
        return None
    best: Section | None = None
    for section in find_sections(text):
        if section.first_line <= line <= section.last_line and (
            best is None or section.first_line >= best.first_line
        ):
            best = section
    return best.name if best else None


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
