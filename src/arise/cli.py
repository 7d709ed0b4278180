"""Command line: a thin layer; every command is one call into the library.

Errors are handled once, here, for every command (sub-commands included): no command
prints an error itself. An `AriseError` is printed on one line and exits with its code
(2, or 1 for a model that failed, 130 for an interrupted run); any other exception is a
bug in arise, so its traceback goes to a crash report file under the user cache and the
user is told where it is.
"""

from __future__ import annotations

import os
import platform
import shlex
import sys
import traceback
import warnings
from datetime import datetime
from pathlib import Path
from typing import Any

import typer
from typer.core import TyperGroup

from arise import __version__, terminal
from arise.doctor import DOCTOR_HELP, doctor_command
from arise.drive.cli import DRIVE_HELP, drive_command
from arise.errors import AriseError, Interrupted
from arise.evaluate.cli import BENCH_HELP, REPORT_HELP, bench_command, report_command
from arise.evaluate.judge_cli import JUDGE_HELP, judge_command
from arise.evaluate.search.cli import SEARCH_HELP, search_command
from arise.evaluate.search.critical import with_critical_search
from arise.generate.cli import GENERATE_HELP, generate_command
from arise.generate.warm_cli import WARM_HELP, warm_command
from arise.kb.cli import app as kb_app
from arise.llm.cli import app as llm_app
from arise.paths import cache_dir
from arise.present.cli import EXPORT_HELP, REPLAY_HELP, export_command, replay_command
from arise.serve.cli import SERVE_HELP, serve_command
from arise.validate.cli import CHECK_HELP, blueprints_command, check_command, maps_app

#: Exit code of a crash (a bug in arise), as BSD's EX_SOFTWARE.
CRASH_EXIT = 70

errors = terminal.console(stderr=True)


def write_crash_report(error: BaseException) -> Path:
    """Write what is needed to reproduce a crash; returns the file."""
    folder = cache_dir() / "crashes"
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"crash-{datetime.now():%Y%m%d-%H%M%S}-{os.getpid()}.txt"
    path.write_text(
        f"arise {__version__} crashed\n"
        f"command: {shlex.join(sys.argv)}\n"
        f"python: {sys.version.split()[0]} on {platform.platform()}\n\n"
        + "".join(traceback.format_exception(error)),
        encoding="utf-8",
    )
    return path


class AriseGroup(TyperGroup):
    """The root command: catches AriseError and unexpected exceptions once, for all."""

    def invoke(self, ctx: Any) -> Any:
        try:
            return super().invoke(ctx)
        except (typer.Exit, typer.Abort, typer.TyperException):  # usage errors, exits
            raise
        except AriseError as error:
            if isinstance(error, Interrupted):
                errors.print()  # past the "^C" the terminal echoed
            errors.print(terminal.text((f"{error.label}:", "red"), " ", str(error)))
            ctx.exit(error.exit_code)
        except BrokenPipeError:  # `arise ... | head` closed our output: not a crash
            _silence_stdout()
            ctx.exit(0)
        except Exception as error:  # noqa: BLE001  (a bug: report it, do not dump it)
            try:
                report = write_crash_report(error)
            except OSError:
                raise error from None
            errors.print(
                terminal.text(
                    ("arise crashed", "red"),
                    f" (a bug in arise): {type(error).__name__}: ",
                    str(error),
                    f"\nThe details are in {report}; please attach that file to a bug report.",
                )
            )
            ctx.exit(CRASH_EXIT)


def _silence_stdout() -> None:
    """Point stdout at /dev/null, so the interpreter's final flush does not fail again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):
        pass


app = typer.Typer(
    name="arise",
    cls=AriseGroup,
    help="Natural-language traffic scenarios -> executable Scenic 3 scripts, proven to run.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)
app.command("generate", help=GENERATE_HELP)(with_critical_search(generate_command))
app.command("check", help=CHECK_HELP)(check_command)
app.command("bench", help=BENCH_HELP)(bench_command)
app.command("report", help=REPORT_HELP)(report_command)
app.command("judge", help=JUDGE_HELP)(judge_command)
app.command("search", help=SEARCH_HELP)(search_command)
app.command("drive", help=DRIVE_HELP)(drive_command)
app.command("replay", help=REPLAY_HELP)(replay_command)
app.command("export", help=EXPORT_HELP)(export_command)
app.command("serve", help=SERVE_HELP)(serve_command)
app.command("blueprints")(blueprints_command)
app.command("doctor", help=DOCTOR_HELP)(doctor_command)
app.add_typer(maps_app, name="maps")
llm_app.command("warm", help=WARM_HELP)(warm_command)
app.add_typer(llm_app, name="llm")
app.add_typer(kb_app, name="kb")


def main() -> None:
    # Scenic complains when another library already owns sys.excepthook; harmless here.
    warnings.filterwarnings("ignore", message="unable to install sys.excepthook")
    from arise.validate.pool import close_on_signals

    close_on_signals()  # SIGTERM/SIGINT: workers killed at once, pools closed, no traceback
    app()
