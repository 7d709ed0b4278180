"""``get_provider``: settings in, a ready provider stack out.

The stack, outermost first: usage ledger -> cassette recorder -> response cache ->
retries -> backend. The recorder sits outside the cache so a recorded run is complete
even when every answer came from the cache; the ledger sits outermost so it counts cache
hits and every re-ask.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from arise.llm.accounting import UsageLedger
from arise.llm.base import BaseProvider
from arise.llm.cache import CachedProvider, ResponseCache
from arise.llm.cassette import RecordingProvider, ReplayProvider
from arise.llm.retry import RetryingProvider, RetryPolicy
from arise.llm.settings import (
    ProviderKind,
    ProviderSettings,
    Settings,
    load_settings,
    with_overrides,
)
from arise.llm.types import LLMError


def build_backend(profile: ProviderSettings, run_index: int = 0) -> BaseProvider:
    """The bare backend for one profile (no cache, no retries)."""
    caps = profile.capabilities()
    if profile.kind is ProviderKind.LOCAL:
        from arise.llm.local import LocalProvider

        return LocalProvider(
            name=profile.name,
            model_path=profile.model_path,
            threads=profile.threads,
            n_ctx=profile.n_ctx,
            prefix_cache_mb=profile.prefix_cache_mb,
            prefix_store=profile.prefix_store,
            prefix_store_mb=profile.prefix_store_mb,
            lazy_grammar=profile.lazy_grammar,
            capabilities=caps,
        )
    if profile.kind is ProviderKind.OPENAI:
        from arise.llm.openai_compat import OpenAICompatProvider

        if not profile.base_url:
            raise LLMError(
                f"{profile.name}: no base URL; set ARISE_BASE_URL or base_url in the config"
            )
        if not profile.model:
            raise LLMError(f"{profile.name}: no model name; set ARISE_MODEL or model in the config")
        return OpenAICompatProvider(
            name=profile.name,
            model=profile.model,
            base_url=profile.base_url,
            api_key=profile.api_key(),
            capabilities=caps,
            timeout=profile.timeout,
            key_env=profile.api_key_env,
        )
    if profile.kind is ProviderKind.ANTHROPIC:
        from arise.llm.anthropic_provider import AnthropicProvider

        key = profile.api_key()
        if key is None:  # key_required=False in a custom profile: still cannot work without one
            raise LLMError(f"{profile.name}: set {profile.api_key_env or 'ANTHROPIC_API_KEY'}")
        return AnthropicProvider(
            name=profile.name,
            model=profile.model,
            api_key=key,
            capabilities=caps,
            base_url=profile.base_url,
            timeout=profile.timeout,
            key_env=profile.api_key_env or "ANTHROPIC_API_KEY",
        )
    if profile.kind is ProviderKind.REPLAY:
        if not profile.cassette:
            raise LLMError("replay: no cassette; pass --replay FILE or set ARISE_REPLAY")
        return ReplayProvider(Path(profile.cassette), run_index=run_index)
    raise LLMError(f"{profile.name}: unknown kind {profile.kind!r}")


def get_provider(
    name: str | None = None,
    *,
    settings: Settings | None = None,
    cache: bool | None = None,
    cache_path: Path | None = None,
    record: Path | str | None = None,
    replay: Path | str | None = None,
    run_index: int = 0,
    retry: RetryPolicy | None = None,
    **overrides: Any,
) -> UsageLedger:
    """Compose a provider from settings plus explicit overrides (model, base_url, threads...).

    ``replay`` answers from a cassette instead of any backend; ``record`` writes one.
    ``cache=None`` follows the settings (``--no-cache`` passes False).
    """
    settings = settings or load_settings()
    if replay is not None:
        name, overrides = "replay", {**overrides, "cassette": str(replay)}
    profile = with_overrides(settings, name or settings.provider, **overrides)
    provider: BaseProvider = build_backend(profile, run_index=run_index)
    if profile.kind in (ProviderKind.OPENAI, ProviderKind.ANTHROPIC):
        provider = RetryingProvider(provider, retry or RetryPolicy(attempts=settings.retries))
    use_cache = settings.cache if cache is None else cache
    if use_cache and profile.kind is not ProviderKind.REPLAY:
        store = ResponseCache(
            cache_path or (Path(settings.cache_path).expanduser() if settings.cache_path else None)
        )
        provider = CachedProvider(provider, store, run_index=run_index)
    if record is not None:
        provider = RecordingProvider(provider, Path(record), run_index=run_index)
    ledger = UsageLedger(provider)
    ledger.max_reasks = settings.max_reasks
    return ledger
