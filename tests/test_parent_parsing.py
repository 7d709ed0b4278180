"""Scripts and messages are untrusted text in the parent: every reader of them runs in
linear time on adversarial input at the size limit (256 KiB), and still reads it right.

Each of these inputs made a regular expression backtrack quadratically (minutes at this
size). No timing is asserted; a quadratic reader would not let the test finish."""

from __future__ import annotations

from arise.evaluate.judge import compact_script
from arise.evaluate.search.space import find_free_params
from arise.generate.assemble import apply_params
from arise.kb.lints import PARAM_DECL, SCENIC2_FORMS, top_level_names
from arise.validate.diagnostics import rejections_from_log

LIMIT = 256 * 1024


def test_the_judge_drops_inline_comments_after_long_runs_of_spaces() -> None:
    line = "x = 1" + " " * LIMIT + "y"
    assert compact_script(line) == line
    assert compact_script("x = 1" + " " * LIMIT + "# note") == "x = 1"
    assert compact_script("s = '#'  # note\nt = 2 #x") == "s = '#'\nt = 2"


def test_search_reads_params_with_long_values_and_long_gaps() -> None:
    spaces = " " * LIMIT
    text = f"LOW = 1{spaces}\nparam OPT_gap = Range(LOW,{spaces}5){spaces}\nparam x ={spaces}\n"
    [param] = find_free_params(text)
    assert (param.name, param.low, param.high, param.line) == ("OPT_gap", 1.0, 5.0, 2)


def test_kb_lints_on_many_blank_and_annotated_lines() -> None:
    blank = "\n" * LIMIT
    assert not any(pattern.search(blank + "x = 1") for pattern in SCENIC2_FORMS)
    assert any(pattern.search(blank + "  model scenic.x") for pattern in SCENIC2_FORMS)
    assert PARAM_DECL.findall(blank + "param OPT_a = 1\n") == ["OPT_a"]
    annotated = "a:\n" * (LIMIT // 3)
    assert top_level_names(annotated + "b: int = 2\nc = 3\n") == {"b", "c"}


def test_an_overlap_reason_with_a_long_word_names_its_creation_line() -> None:
    script = "ego = new Car\nadv = new Truck\n"
    word = "1" * 60_000  # a rejection reason holds at most 64 KiB
    log = (
        f"Rejected sample 1 because of: {word}\n"
        "Rejected sample 2 because of: unnamed Car intersects unnamed Truck\n"
    )
    rejections = rejections_from_log(log, script)
    assert [(r.reason[:8], r.line) for r in rejections] == [("11111111", None), ("unnamed ", 2)]


def test_tuned_params_are_found_after_long_runs_of_spaces() -> None:
    spaces = " " * LIMIT
    script = f"param OPT_SPEED = Range(5,{spaces}9){spaces}\n\nparam OPT_GAP = 3\n"
    tuned = apply_params(script, {"OPT_SPEED": "7"})
    assert tuned == f"param OPT_SPEED = 7{spaces}\n\nparam OPT_GAP = 3\n"
