"""Loading our knowledge base and the user's folders; bad files are named precisely."""

from __future__ import annotations

from pathlib import Path

import pytest

from arise.kb.loader import ENV_VAR, KBError, load_kb
from arise.kb.schema import Component

GOOD_ENTRY = """
  - id: behavior.user_hold_still
    descriptions: [The adversary holds still.]
    snippet: |
      behavior AdversaryBehavior():
          while True:
              take SetBrakeAction(1.0)
    defines: [AdversaryBehavior]
    adversaries: [Car]
"""


def _write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def test_builtin_kb_loads_cleanly_and_is_large_enough() -> None:
    kb = load_kb(strict=True)
    assert len(kb) >= 150
    counts = kb.counts()
    assert all(counts[c.value] >= 15 for c in Component), counts
    assert all(entry.source for entry in kb)


def test_user_folder_extends_ours(tmp_path: Path) -> None:
    _write(tmp_path, "behavior.yaml", "entries:" + GOOD_ENTRY)
    ours = load_kb()
    kb = load_kb([tmp_path])
    assert not kb.problems
    assert len(kb) == len(ours) + 1
    assert kb.get("behavior.user_hold_still").component is Component.BEHAVIOR


def test_folder_per_component_and_env_variable(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    _write(tmp_path, "behavior/mine.yaml", "entries:" + GOOD_ENTRY)
    monkeypatch.setenv(ENV_VAR, str(tmp_path))
    kb = load_kb()
    assert "behavior.user_hold_still" in kb and not kb.problems


def test_malformed_entry_names_file_entry_and_field(tmp_path: Path) -> None:
    bad = _write(
        tmp_path,
        "spawn.yaml",
        """
entries:
  - id: spawn.user_ok
    descriptions: [Fine.]
    snippet: "adversary = new {{ADVERSARY_CLASS}} ahead of ego by 10, with behavior AdversaryBehavior()"
    defines: [adversary]
    placeholders: [ADVERSARY_CLASS]
  - id: spawn.user_broken
    descriptions: []
    snippet: "x = 1"
""",
    )
    _write(tmp_path, "behavior.yaml", "entries:" + GOOD_ENTRY)
    kb = load_kb([tmp_path])
    assert len(kb.problems) == 1
    message = str(kb.problems[0])
    assert str(bad) in message and "spawn.user_broken" in message and "descriptions" in message
    # Nothing else is affected: our entries and the user's other file still load.
    assert len(kb) == len(load_kb()) + 1
    assert "spawn.user_ok" not in kb  # the bad file is left out whole
    with pytest.raises(KBError) as raised:
        load_kb([tmp_path], strict=True)
    assert raised.value.field == "descriptions" and raised.value.file == str(bad)


def test_unknown_field_and_wrong_component(tmp_path: Path) -> None:
    _write(
        tmp_path,
        "misc.yaml",
        """
- id: misc.user_thing
  descriptions: [A thing.]
  snippet: "thing = new Cone ahead of ego by 20"
  defines: [thing]
  colour: red
""",
    )
    _write(
        tmp_path,
        "weather.yaml",
        """
component: misc
entries: []
""",
    )
    kb = load_kb([tmp_path])
    messages = sorted(str(p) for p in kb.problems)
    assert any("misc.user_thing" in m and "colour" in m for m in messages), messages
    assert any("weather.yaml" in m and "component" in m for m in messages), messages


def test_yaml_syntax_error_names_the_line(tmp_path: Path) -> None:
    _write(tmp_path, "weather.yaml", "entries:\n  - id: weather.x\n    descriptions: [unclosed\n")
    problem = load_kb([tmp_path]).problems[0]
    assert "weather.yaml" in str(problem) and "line" in str(problem)


def test_duplicate_id_and_stray_file(tmp_path: Path) -> None:
    _write(
        tmp_path,
        "weather.yaml",
        """
entries:
  - id: weather.clear_noon
    descriptions: [Again.]
    snippet: "param weather = 'ClearNoon'"
""",
    )
    _write(tmp_path, "notes.yaml", "hello: world\n")
    kb = load_kb([tmp_path])
    messages = [str(p) for p in kb.problems]
    assert any("duplicate id" in m and "weather.clear_noon" in m for m in messages)
    assert any("notes.yaml" in m for m in messages)
    assert kb.get("weather.clear_noon").descriptions[0] != "Again."


def test_missing_folder_is_a_problem_not_a_crash(tmp_path: Path) -> None:
    kb = load_kb([tmp_path / "nope"])
    assert kb.problems and "no such knowledge-base folder" in str(kb.problems[0])
    assert len(kb) == len(load_kb())
