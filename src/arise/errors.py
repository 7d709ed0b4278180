"""The root of every exception arise raises on purpose.

A user mistake (a missing file, a bad option, an unreachable server) is an `AriseError`
with a message fit to print on one line; the command line catches this root once. Any
other exception is a bug in arise and gets a crash report instead of a traceback.
"""

from __future__ import annotations


class AriseError(Exception):
    """Something arise could not do, said in one line a user can act on."""

    #: The command line's exit code for it: 2 is a usage error (the input can be fixed);
    #: a package whose errors mean "the work failed" (e.g. the model) sets 1.
    exit_code: int = 2
    #: The word the command line prints before the message.
    label: str = "error"


class Interrupted(AriseError):
    """The user stopped a long command (Ctrl-C); the message says what was kept. Not a
    mistake, so not labelled one; exit code 130, as a shell reports SIGINT."""

    exit_code = 130
    label = "interrupted"
