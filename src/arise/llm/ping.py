"""A health check of a model provider: one short prompt, never cached (`arise llm ping`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from arise.llm.types import Completion


@dataclass(frozen=True)
class Pong:
    """Which provider answered, its reply, and the models its server says it has loaded
    (for an OpenAI-compatible server; empty otherwise)."""

    provider: str
    reply: Completion
    served: list[str] = field(default_factory=list)

    def answer(self) -> str:
        """The reply on one line, at most 60 characters."""
        return " ".join(self.reply.text.split())[:60]

    def notes(self) -> list[str]:
        """How it went: the model actually loaded, load time, first token, token counts
        and generation speed, whichever the provider reported."""
        reply, usage = self.reply, self.reply.usage
        speed = ""
        generation = reply.details.get("generation_seconds")
        if generation:
            rate = reply.details.get("generated_tokens_evaluated", 0) / generation
            speed = f", {rate:.1f} tok/s generation"
        notes = []
        if self.served and reply.model not in self.served and len(self.served) <= 3:
            # llama.cpp servers echo the requested name; say what is really loaded
            notes.append(f"server has {', '.join(self.served)}")
        if "load_seconds" in reply.details:
            notes.append(f"model load {reply.details['load_seconds']:.1f} s")
        if reply.first_token_latency is not None:
            notes.append(f"first token {reply.first_token_latency:.2f} s")
        notes.append(
            f"{usage.prompt_tokens} prompt + {usage.completion_tokens} completion tokens{speed}"
        )
        return notes


def ping(
    provider: str | None = None,
    *,
    model: str | None = None,
    base_url: str | None = None,
    model_path: Path | None = None,
    threads: int | None = None,
    record: Path | None = None,
    replay: Path | None = None,
) -> Pong:
    """Send the one-word ping prompt, with a short retry: a health check answers fast."""
    from arise.llm.openai_compat import OpenAICompatProvider
    from arise.llm.registry import get_provider
    from arise.llm.retry import RetryPolicy
    from arise.llm.structured import template
    from arise.llm.types import user

    llm = get_provider(
        provider,
        cache=False,
        retry=RetryPolicy(attempts=2, base=0.5),
        record=record,
        replay=replay,
        model=model,
        base_url=base_url,
        model_path=str(model_path) if model_path else None,
        threads=threads,
    )
    with llm:
        reply = llm.complete([user(template("ping.txt").strip())], max_tokens=8)
        backend = llm.unwrap()
        served = backend.served_models() if isinstance(backend, OpenAICompatProvider) else []
    return Pong(llm.name, reply, served)
