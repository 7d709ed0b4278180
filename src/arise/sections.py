"""The one owner of the script's section format: `# BEGIN NAME` ... `# END NAME`.

The composer writes sections, the validator names the section a failing line is in, the
repair loop rewrites one section and the judge keeps the BEGIN markers; they all read the
markers here, so they agree on where a section starts and ends.

The format, read tolerantly and written strictly:

* a marker is a comment line `# BEGIN NAME` or `# END NAME`; indentation, spaces around
  `#` and trailing spaces are allowed; the keywords BEGIN and END are upper case (a
  comment such as `# end of the loop` is not a marker);
* NAME is one word (letters, digits, `_`, `-`), compared without case and reported upper
  case (`# BEGIN behavior` opens BEHAVIOR);
* sections may nest; an END closes the innermost open section of that name, and an END
  that matches no open section is ignored;
* a section without END runs to the end of the text: a line in it still belongs to it,
  but it cannot be replaced (where its body ends is unknown).
"""

from __future__ import annotations

import heapq
import re
from dataclasses import dataclass
from enum import StrEnum

_MARKER = re.compile(r"^\s*#\s*(BEGIN|END)\s+([A-Za-z_][\w-]*)\s*$")


class MarkerKind(StrEnum):
    BEGIN = "BEGIN"
    END = "END"


@dataclass(frozen=True)
class Marker:
    kind: MarkerKind
    name: str  # upper case


@dataclass(frozen=True)
class Section:
    name: str
    first_line: int  # line of the BEGIN marker, 1-based
    last_line: int  # line of the END marker, or the last line of the text if unclosed
    closed: bool = True

    def contains(self, line: int) -> bool:
        return self.first_line <= line <= self.last_line


def parse_marker(line: str) -> Marker | None:
    """The marker a line is, or None for any other line."""
    match = _MARKER.match(line)
    if match is None:
        return None
    return Marker(MarkerKind(match.group(1)), match.group(2).upper())


def begin_marker(name: str) -> str:
    return f"# BEGIN {name.upper()}"


def end_marker(name: str) -> str:
    return f"# END {name.upper()}"


def write_section(name: str, body: list[str]) -> list[str]:
    """The lines of one section: BEGIN marker, body lines, END marker."""
    return [begin_marker(name), *body, end_marker(name)]


def find_sections(text: str) -> list[Section]:
    """All marked sections in order of their BEGIN line (an outer one before its inner)."""
    lines = text.splitlines()
    # The BEGIN lines still open, per name: an END pops the innermost of its own name in
    # constant time, so a script of thousands of unmatched markers stays linear.
    open_sections: dict[str, list[int]] = {}
    found: list[Section] = []
    for number, line in enumerate(lines, start=1):
        marker = parse_marker(line)
        if marker is None:
            continue
        starts = open_sections.setdefault(marker.name, [])
        if marker.kind is MarkerKind.BEGIN:
            starts.append(number)
        elif starts:
            found.append(Section(marker.name, starts.pop(), number))
    found.extend(
        Section(name, start, len(lines), closed=False)
        for name, starts in open_sections.items()
        for start in starts
    )
    return sorted(found, key=lambda s: (s.first_line, -s.last_line))


def section_of_line(text: str, line: int | None) -> str | None:
    """Name of the innermost section containing `line` (1-based), if any."""
    if line is None:
        return None
    best: Section | None = None
    for section in find_sections(text):
        if section.contains(line) and (best is None or section.first_line >= best.first_line):
            best = section
    return best.name if best else None


def sections_by_line(text: str) -> list[str | None]:
    """The innermost section of every line (index 0 is line 1), as `section_of_line` names
    it, in one sweep: asking `section_of_line` line by line would be quadratic."""
    line_count = len(text.splitlines())
    sections = find_sections(text)  # by first line
    names: list[str | None] = []
    started: list[tuple[int, int, str]] = []  # (-first_line, last_line, name): a max-heap
    following = 0
    for line in range(1, line_count + 1):
        while following < len(sections) and sections[following].first_line <= line:
            section = sections[following]
            heapq.heappush(started, (-section.first_line, section.last_line, section.name))
            following += 1
        while started and started[0][1] < line:
            heapq.heappop(started)  # ended: it contains no later line either
        names.append(started[0][2] if started else None)
    return names


def find_section(text: str, name: str) -> Section | None:
    """The first closed section called `name` (any case), or None."""
    wanted = name.upper()
    return next((s for s in find_sections(text) if s.name == wanted and s.closed), None)


def section_body(text: str, name: str) -> str:
    """The lines between the markers of a closed section ('' when there is none)."""
    section = find_section(text, name)
    if section is None:
        return ""
    return "\n".join(text.splitlines()[section.first_line : section.last_line - 1])


def replace_section(text: str, name: str, body: str) -> str | None:
    """`text` with the body of section `name` replaced, or None when it has no such closed
    section. Markers of that section inside `body` (a model often repeats them) are dropped;
    everything outside the body, markers included, stays byte for byte."""
    section = find_section(text, name)
    if section is None:
        return None
    wanted = name.upper()
    lines = text.splitlines(keepends=True)
    body_lines = [
        line
        for line in body.strip("\n").split("\n")
        if (marker := parse_marker(line)) is None or marker.name != wanted
    ]
    new_body = "".join(f"{line}\n" for line in body_lines)
    return "".join(lines[: section.first_line]) + new_body + "".join(lines[section.last_line - 1 :])
