"""The confined worker: active here, loud when missing, and what it cannot reach.

These run real workers; the hostile corpus (test_hostile.py) attacks them script by
script. Here: the mechanisms themselves, the environment, the map cache, the PNG
hand-over and the CLI's report of the sandbox.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from arise.validate import CheckOptions, WorkerPool, check, check_text
from arise.validate.map_cache import cache_file
from arise.validate.sandbox import kernel_support, landlock_abi
from arise.validate.types import Mechanism, Stage

pytestmark = pytest.mark.slow

HEADER = """Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
"""
EGO = "ego = new Car on road, with behavior FollowLaneBehavior(target_speed=5)\n"
OPTIONS = CheckOptions(seed=1, steps=20, timeout=40, static_gate=False)


def _raise_with(expression: str) -> str:
    """A script whose top level fails with the value of `expression` in its message."""
    return HEADER + "import os\n" + f"raise ValueError(repr({expression}))\n" + EGO


def test_this_machine_confines_every_worker(validator_pool: WorkerPool) -> None:
    """CI and developers' machines must have full confinement; the suite fails if not."""
    assert landlock_abi() >= 6, "this kernel lacks Landlock ABI 6 (scopes)"
    assert kernel_support().full
    sandbox = validator_pool.sandbox()
    assert sandbox.full, sandbox.notes
    assert set(sandbox.active) == set(Mechanism)
    assert sandbox.label == "landlock+seccomp+rlimits+namespaces"
    assert any("pids.max" in note or "RLIMIT_NPROC" in note for note in sandbox.notes)


def test_every_result_names_its_confinement(validator_pool: WorkerPool) -> None:
    result = check_text(HEADER + EGO, CheckOptions(seed=1, steps=20), pool=validator_pool)
    assert result.ok, result.diagnostic
    assert result.sandbox is not None and result.sandbox.full


def test_no_api_key_reaches_the_worker(
    validator_pool: WorkerPool, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("OPENAI_API_KEY", "sk-canary-0123456789")
    monkeypatch.setenv("ANTHROPIC_API_KEY", "sk-ant-canary-0123456789")
    # A fresh pool: workers inherit the environment when they start.
    with WorkerPool(size=1) as pool:
        result = check_text(_raise_with("dict(os.environ)"), OPTIONS, pool=pool)
    dumped = result.model_dump_json()
    assert result.diagnostic is not None and "HOME" in dumped  # the script really ran
    assert "canary" not in dumped


def test_home_is_the_scratch_folder_and_the_real_home_is_unreadable(
    validator_pool: WorkerPool,
) -> None:
    home = Path.home()
    result = check_text(_raise_with(f"os.listdir({str(home)!r})"), OPTIONS, pool=validator_pool)
    assert result.diagnostic is not None
    assert result.diagnostic.error_type == "PermissionError", result.diagnostic
    assert "sandbox refused" in (result.diagnostic.hint or "")


def test_require_sandbox_refuses_an_unconfined_worker() -> None:
    with WorkerPool(size=1, confine=False) as pool:
        unconfined = check_text(HEADER + EGO, CheckOptions(seed=1, steps=5), pool=pool)
        refused = check_text(
            HEADER + EGO, CheckOptions(seed=1, steps=5, require_sandbox=True), pool=pool
        )
    assert unconfined.ok and unconfined.sandbox is not None
    assert not unconfined.sandbox.full and "MISSING" in unconfined.sandbox.label
    assert not refused.ok and refused.diagnostic is not None
    assert refused.diagnostic.error_type == "SandboxUnavailable"
    assert "landlock-fs" in refused.diagnostic.message


def test_require_sandbox_from_the_config_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    config = tmp_path / "config.toml"
    config.write_text("[sandbox]\nrequire = true\n", encoding="utf-8")
    monkeypatch.setenv("ARISE_CONFIG", str(config))
    monkeypatch.delenv("ARISE_REQUIRE_SANDBOX", raising=False)
    with WorkerPool(size=1, confine=False) as pool:
        refused = check_text(HEADER + EGO, CheckOptions(seed=1, steps=5), pool=pool)
    assert refused.diagnostic is not None
    assert refused.diagnostic.error_type == "SandboxUnavailable"


def test_map_cache_is_prepared_outside_the_worker(validator_pool: WorkerPool) -> None:
    result = check_text(HEADER + EGO, CheckOptions(seed=2, steps=5), pool=validator_pool)
    assert result.map is not None
    assert cache_file(Path(result.map.path)).exists()


def test_a_worker_cannot_write_the_map_cache(validator_pool: WorkerPool) -> None:
    first = check_text(HEADER + EGO, CheckOptions(seed=2, steps=5), pool=validator_pool)
    assert first.map is not None
    target = Path(first.map.path).with_suffix(".pwned")
    result = check_text(
        _raise_with(f"open({str(target)!r}, 'w').write('x')"), OPTIONS, pool=validator_pool
    )
    assert result.diagnostic is not None and not target.exists()


def test_a_symlinked_map_beside_the_script_is_not_read(
    tmp_path: Path, validator_pool: WorkerPool
) -> None:
    secret = tmp_path / "secret.txt"
    secret.write_text("canary-map-secret", encoding="utf-8")
    folder = tmp_path / "scenario"
    folder.mkdir()
    (folder / "mine.xodr").symlink_to(secret)
    script = folder / "s.scenic"
    script.write_text(
        "param map = localPath('mine.xodr')\nmodel scenic.simulators.carla.model\n" + EGO,
        encoding="utf-8",
    )
    result = check(script, CheckOptions(seed=1, steps=5), pool=validator_pool)
    assert result.map is not None and result.map.name != "mine"
    assert "canary-map-secret" not in result.model_dump_json()


def test_picture_is_drawn_in_the_worker_and_written_by_the_parent(
    tmp_path: Path, validator_pool: WorkerPool
) -> None:
    target = tmp_path / "pictures" / "scene.png"
    result = check_text(
        HEADER + EGO, CheckOptions(seed=1, steps=10, png=str(target)), pool=validator_pool
    )
    assert result.ok and result.png == str(target)
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_scratch_flood_stops_the_worker(validator_pool: WorkerPool) -> None:
    flood = (
        HEADER + "import os\nimport numpy\n"
        "block = numpy.zeros(8 * 1024 * 1024, dtype=numpy.uint8)\n"
        "for i in range(200):\n"
        "    block.tofile(f'fill{i}.bin')\n" + EGO
    )
    result = check_text(flood, OPTIONS.model_copy(update={"timeout": 60}), pool=validator_pool)
    assert result.diagnostic is not None
    assert result.diagnostic.error_type in ("DiskQuotaExceeded", "OSError"), result.diagnostic
    # 200 x 8 MB is far past the 256 MB tmpfs: the writes stop short (ENOSPC or a short write)
    assert result.diagnostic.message


def test_check_cli_prints_the_sandbox(tmp_path: Path) -> None:
    script = tmp_path / "ok.scenic"
    script.write_text(HEADER + EGO, encoding="utf-8")
    arise = [sys.executable, "-m", "arise"]
    shown = subprocess.run(
        [*arise, "check", str(script), "--steps", "5", "--seed", "1"],
        capture_output=True,
        text=True,
        timeout=180,
    )
    assert shown.returncode == 0, shown.stdout + shown.stderr
    assert "sandbox: landlock+seccomp+rlimits" in shown.stdout
    as_json = subprocess.run(
        [*arise, "check", str(script), "--steps", "5", "--json"],
        capture_output=True,
        text=True,
        timeout=180,
    )
    assert json.loads(as_json.stdout)["sandbox"]["active"]


def test_doctor_reports_the_sandbox_reached_by_a_worker() -> None:
    shown = subprocess.run(
        [sys.executable, "-m", "arise", "doctor"],
        capture_output=True,
        text=True,
        timeout=180,
        env={**os.environ, "COLUMNS": "200"},
    )
    line = next(line for line in shown.stdout.splitlines() if "sandbox" in line)
    assert line.split()[0] == "ok" and "landlock+seccomp+rlimits" in line, shown.stdout


def test_a_failed_check_still_says_where_it_stopped(validator_pool: WorkerPool) -> None:
    result = check_text(HEADER + "import os\nos.fork()\n" + EGO, OPTIONS, pool=validator_pool)
    assert result.diagnostic is not None
    assert result.diagnostic.stage is Stage.COMPILE
    assert result.diagnostic.error_type == "PermissionError"
