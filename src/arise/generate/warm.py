"""The prefix store of the embedded model, filled ahead of time: what `arise llm warm` does.

A first `arise generate` fills the store by itself; warming it up front suits an image,
or a benchmark that should not count the first run's extra work.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from arise.generate.prefixes import fixed_prefixes
from arise.llm.local_prefix import PrefixOutcome
from arise.llm.prefix_store import PrefixStore
from arise.llm.types import LLMError

if TYPE_CHECKING:
    from arise.llm.local import LocalProvider


@dataclass(frozen=True)
class Warmed:
    """What each fixed prefix cost and whether it was built or found; `discarded` says
    which stored entries were thrown away (corrupt, stale) and rebuilt."""

    outcomes: dict[str, PrefixOutcome]
    discarded: list[str]
    store: str


def _store(model_path: str | None) -> tuple[LocalProvider, PrefixStore]:
    """The embedded model's provider (not loaded yet) and its store; LLMError if the
    store is off or "local" is not the embedded model."""
    from arise.llm.local import LocalProvider
    from arise.llm.registry import get_provider

    backend = get_provider("local", cache=False, model_path=model_path).unwrap()
    if not isinstance(backend, LocalProvider):  # a config that redefines "local"
        raise LLMError("the prefix store is for the embedded model (kind = local)")
    if backend.store is None:
        raise LLMError("the prefix store is off (ARISE_PREFIX_STORE=off or prefix_store = false)")
    return backend, backend.store


def warm_prefixes(model_path: str | None = None) -> Warmed:
    """Evaluate the generator's fixed prompt prefixes once and keep the model's state
    after each; a prefix already stored is loaded, not evaluated."""
    backend, store = _store(model_path)
    outcomes = backend.warm(fixed_prefixes())
    return Warmed(outcomes, list(store.discarded), store.describe())


def clear_prefixes(model_path: str | None = None) -> tuple[int, Path]:
    """Delete every stored prefix; returns how many, and the store's folder."""
    _, store = _store(model_path)
    return store.clear(), store.root
