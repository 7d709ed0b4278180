"""`arise llm ...` commands (placeholder until the providers land)."""

import typer

app = typer.Typer(help="Language model providers.", no_args_is_help=True)
