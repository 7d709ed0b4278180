"""`arise serve`: the web app on this machine."""

from __future__ import annotations

import os
import secrets
from pathlib import Path
from typing import Annotated

import typer

from arise import terminal
from arise.generate.options import GenerateOptions
from arise.llm.cli_options import ModelOption, ProviderOption, ReplayOption
from arise.serve.config import (
    DEFAULT_PORT,
    MAX_QUEUED,
    MAX_SCRIPT_BYTES,
    TOKEN_ENV,
    ServeConfig,
    default_runs_dir,
)
from arise.serve.launch import address, serve

console = terminal.console()

SERVE_HELP = f"""Open arise in a browser: describe a scenario, watch it being made, see it move.

One page on http://127.0.0.1:{DEFAULT_PORT}/ : type a description or pick an example,
choose the model, watch every stage stream in, see the replay, the script with its
sections and repairs, the spec and the conformity checks, download the files; or check a
Scenic script of your own (in the confined validator). Runs are kept in --runs-dir, so a
restart loses no finished run. The model and the validator stay warm between jobs; one
job runs per model, the others wait in its queue.

Examples:

  arise serve                                   # http://127.0.0.1:{DEFAULT_PORT}/

  arise serve --provider openai --port 9000     # another model preselected

  arise serve --host 0.0.0.0 --token "$(python -c 'import secrets; print(secrets.token_urlsafe())')"

Any address other than loopback needs an access token (--token or {TOKEN_ENV});
every request must then carry it.
"""


def serve_command(
    host: Annotated[
        str, typer.Option(help="Address to bind; anything but loopback needs --token.")
    ] = "127.0.0.1",
    port: Annotated[int, typer.Option(help="Port to listen on.", min=1, max=65535)] = DEFAULT_PORT,
    token: Annotated[
        str | None,
        typer.Option(
            help=f"Access token every request must carry (env {TOKEN_ENV}).",
            envvar=TOKEN_ENV,
            show_envvar=False,
        ),
    ] = None,
    new_token: Annotated[
        bool, typer.Option("--new-token", help="Make a random access token and print it.")
    ] = False,
    runs_dir: Annotated[
        Path | None,
        typer.Option(help="Where runs are kept (default: ARISE_RUNS_DIR or the user data folder)."),
    ] = None,
    provider: ProviderOption = None,
    model: ModelOption = None,
    replay: ReplayOption = None,
    map_dir: Annotated[str | None, typer.Option(help="Extra maps (e.g. CARLA towns).")] = None,
    max_repairs: Annotated[int, typer.Option(help="Repair budget per run.", min=0)] = 10,
    workers: Annotated[int, typer.Option(help="Confined validation workers.", min=1)] = 1,
    max_description_chars: Annotated[
        int, typer.Option(help="Longest description accepted.", min=1)
    ] = 2000,
    max_script_kb: Annotated[
        int, typer.Option(help="Largest script accepted for a check, KiB.", min=1)
    ] = MAX_SCRIPT_BYTES // 1024,
    max_queued: Annotated[int, typer.Option(help="Jobs that may wait per model.", min=1)] = (
        MAX_QUEUED
    ),
) -> None:
    if new_token and not token:
        token = secrets.token_urlsafe(24)
    if replay is not None and not Path(replay).is_file():
        raise typer.BadParameter(f"no such cassette: {replay}", param_hint="--replay")
    config = ServeConfig(  # a non-loopback host without a token is refused here
        host=host,
        port=port,
        token=token or None,
        runs_dir=runs_dir or default_runs_dir(),
        max_description_chars=max_description_chars,
        max_script_bytes=max_script_kb * 1024,
        max_queued=max_queued,
        workers=workers,
        replay=replay,
        provider=provider,
        model=model,
        options=GenerateOptions(max_repairs=max_repairs, map_dir=map_dir),
    )

    def announce() -> None:
        console.print(terminal.text("arise serve: open ", address(config)))
        console.print(terminal.text("runs are kept in ", terminal.name(config.runs_dir)))
        if os.environ.get(TOKEN_ENV) and token == os.environ[TOKEN_ENV]:
            console.print(terminal.text(f"(token from {TOKEN_ENV})"))

    serve(config, announce)  # missing web packages: ServeError, one line, exit 2
