"""The embedded default: a GGUF model run in this process by llama-cpp-python.

One model stays loaded per process (loading costs ~1.3 s and ~2 GB), and its KV state is
kept between calls: llama-cpp-python compares the new prompt's tokens with the ones it
already evaluated and only evaluates the rest. The fixed prefix of each prompt (system
prompt and few-shot examples) is evaluated on its own and its state kept, in memory and
in the disk prefix store (`local_prefix`, `prefix_store`), so interleaved prompts and new
processes skip it. An optional RAM state cache (``prefix_cache_mb``) is llama-cpp-python's
own whole-prompt cache.

The thread count is a parameter because on 2 cores a second busy process makes two
threads much slower than one (generation fell from ~16 to under 1 token/s in our
benchmark); the pipeline lowers it while the validator runs. ``threads=0`` ("auto")
decides before each call from how busy the other processes kept the CPU just before.
"""

from __future__ import annotations

import os
import threading
import time
from pathlib import Path
from typing import Any

from arise.llm import lazy_grammar
from arise.llm.base import BaseProvider
from arise.llm.local_prefix import PrefixKeeper, PrefixOutcome
from arise.llm.model_files import DEFAULT_MODEL, default_model_path, how_to_get
from arise.llm.prefix_store import DEFAULT_LIMIT_MB, PrefixStore
from arise.llm.structured import response_format
from arise.llm.types import (
    Capabilities,
    Completion,
    Message,
    ModelNotInstalled,
    PrefixUse,
    ProviderError,
    ProviderErrorKind,
    ProviderUnavailable,
    Request,
    Usage,
)

_LOCK = threading.RLock()  # one Llama is not thread-safe; calls in a process take turns
_LOADED: dict[str, Any] = {}  # {"key": (path, n_ctx, cache_mb), "llama": Llama, "keeper": ...}
_N_BATCH = 512


def _import_llama_cpp() -> Any:
    try:
        import llama_cpp
    except ImportError as exc:
        raise ProviderUnavailable(
            "local: llama-cpp-python is not installed; pip install 'arise[local]' "
            "(it builds from source, ~5 min) or pick another --provider"
        ) from exc
    return llama_cpp


def loaded_model() -> Any | None:
    """The Llama instance this process holds, if any (for tests and benchmarks)."""
    return _LOADED.get("llama")


def unload() -> None:
    """Free the model (the next call loads it again)."""
    with _LOCK:
        llama = _LOADED.pop("llama", None)
        _LOADED.clear()
        if llama is not None:
            llama.close()


def _load(path: Path, n_ctx: int, threads: int, cache_mb: int) -> tuple[Any, float]:
    key = (str(path), n_ctx, cache_mb)
    if _LOADED.get("key") == key:
        return _LOADED["llama"], 0.0
    unload()
    llama_cpp = _import_llama_cpp()
    started = time.perf_counter()
    try:
        llama = llama_cpp.Llama(
            model_path=str(path),
            n_ctx=n_ctx,
            n_batch=_N_BATCH,
            n_threads=threads,
            n_threads_batch=threads,
            verbose=False,
        )
    except (ValueError, RuntimeError) as exc:
        raise ProviderUnavailable(f"local: could not load {path}: {exc}") from exc
    if cache_mb > 0:
        llama.set_cache(llama_cpp.LlamaRAMCache(capacity_bytes=cache_mb << 20))
    seconds = time.perf_counter() - started
    # What changes the numbers of a prefix's state besides the model and the tokens.
    state_settings: dict[str, object] = {
        "n_ctx": n_ctx,
        "n_batch": _N_BATCH,
        "llama_cpp": getattr(llama_cpp, "__version__", "?"),
    }
    keeper = PrefixKeeper(llama, llama_cpp, str(path), state_settings)
    lazy_grammar.install(
        llama,
        llama_cpp,
        enabled=lambda: bool(_LOADED.get("lazy_grammar", True)),
        on_build=lambda sampler: _LOADED.__setitem__("lazy_sampler", sampler),
    )
    _LOADED.update(key=key, llama=llama, seconds=seconds, threads=threads, keeper=keeper)
    return llama, seconds


def _set_threads(llama: Any, threads: int) -> None:
    """Change threads without reloading (llama.cpp allows it per context)."""
    if _LOADED.get("threads") == threads:
        return
    llama_cpp = _import_llama_cpp()
    llama_cpp.llama_set_n_threads(llama.ctx, threads, threads)
    llama.n_threads = threads
    llama.n_threads_batch = threads
    _LOADED["threads"] = threads


class CpuWatch:
    """How many cores *other* processes used since the last look (Linux /proc/stat).

    The load average cannot answer this: it counts our own threads too.
    """

    def __init__(self) -> None:
        self._last = self._snapshot()

    @staticmethod
    def _snapshot() -> tuple[float, float, float] | None:
        try:
            with open("/proc/stat") as fh:
                fields = [int(x) for x in fh.readline().split()[1:9]]
        except (OSError, ValueError):
            return None
        user, nice, system_, _idle, _iowait, irq, softirq, steal = fields
        busy = (user + nice + system_ + irq + softirq + steal) / os.sysconf("SC_CLK_TCK")
        own = os.times()
        return busy, own.user + own.system, time.monotonic()

    def others(self, min_window: float = 0.3) -> float:
        before = self._last
        if before is None:
            return 0.0
        now = self._snapshot()
        if now is not None and now[2] - before[2] < min_window:
            time.sleep(min_window - (now[2] - before[2]))
            now = self._snapshot()
        if now is None:
            return 0.0
        self._last = now
        wall = max(now[2] - before[2], 1e-6)
        return max(0.0, (now[0] - before[0]) - (now[1] - before[1])) / wall


def auto_threads(busy_other_cores: float, cores: int | None = None) -> int:
    """All cores when the machine is ours; one fewer for each core someone else keeps busy."""
    cores = cores or os.cpu_count() or 1
    return max(1, min(cores, round(cores - busy_other_cores)))


class _FirstToken:
    """A logits processor that only notes when the first token is about to be sampled."""

    def __init__(self) -> None:
        self.at: float | None = None

    def __call__(self, input_ids: Any, scores: Any) -> Any:
        if self.at is None:
            self.at = time.perf_counter()
        return scores


class LocalProvider(BaseProvider):
    def __init__(
        self,
        *,
        name: str = "local",
        model_path: Path | str | None = None,
        threads: int = 2,
        n_ctx: int = 8192,
        prefix_cache_mb: int = 0,
        prefix_store: bool = True,
        prefix_store_mb: int = DEFAULT_LIMIT_MB,
        store_dir: Path | None = None,
        lazy_grammar: bool = True,
        capabilities: Capabilities | None = None,
    ) -> None:
        self.name = name
        self.path = Path(model_path).expanduser() if model_path else default_model_path()
        if not self.path.is_file():
            if model_path:
                raise ModelNotInstalled(
                    f"local: no model file at {self.path}; fix ARISE_MODEL_PATH / model_path"
                )
            raise ModelNotInstalled(f"local: the default model is not installed; {how_to_get()}")
        self.model = (
            DEFAULT_MODEL.key if self.path.name == DEFAULT_MODEL.filename else self.path.stem
        )
        self.threads = max(0, int(threads))  # 0 = auto
        self._watch = CpuWatch() if self.threads == 0 else None
        self.n_ctx = int(n_ctx)
        self.prefix_cache_mb = int(prefix_cache_mb)
        self.store = PrefixStore(store_dir, prefix_store_mb) if prefix_store else None
        self.lazy_grammar = bool(lazy_grammar)
        self.capabilities = capabilities or Capabilities(
            structured="json_object_schema", max_context=self.n_ctx, seed=True, local=True
        )

    def set_threads(self, threads: int) -> None:
        """Pick 1 while another CPU-heavy process (the validator) runs, 2 when idle, 0 = auto."""
        self.threads = max(0, int(threads))
        if self.threads == 0 and self._watch is None:
            self._watch = CpuWatch()

    def _threads_now(self) -> int:
        if self.threads or self._watch is None:
            return self.threads or 1
        return auto_threads(self._watch.others())

    def _prefix(self, request: Request) -> PrefixOutcome:
        """Bring the context to the state after the request's fixed prefix (lock held)."""
        keeper: PrefixKeeper = _LOADED["keeper"]
        tokens = keeper.prefix_tokens(request.messages)
        if tokens is None:
            keeper.forget_context()
            return PrefixOutcome(PrefixUse.NONE, 0, 0.0)
        return keeper.ensure(tokens, self.store)

    def warm(self, prefixes: dict[str, list[Message]]) -> dict[str, PrefixOutcome]:
        """Make sure each named prefix is in the store (``arise llm warm``)."""
        outcomes: dict[str, PrefixOutcome] = {}
        with _LOCK:
            _load(self.path, self.n_ctx, self._threads_now(), self.prefix_cache_mb)
            for name, messages in prefixes.items():
                # the prefix is every message but the last: add a placeholder last one
                request = Request.build([*messages, Message("user", "-")])
                outcomes[name] = self._prefix(request)
        return outcomes

    def send(self, request: Request) -> Completion:
        llama_cpp = _import_llama_cpp()
        threads = self._threads_now()
        with _LOCK:
            llama, load_seconds = _load(self.path, self.n_ctx, threads, self.prefix_cache_mb)
            _set_threads(llama, threads)
            _LOADED["lazy_grammar"] = self.lazy_grammar
            _LOADED.pop("lazy_sampler", None)
            llama_cpp.llama_perf_context_reset(llama.ctx)
            started = time.perf_counter()
            prefix = self._prefix(request)
            probe = _FirstToken()
            kwargs: dict[str, Any] = {
                "messages": [m.as_dict() for m in request.messages],
                "temperature": request.temperature,
                "max_tokens": request.max_tokens,
                "logits_processor": llama_cpp.LogitsProcessorList([probe]),
            }
            if request.stop:
                kwargs["stop"] = list(request.stop)
            if request.seed is not None:
                kwargs["seed"] = request.seed
            fmt = response_format(
                self.capabilities.structured, request.json_schema, request.schema_name
            )
            if fmt is not None:
                kwargs["response_format"] = fmt
            try:
                reply = llama.create_chat_completion(**kwargs)
            except ValueError as exc:
                if "context window" in str(exc):
                    raise ProviderError(
                        f"local: {exc}; shorten the prompt or raise ARISE_LLM_CTX",
                        kind=ProviderErrorKind.BAD_REQUEST,
                    ) from exc
                raise
            latency = time.perf_counter() - started
            perf = llama_cpp.llama_perf_context(llama.ctx)
            lazy = _LOADED.pop("lazy_sampler", None)
        choice = reply["choices"][0]
        usage = reply.get("usage") or {}
        details: dict[str, Any] = {
            "threads": threads,
            "prefix": prefix.use.value,
            "prefix_tokens": prefix.tokens,
            "prefix_seconds": round(prefix.seconds, 3),
            "prompt_tokens_evaluated": int(perf.n_p_eval),
            "prompt_eval_seconds": perf.t_p_eval_ms / 1000.0,
            "generated_tokens_evaluated": int(perf.n_eval),
            "generation_seconds": perf.t_eval_ms / 1000.0,
        }
        if lazy is not None:
            details["grammar_full_passes"] = lazy.full_passes
        if load_seconds:
            details["load_seconds"] = load_seconds
        return Completion(
            text=choice["message"].get("content") or "",
            usage=Usage(
                calls=1,
                prompt_tokens=int(usage.get("prompt_tokens", 0)),
                completion_tokens=int(usage.get("completion_tokens", 0)),
                seconds=latency,
                prompt_tokens_evaluated=int(perf.n_p_eval),
                prefixes_built=int(prefix.use is PrefixUse.BUILT),
                prefixes_loaded=int(prefix.use is PrefixUse.LOADED),
            ),
            model=self.model,
            latency=latency,
            provider=self.name,
            finish_reason=choice.get("finish_reason"),
            first_token_latency=(probe.at - started) if probe.at is not None else None,
            details=details,
        )
