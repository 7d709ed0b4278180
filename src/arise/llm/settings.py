"""Where settings come from: built-in presets < config file < environment < explicit arguments.

The config file is ``$ARISE_CONFIG`` or ``<user config dir>/arise/config.toml`` (on Linux
``~/.config/arise/config.toml``). It may name the environment variable that holds a key
(``api_key_env``) but never hold a key: a key in a file is refused, so none can end up
committed with a project.
"""

from __future__ import annotations

import os
import tomllib
from dataclasses import dataclass, field, fields, replace
from enum import StrEnum
from pathlib import Path
from typing import Any, get_args

from arise.llm.types import Capabilities, LLMError, MissingCredentials, StructuredStyle
from arise.paths import config_path


class ProviderKind(StrEnum):
    """Which backend a profile builds; parsed once from the config file, never compared as text."""

    OPENAI = "openai"  # any OpenAI-compatible server (llama.cpp, Ollama, vLLM, the hosted ones)
    ANTHROPIC = "anthropic"
    LOCAL = "local"  # the embedded llama-cpp-python model
    REPLAY = "replay"  # answers from a recorded cassette


#: Words that mean "a secret" in a config file; we refuse them.
_SECRET_FIELDS = {"api_key", "key", "token", "secret", "password"}


@dataclass(frozen=True)
class ProviderSettings:
    name: str
    kind: ProviderKind
    model: str = ""
    base_url: str | None = None
    api_key_env: str | None = None
    key_required: bool = False
    structured: str = "prompt"
    max_context: int = 8192
    seed: bool = False
    local: bool = False
    timeout: float = 300.0
    # embedded model only
    model_path: str | None = None
    threads: int = 2  # 0 or "auto": pick per call from how busy the CPU is
    n_ctx: int = 8192
    prefix_cache_mb: int = 0  # >0: llama-cpp-python's own whole-prompt RAM cache
    prefix_store: bool = True  # keep fixed prompt prefixes' states on disk for new processes
    prefix_store_mb: int = 512  # size bound of that store (least recently used dropped)
    lazy_grammar: bool = True  # greedy JSON: ask the grammar about the best token first
    # replay only
    cassette: str | None = None

    def capabilities(self) -> Capabilities:
        return Capabilities(
            structured=self.structured,  # type: ignore[arg-type]
            max_context=self.n_ctx if self.kind is ProviderKind.LOCAL else self.max_context,
            seed=self.seed,
            local=self.local,
        )

    def api_key(self) -> str | None:
        """The key from the environment; a required but absent key is one clear error."""
        if not self.api_key_env:
            return None
        value = os.environ.get(self.api_key_env, "").strip()
        if not value and self.key_required:
            raise MissingCredentials(self.name, self.api_key_env)
        return value or None


PRESETS: dict[str, ProviderSettings] = {
    p.name: p
    for p in (
        ProviderSettings(
            "local",
            ProviderKind.LOCAL,
            model="qwen2.5-coder-1.5b-instruct-q4_k_m",
            structured="json_object_schema",
            seed=True,
            local=True,
        ),
        ProviderSettings(
            "llamacpp",
            ProviderKind.OPENAI,
            model="local",
            base_url="http://127.0.0.1:8080/v1",
            api_key_env="LLAMACPP_API_KEY",
            structured="json_object_schema",
            seed=True,
            local=True,
            max_context=8192,
        ),
        ProviderSettings(
            "ollama",
            ProviderKind.OPENAI,
            model="qwen2.5-coder:1.5b",
            base_url="http://127.0.0.1:11434/v1",
            structured="json_schema",
            seed=True,
            local=True,
            max_context=8192,
        ),
        ProviderSettings(
            "vllm",
            ProviderKind.OPENAI,
            model="Qwen/Qwen2.5-Coder-7B-Instruct",
            base_url="http://127.0.0.1:8000/v1",
            api_key_env="VLLM_API_KEY",
            structured="json_schema",
            seed=True,
            local=True,
            max_context=32768,
        ),
        ProviderSettings(
            "openai",
            ProviderKind.OPENAI,
            model="gpt-4o-mini",
            base_url="https://api.openai.com/v1",
            api_key_env="OPENAI_API_KEY",
            key_required=True,
            structured="json_schema",
            seed=True,
            max_context=128_000,
            timeout=120.0,
        ),
        ProviderSettings(
            "deepseek",
            ProviderKind.OPENAI,
            model="deepseek-chat",
            base_url="https://api.deepseek.com/v1",
            api_key_env="DEEPSEEK_API_KEY",
            key_required=True,
            structured="json_object",
            max_context=64_000,
            timeout=120.0,
        ),
        ProviderSettings(
            "gemini",
            ProviderKind.OPENAI,
            model="gemini-2.5-flash",
            base_url="https://generativelanguage.googleapis.com/v1beta/openai/",
            api_key_env="GEMINI_API_KEY",
            key_required=True,
            structured="json_schema",
            max_context=1_000_000,
            timeout=120.0,
        ),
        ProviderSettings(
            "anthropic",
            ProviderKind.ANTHROPIC,
            model="claude-haiku-4-5",
            api_key_env="ANTHROPIC_API_KEY",
            key_required=True,
            structured="tool",
            max_context=200_000,
            timeout=120.0,
        ),
        ProviderSettings("replay", ProviderKind.REPLAY, model="recorded"),
    )
}

_FIELD_TYPES = {f.name: f.type for f in fields(ProviderSettings)}
_STRUCTURED_STYLES = get_args(StructuredStyle)


@dataclass(frozen=True)
class Settings:
    provider: str = "local"
    cache: bool = True
    cache_path: str | None = None
    max_reasks: int = 2
    retries: int = 4
    profiles: dict[str, ProviderSettings] = field(default_factory=lambda: dict(PRESETS))
    config_path: Path | None = None  # the file that was read, if any

    def profile(self, name: str | None = None) -> ProviderSettings:
        wanted = name or self.provider
        if wanted not in self.profiles:
            known = ", ".join(sorted(self.profiles))
            raise LLMError(
                f"unknown provider {wanted!r}; known: {known} (or add [providers.{wanted}] to the config file)"
            )
        return self.profiles[wanted]


def _coerce(name: str, value: Any, where: str) -> Any:
    """Light type checking, so a typo in the config is reported, not carried along."""
    expected = str(_FIELD_TYPES[name])
    if name == "threads" and str(value).lower() == "auto":
        return 0
    if "bool" in expected:
        if isinstance(value, bool):
            return value
        words = ("1", "true", "yes", "on", "0", "false", "no", "off")
        if isinstance(value, str) and value.lower() in words:
            return value.lower() in ("1", "true", "yes", "on")
    elif "int" in expected and "str" not in expected:
        try:
            return int(value)
        except (TypeError, ValueError):
            pass
    elif "float" in expected:
        try:
            return float(value)
        except (TypeError, ValueError):
            pass
    elif isinstance(value, str):
        return value
    raise LLMError(f"{where}: {name} = {value!r} is not a valid {expected}")


def _apply(profile: ProviderSettings, values: dict[str, Any], where: str) -> ProviderSettings:
    updates: dict[str, Any] = {}
    for raw_key, value in values.items():
        key = raw_key.replace("-", "_")
        if key in _SECRET_FIELDS:
            raise LLMError(
                f"{where}: refusing '{raw_key}': keep keys in the environment and name the "
                f'variable with api_key_env = "..."'
            )
        if key == "name" or key not in _FIELD_TYPES:
            raise LLMError(f"{where}: unknown setting {raw_key!r}")
        updates[key] = _coerce(key, value, where)
    if "kind" in updates:
        updates["kind"] = _parse_kind(updates["kind"], where)
    if "structured" in updates and updates["structured"] not in _STRUCTURED_STYLES:
        raise LLMError(f"{where}: structured must be one of {', '.join(_STRUCTURED_STYLES)}")
    return replace(profile, **updates)


def _parse_kind(value: Any, where: str) -> ProviderKind:
    """The one place a profile's kind is read from text."""
    try:
        return ProviderKind(value)
    except ValueError:
        allowed = ", ".join(k.value for k in ProviderKind)
        raise LLMError(f"{where}: kind must be one of {allowed}, not {value!r}") from None


def load_settings(path: Path | None = None, env: dict[str, str] | None = None) -> Settings:
    env = dict(os.environ) if env is None else env
    path = path or config_path()
    data: dict[str, Any] = {}
    read: Path | None = None
    if path.is_file():
        try:
            data = tomllib.loads(path.read_text("utf-8"))
        except tomllib.TOMLDecodeError as exc:
            raise LLMError(f"config {path}: not valid TOML ({exc})") from exc
        read = path
    llm = dict(data.get("llm", {}))
    profiles = dict(PRESETS)
    for name, values in (data.get("providers") or {}).items():
        where = f"config {path} [providers.{name}]"
        if name in profiles:
            profiles[name] = _apply(profiles[name], dict(values), where)
        else:
            values = dict(values)
            kind = _parse_kind(values.pop("kind", ProviderKind.OPENAI), where)
            profiles[name] = _apply(ProviderSettings(name, kind), values, where)
    for key in llm:
        if key.replace("-", "_") in _SECRET_FIELDS:
            raise LLMError(f"config {path} [llm]: refusing '{key}': keys belong in the environment")
    settings = Settings(
        provider=str(llm.get("provider", "local")),
        cache=bool(llm.get("cache", True)),
        cache_path=llm.get("cache_path"),
        max_reasks=int(llm.get("max_reasks", 2)),
        retries=int(llm.get("retries", 4)),
        profiles=profiles,
        config_path=read,
    )
    return apply_env(settings, env)


def apply_env(settings: Settings, env: dict[str, str]) -> Settings:
    """ARISE_* variables override the file; per-provider ones apply to the chosen provider."""
    provider = env.get("ARISE_PROVIDER") or settings.provider
    updates: dict[str, Any] = {}
    if env.get("ARISE_LLM_CACHE"):
        updates["cache"] = env["ARISE_LLM_CACHE"].lower() not in ("0", "false", "no", "off")
    if env.get("ARISE_MAX_REASKS"):
        updates["max_reasks"] = int(env["ARISE_MAX_REASKS"])
    per_provider = {
        "ARISE_MODEL": "model",
        "ARISE_BASE_URL": "base_url",
        "ARISE_MODEL_PATH": "model_path",
        "ARISE_LLM_THREADS": "threads",
        "ARISE_LLM_CTX": "n_ctx",
        "ARISE_LLM_TIMEOUT": "timeout",
        "ARISE_REPLAY": "cassette",
        "ARISE_PREFIX_STORE": "prefix_store",
        "ARISE_PREFIX_STORE_MB": "prefix_store_mb",
        "ARISE_LAZY_GRAMMAR": "lazy_grammar",
    }
    values = {attr: env[var] for var, attr in per_provider.items() if env.get(var)}
    profiles = dict(settings.profiles)
    if values and provider in profiles:
        profiles[provider] = _apply(profiles[provider], values, "environment")
    return replace(settings, provider=provider, profiles=profiles, **updates)


def with_overrides(settings: Settings, name: str, **overrides: Any) -> ProviderSettings:
    """The profile ``name`` with explicit (CLI or caller) values on top; None means unset."""
    given = {k: v for k, v in overrides.items() if v is not None}
    return _apply(settings.profile(name), given, "arguments") if given else settings.profile(name)
