"""Command line: a thin layer; every command is one call into the library."""

from __future__ import annotations

import warnings

import typer

from arise.doctor import DOCTOR_HELP, doctor_command
from arise.evaluate.cli import BENCH_HELP, REPORT_HELP, bench_command, report_command
from arise.evaluate.judge_cli import JUDGE_HELP, judge_command
from arise.generate.cli import GENERATE_HELP, generate_command
from arise.llm.cli import app as llm_app
from arise.validate.cli import CHECK_HELP, blueprints_command, check_command, maps_app

app = typer.Typer(
    name="arise",
    help="Natural-language traffic scenarios -> executable Scenic 3 scripts, proven to run.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)
app.command("generate", help=GENERATE_HELP)(generate_command)
app.command("check", help=CHECK_HELP)(check_command)
app.command("bench", help=BENCH_HELP)(bench_command)
app.command("report", help=REPORT_HELP)(report_command)
app.command("judge", help=JUDGE_HELP)(judge_command)
app.command("blueprints")(blueprints_command)
app.command("doctor", help=DOCTOR_HELP)(doctor_command)
app.add_typer(maps_app, name="maps")
app.add_typer(llm_app, name="llm")
from arise.kb.cli import app as kb_app; app.add_typer(kb_app, name="kb")  # noqa: E402, E702, I001


def main() -> None:
    # Scenic complains when another library already owns sys.excepthook; harmless here.
    warnings.filterwarnings("ignore", message="unable to install sys.excepthook")
    app()
