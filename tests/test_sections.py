"""The section format, read by one module: well-formed and malformed markers."""

from __future__ import annotations

import pytest

from arise.sections import (
    MarkerKind,
    find_section,
    find_sections,
    parse_marker,
    replace_section,
    section_body,
    section_of_line,
    sections_by_line,
    write_section,
)

SCRIPT = (
    "\n".join(
        [
            "# a description",  # 1
            *write_section("HEADER", ["model m"]),  # 2-4
            *write_section("BEHAVIOR", ["behavior B():", "    wait"]),  # 5-8
            *write_section("SPAWN", ["adv = new Car"]),  # 9-11
        ]
    )
    + "\n"
)


def test_written_sections_are_read_back() -> None:
    assert [(s.name, s.first_line, s.last_line) for s in find_sections(SCRIPT)] == [
        ("HEADER", 2, 4),
        ("BEHAVIOR", 5, 8),
        ("SPAWN", 9, 11),
    ]
    assert section_body(SCRIPT, "BEHAVIOR") == "behavior B():\n    wait"
    assert section_of_line(SCRIPT, 7) == "BEHAVIOR" and section_of_line(SCRIPT, 1) is None


def test_replace_changes_only_the_body_and_drops_repeated_markers() -> None:
    new = replace_section(
        SCRIPT, "behavior", "# BEGIN BEHAVIOR\nbehavior C():\n    wait\n#  END   BEHAVIOR  \n"
    )
    assert new is not None
    assert new == SCRIPT.replace("behavior B():", "behavior C():")
    assert replace_section(SCRIPT, "MISC", "x = 1") is None


def test_missing_end_belongs_to_the_section_but_cannot_be_replaced() -> None:
    text = "# BEGIN BEHAVIOR\nx = 1\ny = 2\n"
    [section] = find_sections(text)
    assert not section.closed and section.last_line == 3
    assert section_of_line(text, 3) == "BEHAVIOR"
    assert find_section(text, "BEHAVIOR") is None
    assert (
        replace_section(text, "BEHAVIOR", "z = 3") is None and section_body(text, "BEHAVIOR") == ""
    )


def test_nested_sections_map_lines_to_the_innermost() -> None:
    text = "# BEGIN GEOMETRY\na = 1\n# BEGIN SPAWN\nb = 2\n# END SPAWN\nc = 3\n# END GEOMETRY\n"
    assert [s.name for s in find_sections(text)] == ["GEOMETRY", "SPAWN"]
    assert section_of_line(text, 4) == "SPAWN" and section_of_line(text, 6) == "GEOMETRY"
    replaced = replace_section(text, "GEOMETRY", "only = 1")
    assert replaced == "# BEGIN GEOMETRY\nonly = 1\n# END GEOMETRY\n"
    # An END of the outer section closes it even when the inner one never closed.
    unclosed_inner = "# BEGIN A\n# BEGIN B\nx = 1\n# END A\ny = 2\n"
    assert [(s.name, s.last_line, s.closed) for s in find_sections(unclosed_inner)] == [
        ("A", 4, True),
        ("B", 5, False),
    ]


@pytest.mark.parametrize(
    ("line", "expected"),
    [
        ("# BEGIN BEHAVIOR", (MarkerKind.BEGIN, "BEHAVIOR")),
        ("   #    BEGIN    BEHAVIOR   ", (MarkerKind.BEGIN, "BEHAVIOR")),
        ("#END spawn", (MarkerKind.END, "SPAWN")),
        ("# BEGIN Ego-Route", (MarkerKind.BEGIN, "EGO-ROUTE")),
        ("# begin BEHAVIOR", None),  # the keywords are upper case
        ("# End BEHAVIOR", None),
        ("# end of the loop", None),
        ("# BEGIN BEHAVIOR here", None),  # one word only
        ("x = 1  # BEGIN BEHAVIOR", None),  # a marker is a whole line
        ("# BEGIN", None),
    ],
)
def test_marker_spelling(line: str, expected: tuple[MarkerKind, str] | None) -> None:
    marker = parse_marker(line)
    assert (None if marker is None else (marker.kind, marker.name)) == expected


def test_wrong_case_keyword_is_not_a_marker_so_the_section_is_unclosed() -> None:
    text = "# BEGIN BEHAVIOR\nx = 1\n# end BEHAVIOR\ny = 2\n"
    assert find_section(text, "BEHAVIOR") is None
    assert section_of_line(text, 4) == "BEHAVIOR"


def test_stray_end_is_ignored_and_first_of_two_same_named_sections_wins() -> None:
    text = "# END SPAWN\n# BEGIN SPAWN\na\n# END SPAWN\n# BEGIN SPAWN\nb\n# END SPAWN\n"
    assert [(s.first_line, s.last_line) for s in find_sections(text)] == [(2, 4), (5, 7)]
    assert section_body(text, "SPAWN") == "a"
    assert replace_section(text, "SPAWN", "c") == text.replace("\na\n", "\nc\n", 1)


def test_crlf_text_keeps_its_line_endings_outside_the_body() -> None:
    text = "# BEGIN A\r\nold\r\n# END A\r\n"
    assert section_body(text, "A") == "old"
    assert replace_section(text, "A", "new") == "# BEGIN A\r\nnew\n# END A\r\n"


def test_sections_by_line_agrees_with_section_of_line() -> None:
    text = SCRIPT + "# BEGIN A\nx\n# BEGIN B\ny\n# END A\nz\n# END B\n# BEGIN OPEN\nw\n"
    expected = [section_of_line(text, n) for n in range(1, len(text.splitlines()) + 1)]
    assert sections_by_line(text) == expected
    assert sections_by_line("") == []


def test_thousands_of_unmatched_markers_are_read_in_one_pass() -> None:
    # An END scanned every open section before: 10,000 BEGINs and 10,000 ENDs of other
    # names took 10^8 steps. Per-name stacks make it linear.
    count = 10_000
    text = "".join(f"# BEGIN A{i}\n" for i in range(count))
    text += "".join(f"# END B{i}\n" for i in range(count))
    text += "# BEGIN C\n" * count + "# END C\n" * count
    sections = find_sections(text)
    assert len(sections) == 2 * count
    assert sum(not s.closed for s in sections) == count
    inner = max((s for s in sections if s.name == "C"), key=lambda s: s.first_line)
    assert (inner.first_line, inner.last_line) == (3 * count, 3 * count + 1)
    names = sections_by_line(text)
    assert names[0] == "A0" and names[count - 1] == f"A{count - 1}"
    assert names[3 * count - 1] == "C" and names[-1] == "C"
