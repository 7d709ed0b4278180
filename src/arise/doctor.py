"""`arise doctor`: can this machine do the main job, safely? One screen, no model call.

It starts one real validator worker and reports the confinement that worker reached
(not what the kernel claims), then the model, the maps, CARLA and the cache folders.
Exit code 0 when everything the offline default needs is there, 1 otherwise.
"""

from __future__ import annotations

import importlib.util
import os
import shutil
from dataclasses import dataclass
from enum import StrEnum
from typing import Annotated

import typer

from arise import terminal
from arise.errors import AriseError
from arise.paths import cache_dir, config_path

console = terminal.console()


class Verdict(StrEnum):
    OK = "ok"
    WARN = "warn"  # works, but not as well as it could
    FAIL = "FAIL"  # the offline default cannot run safely


@dataclass(frozen=True)
class Finding:
    topic: str
    verdict: Verdict
    text: str


def _sandbox() -> list[Finding]:
    from arise.validate.pool import WorkerPool
    from arise.validate.sandbox import kernel_support, required_by_settings

    kernel = kernel_support()
    try:
        with WorkerPool(size=1) as pool:
            report = pool.sandbox()
    except AriseError as error:
        return [Finding("sandbox", Verdict.FAIL, f"no validator worker could start: {error}")]
    required = (
        "required for every run"
        if required_by_settings()
        else "not required (--require-sandbox or [sandbox] require = true to insist)"
    )
    verdict = Verdict.OK if report.full else Verdict.FAIL
    text = f"{report.label}; Landlock ABI {report.landlock_abi}; {required}"
    findings = [Finding("sandbox", verdict, text)]
    findings += [Finding("sandbox", Verdict.WARN, note) for note in report.notes]
    if kernel.missing and report.full:
        findings.append(Finding("sandbox", Verdict.WARN, "kernel probe and worker disagree"))
    return findings


def _model() -> list[Finding]:
    from arise.llm import model_files
    from arise.llm.settings import load_settings

    try:
        settings = load_settings()
    except AriseError as error:
        return [Finding("model", Verdict.FAIL, str(error))]
    findings = [Finding("model", Verdict.OK, f"default provider: {settings.provider}")]
    path = model_files.default_model_path()
    if model_files.is_installed(path):
        findings.append(Finding("model", Verdict.OK, f"embedded model installed: {path}"))
    else:
        findings.append(
            Finding("model", Verdict.FAIL, f"embedded model missing; {model_files.how_to_get()}")
        )
    profile = settings.profiles.get("local")
    if profile is not None and profile.prefix_store:
        from arise.llm.prefix_store import PrefixStore

        store = PrefixStore(limit_mb=profile.prefix_store_mb)
        empty = "" if store.entries() else " (the first run, or `arise llm warm`, builds it)"
        findings.append(Finding("model", Verdict.OK, f"prefix store: {store.describe()}{empty}"))
    elif profile is not None:
        findings.append(
            Finding(
                "model",
                Verdict.WARN,
                "prefix store off: every run re-reads the fixed prompt prefixes",
            )
        )
    try:
        import llama_cpp  # noqa: F401
    except ImportError:
        findings.append(
            Finding(
                "model",
                Verdict.FAIL,
                "llama-cpp-python is not installed (pip install 'arise[local]', or `make demo`)",
            )
        )
    return findings


def _maps(map_dir: str | None) -> list[Finding]:
    from arise.maps.registry import MapRegistry

    try:
        registry = MapRegistry(map_dir)
    except AriseError as error:
        return [Finding("maps", Verdict.FAIL, str(error))]
    names = registry.names()
    towns = [n for n in names if registry.entries[n].source == "map-dir"]
    findings = [
        Finding(
            "maps",
            Verdict.OK if names else Verdict.FAIL,
            f"{len(names)} available: {', '.join(names)}",
        )
    ]
    if not towns:
        findings.append(
            Finding(
                "maps",
                Verdict.WARN,
                "no CARLA towns: point --map-dir or "
                "ARISE_MAP_DIR at a folder of .xodr files to use them",
            )
        )
    return findings


def _carla(host: str, port: int) -> list[Finding]:
    from arise.validate.carla_server import unreachable_reason

    reason = unreachable_reason(host, port, 2.0)
    if reason:
        return [
            Finding(
                "carla",
                Verdict.WARN,
                f"{host}:{port} not reachable (offline mode works without it)",
            )
        ]
    return [Finding("carla", Verdict.OK, f"{host}:{port} answers")]


def _verifai() -> list[Finding]:
    """VerifAI is optional: scripts with VerifAI parameters and `arise search` need it."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        installed = version("verifai")
    except PackageNotFoundError:
        return [
            Finding(
                "verifai",
                Verdict.WARN,
                "not installed: VerifAI-style scripts and `arise search` need "
                "`pip install --no-deps verifai==2.2.0 dill` (docs/search.md)",
            )
        ]
    samplers = "random, halton, ce, surrogate" + (
        ", bo" if importlib.util.find_spec("GPyOpt") else " (bo needs GPyOpt)"
    )
    return [Finding("verifai", Verdict.OK, f"verifai {installed}; samplers: {samplers}")]


def _folders() -> list[Finding]:
    findings = []
    root = cache_dir()
    for folder in (root, root / "maps", root / "models"):
        size = (
            sum(f.stat().st_size for f in folder.rglob("*") if f.is_file())
            if folder.is_dir()
            else 0
        )
        writable = os.access(folder if folder.exists() else root, os.W_OK)
        findings.append(
            Finding(
                "cache",
                Verdict.OK if writable else Verdict.FAIL,
                f"{folder} ({size / 1e6:.1f} MB{'' if writable else ', NOT writable'})",
            )
        )
    free = shutil.disk_usage(root).free
    if free < 2 * 1024**3:
        findings.append(Finding("cache", Verdict.WARN, f"only {free / 1e9:.1f} GB free"))
    config = config_path()
    findings.append(
        Finding("config", Verdict.OK, f"{config} ({'present' if config.exists() else 'absent'})")
    )
    return findings


DOCTOR_HELP = """Check this machine: sandbox, model, maps, CARLA, VerifAI, cache folders. No model call.

Examples:

  arise doctor

  arise doctor --map-dir ../shared/maps/CARLA --carla-host 10.0.0.5
"""


def doctor_command(
    map_dir: Annotated[str | None, typer.Option(help="Folder of extra .xodr maps.")] = None,
    carla_host: Annotated[str, typer.Option(help="CARLA server host.")] = "127.0.0.1",
    carla_port: Annotated[int, typer.Option(help="CARLA server port.")] = 2000,
) -> None:
    findings = [
        *_sandbox(),
        *_model(),
        *_maps(map_dir),
        *_carla(carla_host, carla_port),
        *_verifai(),
        *_folders(),
    ]
    colour = {Verdict.OK: "green", Verdict.WARN: "yellow", Verdict.FAIL: "bold red"}
    for finding in findings:
        console.print(
            terminal.text(
                (f"{finding.verdict.value:>4}", colour[finding.verdict]),
                f" {finding.topic:<8} ",
                finding.text,
            )
        )
    failed = [f for f in findings if f.verdict is Verdict.FAIL]
    console.print("\nready" if not failed else f"\n{len(failed)} problem(s) to fix")
    raise typer.Exit(1 if failed else 0)
