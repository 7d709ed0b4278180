"""Reading a script without running it: sections, excerpts, model line, requested map."""

from __future__ import annotations

from arise.sections import find_sections, section_of_line
from arise.validate.diagnostics import excerpt
from arise.validate.script_info import read_script_info

SCRIPT = """# BEGIN HEADER
Town = 'Town05'
param map = localPath(f'../maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
# END HEADER
# BEGIN GEOMETRY
ego = new Car
# BEGIN SPAWN
adv = new Car ahead of ego by 10
# END SPAWN
# END GEOMETRY
"""


def test_sections_nest_and_lines_map_to_innermost() -> None:
    names = [s.name for s in find_sections(SCRIPT)]
    assert names == ["HEADER", "GEOMETRY", "SPAWN"]
    assert section_of_line(SCRIPT, 3) == "HEADER"
    assert section_of_line(SCRIPT, 8) == "GEOMETRY"
    assert section_of_line(SCRIPT, 10) == "SPAWN"
    assert section_of_line(SCRIPT, 100) is None


def test_unclosed_section_runs_to_the_end() -> None:
    assert section_of_line("# BEGIN BEHAVIOR\nx = 1\ny = 2\n", 3) == "BEHAVIOR"


def test_excerpt_marks_the_line_and_column() -> None:
    text = excerpt(SCRIPT, 10, context=1, column=5)
    assert text is not None
    rows = text.splitlines()
    assert rows[0].startswith("   9 |") or rows[0].startswith("  9 |")
    assert rows[1].startswith("> 10 | adv = new Car")
    assert rows[2].strip() == "^"


def test_map_and_model_are_read_from_the_text() -> None:
    info = read_script_info(SCRIPT)
    assert info.model == "scenic.simulators.carla.model" and info.model_line == 5
    assert info.requested_map == "Town05"
    assert info.requested_map_file == "../maps/Town05.xodr"
    assert info.map_line == 3 and info.ego_line == 8


def test_carla_map_alone_and_no_map() -> None:
    assert read_script_info("param carla_map = 'Town03'\n").requested_map == "Town03"
    info = read_script_info("ego = new Car\n")
    assert info.requested_map is None and info.model is None
