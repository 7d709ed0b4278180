"""Fixtures for the LLM tests: a hermetic environment, the real model, a real server.

The server fixture runs llama-cpp-python's OpenAI-compatible server on loopback with the
default local model; tests that need it skip with the reason when the model or the
package is absent (``make setup-dev`` installs both).
"""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator
from pathlib import Path

import pytest

from arise.llm import model_files

CASSETTES = Path(__file__).resolve().parents[1] / "cassettes" / "llm"

_SECRET_SUFFIXES = ("_API_KEY", "_TOKEN")


@pytest.fixture(autouse=True)
def hermetic_env(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> Path:
    """No user config, no user cache, no real keys: every test starts from the presets."""
    for name in list(os.environ):
        if (
            name.startswith("ARISE_")
            and name != "ARISE_MODELS_DIR"
            or name.endswith(_SECRET_SUFFIXES)
        ):
            monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("ARISE_CONFIG", str(tmp_path / "no-config.toml"))
    monkeypatch.setenv("ARISE_CACHE_DIR", str(tmp_path / "cache"))
    return tmp_path


def _have_llama_cpp() -> bool:
    try:
        import llama_cpp  # noqa: F401
    except ImportError:
        return False
    return True


@pytest.fixture(scope="session")
def model_path() -> Path:
    path = model_files.default_model_path()
    if not model_files.is_installed(path):
        pytest.skip(f"default model not installed at {path}: run `arise llm install-model`")
    if not _have_llama_cpp():
        pytest.skip("llama-cpp-python is not installed: pip install -e '.[local]'")
    return path


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


@pytest.fixture(scope="session")
def llama_server(model_path: Path) -> Iterator[str]:
    """``python -m llama_cpp.server`` on 127.0.0.1 with the local model; yields the base URL."""
    try:
        import llama_cpp.server  # noqa: F401
    except ImportError:
        pytest.skip("llama-cpp-python[server] extras are not installed")
    port = _free_port()
    log = open(  # noqa: SIM115 - closed in the finaliser below
        Path(os.environ.get("TMPDIR", "/tmp")) / f"arise-llama-server-{port}.log", "w"
    )
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "llama_cpp.server",
            "--model",
            str(model_path),
            "--model_alias",
            "qwen-local",
            "--host",
            "127.0.0.1",
            "--port",
            str(port),
            "--n_threads",
            "1",
            "--n_threads_batch",
            "1",
            "--n_ctx",
            "4096",
        ],
        stdout=log,
        stderr=subprocess.STDOUT,
        start_new_session=True,
    )
    base_url = f"http://127.0.0.1:{port}/v1"
    deadline = time.monotonic() + 120
    try:
        while True:
            if proc.poll() is not None:
                pytest.fail(f"llama_cpp.server exited with {proc.returncode}; see {log.name}")
            try:
                with urllib.request.urlopen(f"{base_url}/models", timeout=2) as resp:
                    if resp.status == 200:
                        break
            except OSError:
                pass
            if time.monotonic() > deadline:
                pytest.fail(f"llama_cpp.server not ready after 120 s; see {log.name}")
            time.sleep(0.5)
        yield base_url
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGTERM)
            try:
                proc.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
        log.close()
