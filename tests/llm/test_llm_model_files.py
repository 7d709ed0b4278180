"""Assembling the default GGUF from the PyPI part packages."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from arise.llm import ModelNotInstalled, model_files

SPEC = model_files.DEFAULT_MODEL


def _parts_or_skip() -> list[Path]:
    try:
        return model_files.part_files(SPEC)
    except ModelNotInstalled as exc:
        pytest.skip(str(exc))


def test_parts_are_found_in_order_and_add_up() -> None:
    parts = _parts_or_skip()
    assert len(parts) == SPEC.parts
    assert [p.name for p in parts] == [f"part{i:02d}.bin" for i in range(1, SPEC.parts + 1)]
    assert sum(p.stat().st_size for p in parts) == SPEC.size
    assert parts[0].read_bytes()[:4] == b"GGUF"


def test_missing_parts_say_what_to_install() -> None:
    ghost = replace(SPEC, part_package="arise-no-such-package-part{i}")
    with pytest.raises(ModelNotInstalled, match=r"22 of 22 missing.*pip install 'arise\[model\]'"):
        model_files.install(ghost, target=Path("/nonexistent/never-written.gguf"))


@pytest.mark.slow
def test_a_wrong_hash_leaves_nothing_behind(tmp_path: Path) -> None:
    _parts_or_skip()
    wrong = replace(SPEC, sha256="0" * 64)
    target = tmp_path / "model.gguf"
    with pytest.raises(ModelNotInstalled, match="sha256"):
        model_files.install(wrong, target=target)
    assert list(tmp_path.iterdir()) == []  # no partial file, no temporary left over


@pytest.mark.slow
def test_installed_default_model_is_verified() -> None:
    path = model_files.default_model_path()
    if not model_files.is_installed(path):
        pytest.skip(f"not installed at {path}: run `arise llm install-model`")
    assert model_files.sha256_of(path) == SPEC.sha256
    # a second install is a no-op on a good file
    assert model_files.install(SPEC) == path
