"""The parent believes nothing a worker or a map file tells it (issue 27).

A script that gets past the gate can write its own result line, naming any file as its
map, model or picture. The parent keeps only the facts, after a strict schema, and takes
the rest from its own request; it unpickles Scenic's `.snet` only from its own cache; map
files are bounded, regular and streamed; output folders that cannot take a file give one
clear error and no leftovers. The planted `.snet` is proven dangerous first (liveness), so
the tests that find no canary are not vacuous.
"""

from __future__ import annotations

import base64
import json
import math
import os
import resource
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest
from pydantic import ValidationError

from arise.atomic import OutputError, write_bytes_atomic, write_text_atomic
from arise.limits import (
    MAX_AGENTS,
    MAX_MAP_BYTES,
    MAX_MESSAGE,
    MAX_TOTAL_POINTS,
    MAX_TRACE_POINTS,
)
from arise.maps.cache import cached_copy, evict, maps_root, trusted_entry
from arise.maps.choice import MapChoice
from arise.maps.errors import MapError
from arise.maps.registry import MapRegistry
from arise.render.outline import load_network
from arise.validate import CheckOptions, WorkerPool, check
from arise.validate.api import _accepted, _write_png
from arise.validate.types import SimulationFacts, WorkerResult
from tests.validate.planted import (
    SECRET_TEXT,
    STRAIGHT,
    forged_facts,
    forged_result,
    forging_script,
    plant,
)

PNG = b"\x89PNG\r\n\x1a\n" + b"\x00" * 32


@pytest.fixture()
def own_cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A map cache of the test's own (the real one is shared with the other tests)."""
    folder = tmp_path / "cache"
    monkeypatch.setenv("ARISE_CACHE_DIR", str(folder))
    return folder


def _parent_choice() -> MapChoice:
    return MapRegistry(None).resolve("arise_intersection4")


# --- the planted .snet is dangerous where Scenic loads it (liveness) ---------------------------
def test_the_planted_snet_runs_code_when_scenic_loads_it(tmp_path: Path) -> None:
    from scenic.domains.driving.roads import Network

    xodr, canary, _ = plant(tmp_path)
    loaded = Network.fromFile(str(xodr))  # the "network" is the file the pickle opened
    loaded.close()
    assert canary.exists(), "the planted cache must be a real attack for the tests to mean much"


# --- .snet only from our own cache -------------------------------------------------------------
def test_load_network_parses_a_foreign_map_without_its_planted_cache(tmp_path: Path) -> None:
    xodr, canary, _ = plant(tmp_path)
    network = load_network(xodr)
    assert len(network.lanes) > 0
    with pytest.raises(MapError, match="not an OpenDRIVE map"):
        load_network(xodr.with_suffix(".snet"))
    assert not canary.exists()


def test_a_cache_folder_whose_content_does_not_match_its_digest_is_not_trusted(
    own_cache: Path, tmp_path: Path
) -> None:
    xodr, canary, _ = plant(tmp_path)
    real = Path(cached_copy(STRAIGHT))
    assert trusted_entry(real) == real
    # A folder that looks like ours, with another map's digest as its name.
    fake = maps_root() / ("0" * 16) / "arise_straight.xodr"
    fake.parent.mkdir()
    fake.write_bytes(xodr.read_bytes() + b"\n<!-- changed -->\n")
    (fake.parent / "arise_straight.snet").write_bytes(xodr.with_suffix(".snet").read_bytes())
    assert trusted_entry(fake) is None
    # A link into the cache, and a cache entry reached through a link.
    link = tmp_path / "link.xodr"
    link.symlink_to(real)
    assert trusted_entry(link) is None
    (tmp_path / "cache-link").symlink_to(real.parent)
    assert trusted_entry(tmp_path / "cache-link" / real.name) is None
    # Our own entry whose .snet is a link (to the planted one) is not trusted either.
    real.with_suffix(".snet").unlink(missing_ok=True)
    real.with_suffix(".snet").symlink_to(xodr.with_suffix(".snet"))
    assert trusted_entry(real) is None
    load_network(fake)
    load_network(real)
    assert not canary.exists()


# --- the worker's result: facts after a strict schema, the rest from the request ---------------
def _facts(**changes: Any) -> dict[str, Any]:
    return {**forged_facts(), **changes}


def _agent(**changes: Any) -> dict[str, Any]:
    return {**forged_facts()["agents"][0], **changes}


def _point(**changes: Any) -> dict[str, Any]:
    return {"step": 0, "x": 0.0, "y": 0.0, "heading": 0.0, "speed": 1.0, **changes}


@pytest.mark.parametrize(
    "simulation",
    [
        _facts(timestep=math.nan),
        _facts(timestep=-0.1),
        _facts(steps=-1),
        _facts(agents=[_agent(width=-2.0)]),
        _facts(agents=[_agent(length=math.inf)]),
        _facts(agents=[_agent(trajectory=[_point(x=math.nan)])]),
        _facts(agents=[_agent(trajectory=[_point(y=-math.inf)])]),
        _facts(agents=[_agent(trajectory=[_point(speed=-3.0)])]),
        _facts(agents=[_agent(name="../../etc")]),
        _facts(agents=[_agent(name=f"a{i}") for i in range(MAX_AGENTS + 1)]),
        _facts(agents=[_agent(trajectory=[_point(step=0)] * (MAX_TRACE_POINTS + 1))]),
        pytest.param(  # half a million points: seconds to build and validate
            _facts(
                agents=[
                    _agent(name=f"a{i}", trajectory=[_point()] * MAX_TRACE_POINTS)
                    for i in range(MAX_TOTAL_POINTS // MAX_TRACE_POINTS + 1)
                ]
            ),
            marks=pytest.mark.slow,
        ),
        _facts(events=[{"step": 1, "payload": {"nested": "dict"}}]),
        _facts(events=[{"step": 1}] * 10_001),
        _facts(unknown_field=1),
    ],
    ids=[
        "nan-timestep",
        "negative-timestep",
        "negative-steps",
        "negative-width",
        "infinite-length",
        "nan-x",
        "minus-inf-y",
        "negative-speed",
        "path-as-name",
        "too-many-agents",
        "too-many-points",
        "too-many-points-in-total",
        "nested-event",
        "too-many-events",
        "unknown-field",
    ],
)
def test_the_result_schema_refuses_what_no_simulation_gives(simulation: dict[str, Any]) -> None:
    with pytest.raises(ValidationError):
        WorkerResult.model_validate({"simulation": simulation})


@pytest.mark.parametrize(
    "raw",
    [
        {"diagnostic": {"stage": "nowhere", "error_type": "E", "message": "m"}},
        {"warnings": ["w"] * 65},
        {"timings": {"simulate": math.nan}},
        {"sandbox": {"active": ["telepathy"]}},
        {"spawn_attempts_used": -1},
    ],
    ids=["unknown-stage", "many-warnings", "nan-timing", "bad-mechanism", "neg"],
)
def test_the_rest_of_a_result_is_bounded_too(raw: dict[str, Any]) -> None:
    with pytest.raises(ValidationError):
        WorkerResult.model_validate(raw)


def test_free_text_is_cut_to_its_bound_not_refused() -> None:
    """A script can make Scenic's messages longer than any bound (a 256 KiB line in an
    excerpt): the worker must still be able to report it, and the parent keeps it bounded."""
    huge = "x" * (MAX_MESSAGE + 10)
    result = WorkerResult.model_validate(
        {
            "diagnostic": {"stage": "parse", "error_type": "E", "message": huge, "excerpt": huge},
            "simulation": _facts(params={"weather": huge}),
        }
    )
    assert result.diagnostic is not None and result.simulation is not None
    assert len(result.diagnostic.message) == len(result.diagnostic.excerpt or "") == MAX_MESSAGE
    assert len(result.simulation.params["weather"]) <= MAX_MESSAGE


@pytest.mark.parametrize("name", ["../x", ".hidden", "a/b", "", "x" * 65, "/etc/passwd", "a b"])
def test_a_map_name_is_a_plain_file_stem(name: str) -> None:
    with pytest.raises(ValidationError):
        MapChoice(requested=None, name=name, path="/tmp/x.xodr")


def test_a_forged_result_names_nothing_the_parent_uses(tmp_path: Path) -> None:
    xodr, canary, secret = plant(tmp_path)
    elsewhere = tmp_path / "elsewhere" / "picture.png"
    raw = forged_result(xodr, secret, elsewhere)
    raw["png_data"] = base64.b64encode(secret.read_bytes()).decode()
    choice = _parent_choice()
    wanted = tmp_path / "out" / "scene.png"
    result = _accepted(raw, "my.scenic", choice, "scenic.simulators.carla.model", str(wanted))
    assert result.ok  # a forgery of plausible facts about itself: the known limitation
    assert result.script == "my.scenic"
    assert result.map == choice
    assert result.model == "scenic.simulators.carla.model"
    assert result.png is None and not wanted.exists() and not elsewhere.exists()
    assert any("not a PNG" in warning for warning in result.warnings)
    assert not canary.exists()


def test_a_result_that_breaks_the_schema_is_a_protocol_violation(tmp_path: Path) -> None:
    xodr, _, secret = plant(tmp_path)
    raw = forged_result(xodr, secret, tmp_path / "x.png")
    raw["simulation"]["agents"][0]["trajectory"][3]["x"] = math.nan
    raw["sandbox"] = {"active": ["seccomp"], "missing": [], "landlock_abi": 6, "notes": []}
    result = _accepted(raw, "my.scenic", _parent_choice(), None, None)
    assert not result.ok and result.simulation is None
    assert result.diagnostic is not None
    assert result.diagnostic.error_type == "ProtocolViolation"
    assert "simulation.agents.0.trajectory.3.x" in result.diagnostic.message
    assert "\n" not in result.diagnostic.one_line()
    assert result.sandbox is not None and result.map is not None


def test_a_real_png_is_written_where_the_caller_asked(tmp_path: Path) -> None:
    raw = {"simulation": forged_facts(), "png_data": base64.b64encode(PNG).decode()}
    wanted = tmp_path / "pictures" / "scene.png"
    result = _accepted(raw, "my.scenic", _parent_choice(), None, str(wanted))
    assert result.png == str(wanted) and wanted.read_bytes() == PNG


# --- map files: bounded, regular, streamed -----------------------------------------------------
def test_a_sparse_3_gb_map_beside_a_script_is_refused_without_reading_it(
    own_cache: Path, tmp_path: Path
) -> None:
    folder = tmp_path / "scripts"
    folder.mkdir()
    huge = folder / "huge.xodr"
    with open(huge, "wb") as handle:
        handle.truncate(3 * 2**30)
    script = folder / "scenario.scenic"
    script.write_text(
        "param map = localPath('huge.xodr')\nmodel scenic.simulators.carla.model\nego = new Car\n",
        encoding="utf-8",
    )
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    result = check(script)  # refused before any worker starts
    grown_kib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before
    assert result.diagnostic is not None and result.diagnostic.error_type == "MapError"
    assert "3.0 GiB" in result.diagnostic.message
    assert f"{MAX_MAP_BYTES // 2**20} MiB" in result.diagnostic.message
    assert grown_kib < 64 * 1024
    assert [p.name for p in maps_root().iterdir()] == []


def test_map_files_that_are_no_regular_files_are_refused(own_cache: Path, tmp_path: Path) -> None:
    link = tmp_path / "link.xodr"
    link.symlink_to(STRAIGHT)
    with pytest.raises(MapError, match="symbolic link"):
        cached_copy(link)
    fifo = tmp_path / "fifo.xodr"
    os.mkfifo(fifo)
    with pytest.raises(MapError, match="not a regular file"):
        cached_copy(fifo)  # opened non-blocking: no writer, no hang
    with pytest.raises(MapError, match="not a regular file"):
        cached_copy(Path("/dev/zero"), "zero")
    odd = tmp_path / "my map.xodr"
    odd.write_bytes(STRAIGHT.read_bytes())
    with pytest.raises(MapError, match="no plain name"):
        cached_copy(odd)
    assert [p.name for p in maps_root().iterdir()] == []


def test_a_map_is_copied_whole_under_its_digest(own_cache: Path) -> None:
    copy = cached_copy(STRAIGHT)
    assert copy.read_bytes() == STRAIGHT.read_bytes()
    assert copy.parent.parent == maps_root() and copy.name == "arise_straight.xodr"
    assert cached_copy(STRAIGHT) == copy
    assert [p.name for p in maps_root().iterdir()] == [copy.parent.name]


def _aged(folder: Path, seconds: float) -> None:
    past = time.time() - seconds
    os.utime(folder, (past, past))


def test_the_cache_evicts_least_recently_used_folders_beyond_its_budget(
    own_cache: Path, tmp_path: Path
) -> None:
    builtin = cached_copy(STRAIGHT).parent
    copies = []
    for index in range(4):
        source = tmp_path / f"map{index}.xodr"
        source.write_bytes(STRAIGHT.read_bytes() + f"<!-- {index} -->\n".encode() * 2000)
        copies.append(cached_copy(source).parent)
    for age, folder in zip((5000, 4000, 3000, 10), copies, strict=True):
        _aged(folder, age)
    _aged(builtin, 9000)
    size = sum(p.stat().st_size for p in copies[0].iterdir())
    evicted = evict(keep=copies[2], budget=size + 10_000, in_use=60)
    # Oldest first; the kept folder, the one used a moment ago and our own map stay.
    assert evicted == [copies[0].name, copies[1].name]
    assert builtin.is_dir() and copies[2].is_dir() and copies[3].is_dir()
    assert not copies[0].exists() and not copies[1].exists()
    assert not [p for p in maps_root().iterdir() if p.name.startswith(".")]


def test_a_folder_whose_map_is_being_parsed_is_not_evicted(own_cache: Path, tmp_path: Path) -> None:
    import fcntl

    source = tmp_path / "busy.xodr"
    source.write_bytes(STRAIGHT.read_bytes() + b"<!-- busy -->\n")
    folder = cached_copy(source).parent
    with open(folder / ".prepare.lock", "a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        _aged(folder, 9000)
        assert evict(budget=0, in_use=60) == []
    assert folder.is_dir()


# --- output folders that cannot take a file ----------------------------------------------------
def _no_leftovers(folder: Path) -> bool:
    return not folder.exists() or not [p for p in folder.iterdir() if p.name.startswith(".")]


def test_an_output_below_a_file_is_one_clear_error(tmp_path: Path) -> None:
    blocker = tmp_path / "a-file"
    blocker.write_text("x")
    with pytest.raises(OutputError) as caught:
        _write_png(str(blocker / "pictures" / "scene.png"), PNG)
    message = str(caught.value)
    assert "\n" not in message and str(blocker / "pictures") in message
    assert "Not a directory" in message


def test_a_read_only_output_folder_is_one_clear_error(tmp_path: Path) -> None:
    if os.geteuid() == 0:
        pytest.skip("root writes into a mode-0500 folder anyway (the EROFS test covers it)")
    folder = tmp_path / "read-only"
    folder.mkdir()
    folder.chmod(0o500)
    try:
        with pytest.raises(OutputError, match="Permission denied"):
            _write_png(str(folder / "scene.png"), PNG)
        assert list(folder.iterdir()) == []
    finally:
        folder.chmod(0o700)


_IN_NAMESPACE = """
import json, sys
from pathlib import Path
from arise.atomic import OutputError, write_bytes_atomic, write_text_atomic
folder = Path(sys.argv[1])
try:
    if sys.argv[2] == "big":
        write_bytes_atomic(folder / "scene.png", b"x" * (1024 * 1024))
    else:
        write_text_atomic(folder / "report.json", "{}")
    error = None
except OutputError as caught:
    error = str(caught)
print(json.dumps({"error": error, "left": sorted(p.name for p in folder.iterdir())}))
"""


def _in_namespace(mount: str, folder: Path, what: str) -> dict[str, Any]:
    """Run a write in a user and mount namespace with `folder` mounted as given (a tiny
    tmpfs, a read-only bind): real ENOSPC and EROFS without root on the host."""
    command = [
        "unshare",
        "--user",
        "--map-root-user",
        "--mount",
        "sh",
        "-c",
        f'{mount} && exec "$1" -c "$2" "$0" "$3"',
        str(folder),
        sys.executable,
        _IN_NAMESPACE,
        what,
    ]
    done = subprocess.run(command, capture_output=True, text=True, timeout=60)
    if done.returncode != 0 and "unshare" in done.stderr:
        pytest.skip(f"no user namespaces here: {done.stderr.strip()}")
    assert done.returncode == 0, done.stderr
    result: dict[str, Any] = json.loads(done.stdout)
    return result


def test_a_full_output_folder_is_one_clear_error_and_leaves_nothing(tmp_path: Path) -> None:
    folder = tmp_path / "full"
    folder.mkdir()
    seen = _in_namespace('mount -t tmpfs -o size=64k tmpfs "$0"', folder, "big")
    assert seen["left"] == []
    assert seen["error"] == f"cannot write scene.png in {folder}: No space left on device"


def test_a_read_only_file_system_is_one_clear_error(tmp_path: Path) -> None:
    folder = tmp_path / "ro"
    folder.mkdir()
    (folder / "report.json").write_text("old")
    seen = _in_namespace('mount --bind "$0" "$0" && mount -o remount,ro,bind "$0"', folder, "small")
    assert seen["error"] == f"cannot write report.json in {folder}: Read-only file system"
    assert seen["left"] == ["report.json"]
    assert (folder / "report.json").read_text() == "old"


def test_atomic_writers_write_whole_files(tmp_path: Path) -> None:
    target = write_text_atomic(tmp_path / "deep" / "a.txt", "hello")
    assert target.read_text() == "hello" and (target.stat().st_mode & 0o777) == 0o644
    write_bytes_atomic(target, b"again")
    assert target.read_bytes() == b"again" and _no_leftovers(target.parent)


# --- end to end: a script forges its result in a real worker -----------------------------------
@pytest.mark.slow
def test_a_forged_result_through_check_names_nothing(tmp_path: Path) -> None:
    xodr, canary, secret = plant(tmp_path)
    forged = forged_result(xodr, secret, tmp_path / "elsewhere.png")
    forged["png_data"] = base64.b64encode(secret.read_bytes()).decode()
    script = tmp_path / "scripts" / "forger.scenic"
    script.parent.mkdir()
    script.write_text(forging_script(forged), encoding="utf-8")
    bad = dict(forged, simulation=_facts(timestep=math.inf))
    broken = tmp_path / "scripts" / "nan.scenic"
    broken.write_text(forging_script(bad), encoding="utf-8")  # json writes inf as Infinity
    picture = tmp_path / "out" / "forger.png"
    with WorkerPool(size=1) as pool:
        result = check(script, CheckOptions(static_gate=False, png=str(picture)), pool=pool)
        refused = check(broken, CheckOptions(static_gate=False), pool=pool)
    assert "HOSTILE-FORGED" in result.warnings, "the forgery must reach the parent"
    assert result.map is not None and result.map.name == "arise_intersection4"
    assert trusted_entry(result.map.path) is not None
    assert result.model == "scenic.simulators.carla.model"
    assert result.script == str(script)
    assert not picture.exists() and not (tmp_path / "elsewhere.png").exists()
    assert refused.diagnostic is not None
    assert refused.diagnostic.error_type == "ProtocolViolation", refused.diagnostic
    assert not canary.exists()
    assert SECRET_TEXT not in result.model_dump_json() + refused.model_dump_json()


def test_simulation_facts_of_a_real_shape_pass(tmp_path: Path) -> None:
    facts = SimulationFacts.model_validate(
        _facts(
            events=[{"step": 3, "agent": "world", "kind": "traffic_light", "signals": ["1"]}],
            ego_pairs=[{"other": "Car1", "min_distance": -1.0, "min_distance_step": 0}],
            params={"weather": "ClearNoon"},
        )
    )
    assert facts.agents[0].trajectory[-1].step == 20
    # A map without junctions is infinitely far from one: that is no gap, not a number.
    agent = _agent(junction_gap=math.inf)
    assert SimulationFacts.model_validate(_facts(agents=[agent])).agents[0].junction_gap is None
    with pytest.raises(ValidationError):
        SimulationFacts.model_validate(_facts(agents=[_agent(junction_gap=math.nan)]))


@pytest.mark.slow
def test_a_256_kib_line_is_a_parse_error_not_a_crash(tmp_path: Path) -> None:
    script = tmp_path / "spaces.scenic"
    script.write_text(" " * 256 * 1024 + "x\n", encoding="utf-8")
    result = check(script, CheckOptions(seed=0, timeout=60))
    assert result.diagnostic is not None, result
    assert result.diagnostic.error_type == "ScenicParseError", result.diagnostic.one_line()
