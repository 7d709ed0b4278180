"""Which attempt wrote each line of the final script."""

from __future__ import annotations

from arise.serve.view import line_origins


def test_lines_keep_the_attempt_that_last_wrote_them() -> None:
    first = "a\nb\nc\nd\n"
    second = "a\nB\nc\nd\n"  # attempt 1 rewrote line 2
    third = "a\nB\nc\nx\ny\nd\n"  # attempt 2 inserted two lines
    assert line_origins([first]) == [0, 0, 0, 0]
    assert line_origins([first, second]) == [0, 1, 0, 0]
    assert line_origins([first, second, third]) == [0, 1, 0, 2, 2, 0]
    assert line_origins([first, "a\nd\n"]) == [0, 0]  # deletions leave no line behind
    assert line_origins([]) == []
