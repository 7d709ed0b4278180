"""Which part of a chat prompt is its fixed prefix, and how the embedded model gets there.

A call's prefix is every message but the last (system prompt and few-shot examples); the
last message is the description or the error at hand. Before each call the model's
context is brought to the state right after the prefix, and only the rest of the prompt
is evaluated. That state comes from the context itself, a copy kept in memory, the disk
store, or, the first time, from evaluating the prefix alone.

The prefix is always evaluated alone, from an empty context, whether the store is on or
off: its state is then the same bytes either way, and loading it instead of computing it
cannot change an answer.
"""

from __future__ import annotations

import ctypes
import time
from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from arise.llm.prefix_store import PrefixStore, StoredPrefix, entry_key, file_sha256
from arise.llm.types import Message, PrefixUse

_RAM_ENTRIES = 6  # states kept in memory per process (~30 MB each for the 1.5B model)


@dataclass(frozen=True)
class PrefixOutcome:
    use: PrefixUse
    tokens: int
    seconds: float


def _template_formatters(llama: Any, llama_cpp: Any) -> tuple[Any, Any] | None:
    """The model's own chat template, twice; None when llama-cpp-python formats the chat
    some other way (a handler or a named format), which we cannot render apart."""
    if llama.chat_handler is not None or llama.chat_format != "chat_template.default":
        return None
    template = llama.metadata.get("tokenizer.chat_template")
    if not template:
        return None
    eos, bos = llama.token_eos(), llama.token_bos()
    eos_text = llama._model.token_get_text(eos) if eos != -1 else ""
    bos_text = llama._model.token_get_text(bos) if bos != -1 else ""
    formatter = llama_cpp.llama_chat_format.Jinja2ChatFormatter
    return (
        formatter(template, eos_text, bos_text, add_generation_prompt=False),
        formatter(template, eos_text, bos_text, add_generation_prompt=True),
    )


class PrefixKeeper:
    """Brings one loaded model to a prefix's state; one keeper per loaded model."""

    def __init__(self, llama: Any, llama_cpp: Any, model_path: str, settings: dict[str, object]):
        self.llama = llama
        self.llama_cpp = llama_cpp
        self.model_path = model_path
        self.settings = settings
        self._model_sha: str | None = None
        self._ram: OrderedDict[str, StoredPrefix] = OrderedDict()
        self._context_key: str | None = None  # the prefix the context was last built from
        # The chat template rendered without and with the generation prompt (compiled once).
        self._formatters = _template_formatters(llama, llama_cpp)

    def prefix_tokens(self, messages: Sequence[Message]) -> list[int] | None:
        """The tokens of all messages but the last, as the chat template renders them; None
        when the template is not one we can render apart or the split is not a clean
        prefix."""
        llama = self.llama
        if len(messages) < 2 or self._formatters is None:
            return None
        head, whole = self._formatters
        dicts = [m.as_dict() for m in messages]
        head_text = head(messages=dicts[:-1]).prompt
        whole_text = whole(messages=dicts).prompt
        if not whole_text.startswith(head_text):
            return None
        head_ids = list(llama.tokenize(head_text.encode("utf-8"), add_bos=False, special=True))
        whole_ids = llama.tokenize(whole_text.encode("utf-8"), add_bos=False, special=True)
        if len(head_ids) >= len(whole_ids) or list(whole_ids[: len(head_ids)]) != head_ids:
            return None
        return head_ids

    def key(self, tokens: Sequence[int], store: PrefixStore | None) -> str:
        """The store's key; without a store, one for this process's memory only (the
        model file is then not hashed)."""
        if store is None:
            return entry_key(f"path:{self.model_path}", self.settings, tokens)
        if self._model_sha is None:
            self._model_sha = file_sha256(Path(self.model_path), store.root)
        return entry_key(self._model_sha, self.settings, tokens)

    def ensure(self, tokens: list[int], store: PrefixStore | None) -> PrefixOutcome:
        started = time.perf_counter()
        key = self.key(tokens, store)
        llama = self.llama
        n = len(tokens)
        if self._context_key == key and llama.n_tokens >= n and list(llama.input_ids[:n]) == tokens:
            return PrefixOutcome(PrefixUse.IN_CONTEXT, n, time.perf_counter() - started)
        found = self._ram.get(key)
        if found is None and store is not None:
            found = store.get(key, tokens)
        if found is not None and self._restore(found):
            self._remember(found)
            self._context_key = key
            return PrefixOutcome(PrefixUse.LOADED, n, time.perf_counter() - started)
        self._context_key = None  # until the prefix is whole again
        llama.reset()
        llama.eval(tokens)
        entry = StoredPrefix(key=key, tokens=tuple(tokens), state=self._state_bytes())
        self._remember(entry)
        self._context_key = key
        use = PrefixUse.EVALUATED
        if store is not None and store.put(key, tokens, entry.state) is not None:
            use = PrefixUse.BUILT
        return PrefixOutcome(use, n, time.perf_counter() - started)

    def forget_context(self) -> None:
        """The context no longer starts from a known prefix (a call without one ran)."""
        self._context_key = None

    def _remember(self, entry: StoredPrefix) -> None:
        self._ram[entry.key] = entry
        self._ram.move_to_end(entry.key)
        while len(self._ram) > _RAM_ENTRIES:
            self._ram.popitem(last=False)

    def _state_bytes(self) -> bytes:
        ctx = self.llama.ctx
        size = int(self.llama_cpp.llama_state_get_size(ctx))
        buffer = (ctypes.c_uint8 * size)()
        written = int(self.llama_cpp.llama_state_get_data(ctx, buffer, size))
        return ctypes.string_at(buffer, min(written, size))

    def _restore(self, entry: StoredPrefix) -> bool:
        """Load the state; False (and an empty context) when llama.cpp refuses it."""
        llama = self.llama
        size = len(entry.state)
        buffer = (ctypes.c_uint8 * size).from_buffer_copy(entry.state)
        read = int(self.llama_cpp.llama_state_set_data(llama.ctx, buffer, size))
        if read != size:
            llama.reset()
            self._ram.pop(entry.key, None)
            return False
        n = len(entry.tokens)
        llama.input_ids[:n] = entry.tokens
        llama.n_tokens = n
        llama._requires_eval = True  # the logits are not from a live decode
        return True
