"""The models the page offers: every configured provider, and a cassette when one is given."""

from __future__ import annotations

import importlib.util
import os
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from arise.llm import model_files
from arise.llm.settings import ProviderSettings, Settings

REPLAY = "replay"


@dataclass(frozen=True)
class ModelChoice:
    """One provider and model the user can pick; `ready` says whether it can answer here."""

    provider: str
    model: str
    label: str
    ready: bool
    note: str = ""

    @property
    def key(self) -> str:
        """The queue this choice's jobs wait in: one job at a time per model."""
        return f"{self.provider}/{self.model}"

    def as_dict(self) -> dict[str, Any]:
        return {**asdict(self), "key": self.key}


def _readiness(profile: ProviderSettings) -> tuple[bool, str]:
    if profile.kind == "local":
        if importlib.util.find_spec("llama_cpp") is None:
            return False, "llama-cpp-python is not installed (pip install 'arise[local]')"
        path = Path(profile.model_path) if profile.model_path else None
        if not model_files.is_installed(path):
            return False, f"model not installed: {model_files.how_to_get()}"
        return True, "embedded, offline"
    if profile.api_key_env and profile.key_required and not os.environ.get(profile.api_key_env):
        return False, f"set {profile.api_key_env} in the server's environment"
    where = profile.base_url or "the provider's endpoint"
    return True, f"served at {where}"


def model_choices(settings: Settings, replay: str | None = None) -> list[ModelChoice]:
    """The cassette first (when given), then the configured default, then the others."""
    found: list[ModelChoice] = []
    if replay:
        found.append(
            ModelChoice(REPLAY, Path(replay).name, f"replayed from {Path(replay).name}", True)
        )
    names = sorted(settings.profiles, key=lambda name: (name != settings.provider, name))
    for name in names:
        profile = settings.profiles[name]
        if profile.kind == "replay":
            continue  # only with a cassette, above
        ready, note = _readiness(profile)
        default = " (default)" if name == settings.provider else ""
        label = f"{name}: {profile.model}{default}"
        found.append(ModelChoice(name, profile.model, label, ready, note))
    return found
