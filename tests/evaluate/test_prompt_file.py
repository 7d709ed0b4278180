"""Prompt files in the three formats, and the errors a user gets for broken ones."""

from __future__ import annotations

from pathlib import Path

import pytest

from arise.evaluate.prompt_file import UNCATEGORISED, PromptFileError, read_prompts

REPO = Path(__file__).resolve().parents[2]


def test_the_dev_set_reads_with_categories() -> None:
    prompts = read_prompts(REPO / "benchmarks" / "data" / "dev_prompts.jsonl")
    assert len(prompts) >= 40
    assert {p.category for p in prompts} >= {"straight_obstacle", "right_turn", "highway"}


def test_csv_and_txt(tmp_path: Path) -> None:
    csv_file = tmp_path / "p.csv"
    csv_file.write_text(
        'id,category,description\nx1,right_turn,"The ego turns right, a car crosses."\n'
    )
    [prompt] = read_prompts(csv_file)
    assert (prompt.id, prompt.category) == ("x1", "right_turn")
    assert prompt.description == "The ego turns right, a car crosses."
    txt = tmp_path / "p.txt"
    txt.write_text("# comment\nA car brakes ahead.\n\nhighway\tA truck cuts in.\n")
    first, second = read_prompts(txt)
    assert first.category == UNCATEGORISED and second.category == "highway"
    assert first.id != second.id


@pytest.mark.parametrize(
    ("name", "text", "words"),
    [
        ("p.jsonl", '{"description": "ok"}\n{not json\n', "p.jsonl:2"),
        ("p.jsonl", '{"category": "a"}\n', "no description"),
        ("p.csv", "text\nhello\n", "'description' column"),
        ("p.txt", "\n# only a comment\n", "no prompts"),
        (
            "p.jsonl",
            '{"id": "a", "description": "x"}\n{"id": "a", "description": "y"}\n',
            "used twice",
        ),
    ],
)
def test_broken_files_name_the_problem(tmp_path: Path, name: str, text: str, words: str) -> None:
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(PromptFileError, match=words):
        read_prompts(path)
    with pytest.raises(PromptFileError, match="no such file"):
        read_prompts(tmp_path / "missing.jsonl")
