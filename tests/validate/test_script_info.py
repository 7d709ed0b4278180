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


# Adversarial scripts at the size limit the validator accepts. The regular expressions this
# module used backtracked quadratically on each of them (a 240 KB script froze `arise serve`
# for four minutes); read line by line, each is read in milliseconds. No timing is asserted
# here: the results must be right, and a quadratic reader would not finish the test.
LIMIT = 256 * 1024
MODEL = "model scenic.simulators.carla.model"


def test_blank_lines_and_spaces_before_the_model_line() -> None:
    info = read_script_info("\n" * LIMIT + MODEL + "\n")
    assert info.model == "scenic.simulators.carla.model" and info.model_line == LIMIT + 1
    info = read_script_info(" \n" * (LIMIT // 2) + " " * LIMIT + "\n" + MODEL)
    assert info.model_line == LIMIT // 2 + 2
    assert read_script_info("model" + " " * LIMIT + "x y").model is None


def test_a_param_line_with_a_long_run_of_spaces() -> None:
    info = read_script_info("param weather = a" + " " * LIMIT + "b" + " " * LIMIT + "\n")
    assert info.param_lines == {"weather": 1}
    info = read_script_info("param map =" + " " * LIMIT + "\nTown = 'Town07'\n")
    assert info.map_line is None and info.requested_map == "Town07"


def test_thousands_of_params_keep_their_lines() -> None:
    text = "".join(f"param p{i} = {i}\n" for i in range(LIMIT // 16)) + "param map = 'a/T.xodr'\n"
    info = read_script_info(text)
    assert len(info.param_lines) == LIMIT // 16 + 1
    assert info.param_lines["p100"] == 101 and info.map_line == LIMIT // 16 + 1
    assert info.requested_map == "T" and info.requested_map_file == "a/T.xodr"


def test_unterminated_quotes_braces_and_long_town_names() -> None:
    assert read_script_info("Town = '" + "a" * LIMIT).requested_map is None
    assert read_script_info("x = " + "'" * LIMIT).requested_map is None
    assert read_script_info("param map = f'" + "{" * LIMIT + ".xodr'").requested_map is None
    assert read_script_info("t = 'Town" + "1" * LIMIT + "!'").requested_map is None
    assert read_script_info("t = 'Town" + "1" * LIMIT + "'").requested_map == "Town" + "1" * LIMIT
    fields = "{a}" * (LIMIT // 3)
    info = read_script_info(f"a = 'x'\nparam map = f'maps/{fields}.xodr'\n")
    assert info.requested_map == "x" * (LIMIT // 3)


def test_the_ego_line_is_the_ego_s_not_a_blank_line_before_it() -> None:
    assert read_script_info("x = 1\n\n   \nego = new Car\n").ego_line == 4
    assert read_script_info("egon = 1\nego_car = 2\nego=new Car").ego_line == 3
    assert read_script_info("ego" + " " * LIMIT).ego_line is None


def test_a_value_on_the_next_line_is_not_the_param_s() -> None:
    info = read_script_info("param x =\nparam map = 'maps/Town04.xodr'\n")
    assert info.param_lines == {"map": 2} and info.requested_map == "Town04"
