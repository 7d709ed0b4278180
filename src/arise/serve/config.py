"""How one `arise serve` is set up: address, token, runs folder, limits and the base
options every generation starts from."""

from __future__ import annotations

import ipaddress
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import platformdirs

from arise.generate.extract import MAX_DESCRIPTION_CHARS
from arise.generate.options import GenerateOptions
from arise.serve.errors import UnsafeBinding

DEFAULT_PORT = 8765
TOKEN_ENV = "ARISE_SERVE_TOKEN"
RUNS_ENV = "ARISE_RUNS_DIR"
#: A pasted or uploaded script over this many bytes is refused (413).
MAX_SCRIPT_BYTES = 256 * 1024
#: Jobs that may wait for one model at once; one more is refused (503).
MAX_QUEUED = 50
#: Script checks that may wait for a check process at once; one more is refused (503).
MAX_QUEUED_CHECKS = 8
#: Seconds the check process may spend reading a script, or a worker's result, before it
#: is killed (the script's own run in the validator has its own time-out).
CHECK_PARSE_SECONDS = 30.0
_TOKEN = re.compile(r"^[A-Za-z0-9._~-]{8,256}$")


def default_runs_dir() -> Path:
    """$ARISE_RUNS_DIR, or `runs` under the user's data folder (~/.local/share/arise/runs)."""
    override = os.environ.get(RUNS_ENV)
    if override:
        return Path(override).expanduser()
    return Path(platformdirs.user_data_dir("arise")) / "runs"


def is_loopback(host: str) -> bool:
    """127.0.0.0/8, ::1 and `localhost`: addresses only this machine can reach."""
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False


@dataclass(frozen=True)
class ServeConfig:
    host: str = "127.0.0.1"
    port: int = DEFAULT_PORT
    token: str | None = None
    runs_dir: Path = field(default_factory=default_runs_dir)
    max_description_chars: int = MAX_DESCRIPTION_CHARS
    max_script_bytes: int = MAX_SCRIPT_BYTES
    max_queued: int = MAX_QUEUED
    max_queued_checks: int = MAX_QUEUED_CHECKS
    check_parse_seconds: float = CHECK_PARSE_SECONDS
    # Confined validation workers shared by every job and check.
    workers: int = 1
    # A cassette to answer model calls from (offered as the "replay" model, and the default).
    replay: str | None = None
    # The provider and model preselected on the page (None: the configured default).
    provider: str | None = None
    model: str | None = None
    # What every generation starts from (budgets, simulator, map folder, seed).
    options: GenerateOptions = field(default_factory=GenerateOptions)

    def __post_init__(self) -> None:
        if not is_loopback(self.host) and not self.token:
            raise UnsafeBinding(
                f"--host {self.host} lets other machines reach the server: give an access "
                f"token with --token or {TOKEN_ENV} (or keep the default 127.0.0.1)"
            )
        if self.token is not None and not _TOKEN.match(self.token):
            raise UnsafeBinding(
                "the access token must be at least 8 characters of letters, digits, "
                "'.', '_', '~' or '-' (e.g. from `python -c 'import secrets; "
                "print(secrets.token_urlsafe())'`)"
            )

    @property
    def loopback(self) -> bool:
        return is_loopback(self.host)

    @property
    def max_request_bytes(self) -> int:
        """A whole request body: the largest script, JSON-escaped (at most 6 bytes a
        byte), plus room for the fields around it."""
        return self.max_script_bytes * 6 + 64 * 1024
