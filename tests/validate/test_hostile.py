"""The hostile corpus (issue 10): no script gets out of the validator.

Every script in tests/data/hostile tries to harm the machine that validates it (see
manifest.yaml). Each runs twice on one warm, confined worker: with the static gate, and
without it, so that the OS-level confinement alone must hold. Both times the canary file
must not appear, the secret must not show anywhere in the result, the loopback listener
must see nothing, the test process must get no signal, and the result must be a clear
failure under full confinement.

The liveness test proves the corpus is not vacuous: the harmless attacks (`live: true`)
are run without any confinement and without the gate, each in a throwaway forked child of
an unconfined runner (tests/validate/unconfined_runner.py: Scenic's own
`scenarioFromFile` with arise's offline world model, 40 steps), and must succeed there.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import threading
import uuid
from collections.abc import Iterator
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

import psutil
import pytest
import yaml

from arise.paths import cache_dir
from arise.validate import CheckOptions, WorkerPool, check
from tests.conftest import DATA, EXAMPLES

pytestmark = pytest.mark.slow

HOSTILE = DATA / "hostile"
MANIFEST: list[dict[str, Any]] = yaml.safe_load(
    (HOSTILE / "manifest.yaml").read_text(encoding="utf-8")
)["scripts"]
LIVE = [entry for entry in MANIFEST if entry["live"]]
SECRET_TEXT = f"ARISE-HOSTILE-SECRET-{uuid.uuid4().hex}"
TOKEN_VARIABLE = "ARISE_HOSTILE_TOKEN"  # an environment variable holding the secret text
FORGED_MARKER = "HOSTILE-FORGED"
# A broken script checked after the scripts that try to tamper with the warm worker.
FOLLOWUP = DATA / "broken" / "undefined_name_top.scenic"
CHECK_TIMEOUT = 30.0
LIVE_TIMEOUT = 60.0


class Listener:
    """A loopback TCP listener and a UDP socket on the same port, counting what arrives."""

    def __init__(self) -> None:
        self.tcp = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self.tcp.bind(("127.0.0.1", 0))
        self.port = self.tcp.getsockname()[1]
        self.tcp.listen(16)
        self.tcp.settimeout(0.2)
        self.udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.udp.bind(("127.0.0.1", self.port))
        self.udp.settimeout(0.2)
        self.connections = 0
        self.datagrams = 0
        self._stop = threading.Event()
        self._threads = [
            threading.Thread(target=self._accept, daemon=True),
            threading.Thread(target=self._receive, daemon=True),
        ]
        for thread in self._threads:
            thread.start()

    @property
    def contacts(self) -> int:
        return self.connections + self.datagrams

    def _accept(self) -> None:
        while not self._stop.is_set():
            try:
                connection, _ = self.tcp.accept()
            except OSError:
                continue
            self.connections += 1
            connection.close()

    def _receive(self) -> None:
        while not self._stop.is_set():
            try:
                self.udp.recvfrom(65536)
            except OSError:
                continue
            self.datagrams += 1

    def close(self) -> None:
        self._stop.set()
        for thread in self._threads:
            thread.join(2)
        self.tcp.close()
        self.udp.close()


class SignalCounter:
    """Counts SIGUSR2 sent to this (the test) process by a script."""

    def __init__(self) -> None:
        self.count = 0
        self._previous = signal.signal(signal.SIGUSR2, self._handle)

    def _handle(self, number: int, frame: object) -> None:
        self.count += 1

    def close(self) -> None:
        signal.signal(signal.SIGUSR2, self._previous)


@dataclass
class Case:
    """One script made ready to run: its placeholders filled in, in a folder of its own."""

    entry: dict[str, Any]
    root: Path
    script: Path
    canary: Path
    secret: Path
    home: Path
    work: Path
    listener: Listener

    @property
    def name(self) -> str:
        return str(self.entry["name"])

    def canary_exists(self) -> bool:
        return os.path.lexists(self.canary)

    def forbidden_texts(self) -> list[str]:
        return [SECRET_TEXT, *self.entry.get("forbidden", [])]


def prepare(entry: dict[str, Any], root: Path, listener: Listener) -> Case:
    name = entry["name"]
    root.mkdir(parents=True)
    folder, private, home, outside, work = (
        root / part for part in ("scripts", "private", "home", "outside", "work")
    )
    for path in (folder, private, home / ".ssh", outside, work):
        path.mkdir(parents=True)
    secret = private / "secret.txt"
    secret.write_text(SECRET_TEXT + "\n", encoding="utf-8")
    key = home / ".ssh" / "id_rsa"
    key.write_text(
        f"-----BEGIN OPENSSH PRIVATE KEY-----\n{SECRET_TEXT}\n-----END OPENSSH PRIVATE KEY-----\n",
        encoding="utf-8",
    )
    key.chmod(0o600)
    canary = outside / f"CANARY-{name}.npy"  # .npy: numpy.save keeps the name as it is
    values = {
        "@CANARY@": str(canary),
        "@SECRET_TEXT@": SECRET_TEXT,
        "@SECRET@": str(secret),
        "@SSH_KEY@": str(key),
        "@HOME@": str(home),
        "@PRIVATE@": str(private),
        "@PORT@": str(listener.port),
        "@TEST_PID@": str(os.getpid()),
    }

    def fill(text: str) -> str:
        for placeholder, value in values.items():  # @SECRET_TEXT@ before @SECRET@
            text = text.replace(placeholder, value)
        left = re.search(r"@[A-Z_]+@", text)
        assert left is None, f"unknown placeholder {left.group()} in {name}"
        return text

    def beside(relative: str) -> Path:
        path = Path(fill(relative))
        path = path if path.is_absolute() else folder / path
        assert path.resolve().is_relative_to(root.resolve()), f"{relative} leaves the case"
        path.parent.mkdir(parents=True, exist_ok=True)
        return path

    script_text = fill((HOSTILE / f"{name}.scenic").read_text(encoding="utf-8"))
    assert SECRET_TEXT not in script_text, "a script must not quote the secret itself"
    script = folder / entry.get("file_name", f"{name}.scenic")
    script.write_text(script_text, encoding="utf-8")
    for relative, content in (entry.get("files") or {}).items():
        beside(relative).write_text(fill(content), encoding="utf-8")
    for relative, target in (entry.get("symlinks") or {}).items():
        beside(relative).symlink_to(fill(target))
    return Case(entry, root, script, canary, secret, home, work, listener)


# --- fixtures -----------------------------------------------------------------------------
@pytest.fixture(scope="session")
def hostile_pool() -> Iterator[WorkerPool]:
    """One warm worker for the whole corpus; the secret is in this process's environment,
    so a worker that inherited it could leak it."""
    previous = os.environ.get(TOKEN_VARIABLE)
    os.environ[TOKEN_VARIABLE] = SECRET_TEXT
    try:
        with WorkerPool(size=1) as pool:
            pool.warm()
            yield pool
    finally:
        if previous is None:
            os.environ.pop(TOKEN_VARIABLE, None)
        else:
            os.environ[TOKEN_VARIABLE] = previous


@pytest.fixture(scope="session")
def signals() -> Iterator[SignalCounter]:
    counter = SignalCounter()
    yield counter
    counter.close()


@pytest.fixture()
def listener() -> Iterator[Listener]:
    opened = Listener()
    yield opened
    opened.close()


# --- confinement is there at all ------------------------------------------------------------
def test_confinement_is_active_on_this_machine(hostile_pool: WorkerPool) -> None:
    sandbox = hostile_pool.sandbox()
    assert sandbox.full, f"confinement is incomplete here: {sandbox.label}; {sandbox.notes}"
    result = check(
        EXAMPLES / "pedestrian_crossing.scenic",
        CheckOptions(seed=1, steps=40, timeout=CHECK_TIMEOUT),
        pool=hostile_pool,
    )
    assert result.ok, result.diagnostic
    assert result.sandbox is not None and result.sandbox.full, result.sandbox


def test_manifest_names_every_script_once() -> None:
    names = [entry["name"] for entry in MANIFEST]
    assert len(names) == len(set(names))
    assert sorted(names) == sorted(path.stem for path in HOSTILE.glob("*.scenic"))
    assert len(names) >= 44
    # One documented limit, and only one: a script past the gate can forge its own verdict.
    assert [e["name"] for e in MANIFEST if e.get("limitation")] == ["out_forged_result_with_facts"]
    assert all(e.get("limitation") in (None, "self_verdict") for e in MANIFEST)
    for entry in MANIFEST:
        assert entry["where"] in ("top", "def", "behavior", "monitor", "require", "worker")
        assert not entry["live"] or entry["evidence"] in (
            "canary",
            "secret",
            "connection",
            "signal",
            "marker",
        ), entry["name"]


# --- every script, with and without the static gate -----------------------------------------
def _escapes(
    case: Case,
    result: Any,
    contacts_before: int,
    signals_before: int,
    signals: SignalCounter,
    may_forge_verdict: bool = False,
) -> list[str]:
    """What got out, or what is not a clear failure; empty when the script was contained.

    `may_forge_verdict`: the one documented limit (a script past the gate can lie about
    its own outcome); everything else is still checked."""
    problems = []
    if case.canary_exists():
        problems.append(f"the canary {case.canary.name} exists")
    dumped = result.model_dump_json()
    for text in case.forbidden_texts():
        if text in dumped:
            problems.append(f"the result holds {'the secret' if text == SECRET_TEXT else text!r}")
    if case.listener.contacts > contacts_before:
        problems.append(
            f"the loopback listener was reached ({case.listener.connections} TCP, "
            f"{case.listener.datagrams} UDP)"
        )
    if signals.count > signals_before:
        problems.append("the test process got a signal from the script")
    if may_forge_verdict:
        pass
    elif result.ok is not False:
        problems.append("the check reported success")
    elif (
        result.diagnostic is None
        or not result.diagnostic.stage
        or not result.diagnostic.message.strip()
    ):
        problems.append(f"no clear diagnostic: {result.diagnostic!r}")
    if result.sandbox is None:
        problems.append("the result does not say which confinement it ran under")
    elif not result.sandbox.full:
        problems.append(f"it ran without full confinement: {result.sandbox.label}")
    return problems


def _followup_problems(pool: WorkerPool) -> list[str]:
    """A script that tampered with the warm worker shows on the next check."""
    result = check(FOLLOWUP, CheckOptions(seed=1, steps=40, timeout=CHECK_TIMEOUT), pool=pool)
    diagnostic = result.diagnostic
    if (
        result.ok
        or diagnostic is None
        or diagnostic.error_type != "NameError"
        or "AdversaryBehaviour" not in diagnostic.message
    ):
        return [
            f"the next check (a broken script) came back wrong: ok={result.ok}, "
            f"{diagnostic.one_line() if diagnostic else 'no diagnostic'}"
        ]
    return []


@pytest.mark.parametrize("entry", MANIFEST, ids=[entry["name"] for entry in MANIFEST])
def test_hostile_script_is_contained(
    entry: dict[str, Any],
    hostile_pool: WorkerPool,
    listener: Listener,
    signals: SignalCounter,
    tmp_path: Path,
) -> None:
    report = []
    for static_gate in (True, False):
        label = "with the static gate" if static_gate else "without the static gate"
        case = prepare(entry, tmp_path / ("gate" if static_gate else "no-gate"), listener)
        contacts, signals_before = listener.contacts, signals.count
        options = CheckOptions(
            seed=1,
            steps=40,
            timeout=float(entry.get("timeout", CHECK_TIMEOUT)),
            static_gate=static_gate,
        )
        try:
            result = check(case.script, options, pool=hostile_pool)
        except Exception as error:  # check() must never raise for a bad script
            report.append(f"{label}: check() raised {type(error).__name__}: {error}")
            continue
        forged = not static_gate and entry.get("limitation") == "self_verdict"
        problems = _escapes(case, result, contacts, signals_before, signals, forged)
        if entry.get("followup"):
            problems += _followup_problems(hostile_pool)
        if problems:
            where = result.diagnostic.one_line() if result.diagnostic else "no diagnostic"
            report.append(f"{label}: " + "; ".join(problems) + f" [{where}]")
    assert not report, f"{entry['name']} got out:\n" + "\n".join(report)


# --- the other entry points: replay, export and the server's check -------------------------
# The classes whose payload could reach the parent through what a check hands back: a
# forged or flooded result, a map or model a script names, a link beside it, a pickle,
# state left in the worker, and module escapes (what a forger needs).
PARENT_FACING = ("huge_output", "model_map", "symlink", "pickle", "persistence", "format_string")
PARENT_CASES = [e for e in MANIFEST if e["category"] in PARENT_FACING]


def _files_holding(root: Path, text: str, exclude: Path) -> list[str]:
    found = []
    for path in root.rglob("*"):
        if path.is_file() and not path.is_symlink() and not path.is_relative_to(exclude):
            with contextlib.suppress(OSError):
                if text.encode() in path.read_bytes():
                    found.append(str(path.relative_to(root)))
    return found


def _worker_processes() -> set[int]:
    """Live validator workers under this process (a zombie has already ended)."""
    found = set()
    for child in psutil.Process().children(recursive=True):
        with contextlib.suppress(psutil.Error):  # ended meanwhile, or a zombie
            if "arise.validate.worker" in " ".join(child.cmdline()):
                found.add(child.pid)
    return found


@pytest.mark.parametrize("entry", PARENT_CASES, ids=[e["name"] for e in PARENT_CASES])
def test_hostile_script_through_replay_export_and_the_servers_check(
    entry: dict[str, Any],
    hostile_pool: WorkerPool,
    listener: Listener,
    signals: SignalCounter,
    tmp_path: Path,
) -> None:
    """Replay and export take the trace of a check made with the gate off (so the parent
    alone must hold); the server checks with its own options (gate on). Either a clear
    error or files on the parent's own map, only in the output folder; never the canary or
    the secret, and no worker left behind."""
    from arise.errors import AriseError
    from arise.present.replay import write_replay
    from arise.present.source import load_trace
    from arise.present.xosc import write_export
    from arise.serve.checks import check_script

    case = prepare(entry, tmp_path / "case", listener)
    contacts, signals_before = listener.contacts, signals.count
    workers_before = _worker_processes()
    out = tmp_path / "out"
    options = CheckOptions(
        seed=1, steps=40, timeout=float(entry.get("timeout", CHECK_TIMEOUT)), static_gate=False
    )
    outcomes: list[str] = []
    try:
        source = load_trace(case.script, pool=hostile_pool, options=options)
    except AriseError as refusal:  # the script did not run: one clear line
        assert str(refusal).strip() and "\n" not in str(refusal).strip(), refusal
        outcomes.append("refused")
    else:
        assert source.map is None or Path(source.map.path).is_relative_to(cache_dir())
        write_replay(source, out)
        files = write_export(source, out)
        assert files.xodr is None or files.xodr.parent == out
        outcomes.append("replayed")
    view = check_script(case.script.read_text(encoding="utf-8"), tmp_path / "served", hostile_pool)
    assert isinstance(view, dict) and "ok" in view
    problems = []
    if case.canary_exists():
        problems.append(f"the canary {case.canary.name} exists")
    leaked = _files_holding(tmp_path, SECRET_TEXT, exclude=case.secret.parent)
    leaked += [] if SECRET_TEXT not in json.dumps(view) else ["the server's view"]
    if [name for name in leaked if "home" not in name]:
        problems.append(f"the secret is in {leaked}")
    if listener.contacts > contacts or signals.count > signals_before:
        problems.append("the script reached the network or signalled the test")
    outside = [
        p
        for p in (tmp_path / "case").rglob("*")
        if p.is_file() and p.stat().st_mtime > case.script.stat().st_mtime + 1
    ]
    if outside:
        problems.append(f"files appeared beside the script: {outside}")
    if _worker_processes() - workers_before - _worker_processes_of(hostile_pool):
        problems.append("a worker was left running")
    assert not problems, f"{entry['name']} ({outcomes}): " + "; ".join(problems)


def _worker_processes_of(pool: WorkerPool) -> set[int]:
    """The pool's own warm workers (and their children), which may stay."""
    pids: set[int] = set()
    for worker in list(pool._idle.queue):
        with contextlib.suppress(psutil.Error):
            process = psutil.Process(worker.process.pid)
            pids |= {process.pid, *(c.pid for c in process.children(recursive=True))}
    return pids


# --- the attacks are real -------------------------------------------------------------------
@dataclass
class LiveRun:
    evidence: bool
    output: str


@pytest.fixture(scope="session")
def live_runs(
    tmp_path_factory: pytest.TempPathFactory, signals: SignalCounter
) -> dict[str, LiveRun]:
    """Every live script run with no confinement and no gate: each in a forked child of
    an unconfined runner that imported Scenic once (tests/validate/unconfined_runner.py)."""
    root = tmp_path_factory.mktemp("live")
    map_copy = root / "arise_straight.xodr"
    shutil.copyfile(str(resources.files("arise.maps") / "data" / "arise_straight.xodr"), map_copy)
    env = {
        "PATH": os.environ.get("PATH", "/usr/bin:/bin"),
        "HOME": str(root),
        TOKEN_VARIABLE: SECRET_TEXT,
        "PYTHONDONTWRITEBYTECODE": "1",
        "MPLBACKEND": "Agg",
        "ARISE_CACHE_DIR": str(root / "cache"),
        "OMP_NUM_THREADS": "1",
        "OPENBLAS_NUM_THREADS": "1",
    }
    runner = subprocess.Popen(
        [
            sys.executable,
            str(Path(__file__).with_name("unconfined_runner.py")),
            str(map_copy),
            str(EXAMPLES / "pedestrian_crossing.scenic"),
        ],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
        cwd=root,
        env=env,
        start_new_session=True,
    )
    assert runner.stdin is not None and runner.stdout is not None
    runs: dict[str, LiveRun] = {}
    try:
        assert "ready" in runner.stdout.readline(), "the unconfined runner did not start"
        for entry in LIVE:
            listener = Listener()
            try:
                case = prepare(entry, root / entry["name"], listener)
                signals_before = signals.count
                output_file = case.root / "output.txt"
                runner.stdin.write(
                    json.dumps(
                        {
                            "script": str(case.script),
                            "cwd": str(case.work),
                            "home": str(case.home),
                            "output": str(output_file),
                            "timeout": LIVE_TIMEOUT,
                        }
                    )
                    + "\n"
                )
                runner.stdin.flush()
                reply = json.loads(runner.stdout.readline() or "{}")
                output = output_file.read_text(errors="replace") if output_file.exists() else ""
                evidence = {
                    "canary": case.canary_exists(),
                    "secret": SECRET_TEXT in output,
                    "connection": listener.contacts > 0,
                    "signal": reply.get("signals", 0) > 0 or signals.count > signals_before,
                    "marker": FORGED_MARKER in output,
                }[entry["evidence"]]
                runs[entry["name"]] = LiveRun(evidence, f"{reply}\n{output}")
            finally:
                listener.close()
    finally:
        runner.stdin.close()
        try:
            runner.wait(10)
        except subprocess.TimeoutExpired:
            os.killpg(runner.pid, signal.SIGKILL)
            runner.wait()
    return runs


@pytest.mark.parametrize("entry", LIVE, ids=[entry["name"] for entry in LIVE])
def test_attack_works_without_confinement(
    entry: dict[str, Any], live_runs: dict[str, LiveRun]
) -> None:
    run = live_runs[entry["name"]]
    assert run.evidence, (
        f"{entry['name']} did nothing unconfined (expected: "
        f"{entry['evidence']}); output:\n{run.output[-3000:]}"
    )
