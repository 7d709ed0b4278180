"""The model options shared by the commands that call a model (generate, judge, bench)."""

from __future__ import annotations

from typing import Annotated

import typer

ProviderOption = Annotated[str | None, typer.Option(help="LLM provider (see `arise llm info`).")]
ModelOption = Annotated[str | None, typer.Option(help="Model name for the provider.")]
NoCacheOption = Annotated[bool, typer.Option("--no-cache", help="Do not use the LLM cache.")]
RecordOption = Annotated[str | None, typer.Option(help="Record LLM calls to this cassette.")]
ReplayOption = Annotated[str | None, typer.Option(help="Answer LLM calls from this cassette.")]
