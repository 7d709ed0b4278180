"""The script-check process: where the server reads a pasted script and the worker's
result, so that no parsing of untrusted input runs in the server's own process.

A regular expression that takes minutes on a crafted script holds the interpreter lock
the whole time: in a thread it would freeze every page and `/api/health`. Here it only
holds this process, which the server kills when it does not answer in time.

The process owns no validator: when `check` wants one it asks the server (`run`), which
runs the request on its shared warm pool and sends back the worker's raw result, so the
result, too, is validated here. Messages are JSON lines (never pickles), typed in
`checkmsg`: the server writes to stdin, this process answers on its original stdout
(print() goes to stderr).

    server -> process   {"op": "check", "text", "folder", "map_dir", "timeout"}
    process -> server   {"op": "run", "request"}        (zero or more times)
    server -> process   {"op": "ran", "result"} | {"op": "died", "diagnostic", "sandbox"}
                        | {"op": "refused", "sandbox"} | {"op": "broken", "error"}
    process -> server   {"op": "done", "view"} | {"op": "failed", "error", "internal"}
"""

from __future__ import annotations

import logging
import os
import sys
from pathlib import Path
from typing import IO, Any, cast

from arise.errors import AriseError
from arise.serve.checkmsg import (
    Broken,
    Check,
    Died,
    Done,
    Failed,
    FromProcess,
    MessageError,
    Ran,
    Ready,
    Refused,
    Run,
    ToProcess,
    encode,
    to_process,
)


class PoolFailed(AriseError):
    """The server's pool could not run the check (a worker that could not start)."""


class Channel:
    """JSON lines in from the server, out to it."""

    def __init__(self, incoming: IO[bytes], outgoing: IO[bytes]) -> None:
        self.incoming = incoming
        self.outgoing = outgoing

    def send(self, message: FromProcess) -> None:
        self.outgoing.write(encode(message))
        self.outgoing.flush()

    def receive(self) -> ToProcess | None:
        """The server's next message; None when it hung up or broke the protocol."""
        line = self.incoming.readline()
        if not line:
            return None
        try:
            return to_process(line)
        except MessageError:
            return None


class RemotePool:
    """Stands in for `WorkerPool` inside this process: each run is the server's."""

    def __init__(self, channel: Channel) -> None:
        self.channel = channel

    def run(self, request: dict[str, Any], timeout: float, on_stage: Any = None) -> dict[str, Any]:
        from arise.validate.pool import SandboxRequired, WorkerDied

        self.channel.send(Run(request=request))
        match self.channel.receive():
            case Ran(result=result):
                return result
            case Died(diagnostic=diagnostic, sandbox=sandbox):
                death = WorkerDied(diagnostic)
                death.sandbox = sandbox
                raise death
            case Refused(sandbox=sandbox):
                raise SandboxRequired(sandbox)
            case Broken(error=error) if error:
                raise PoolFailed(error)
            case _:
                raise PoolFailed("the server did not run the check")

    def close(self) -> None:
        """Nothing to close: the pool is the server's."""


def handle(channel: Channel, message: Check) -> Done | Failed:
    """One check: its view, or why it failed (one line)."""
    from arise.serve.checks import check_script
    from arise.validate import WorkerPool

    pool = cast(WorkerPool, RemotePool(channel))  # check() only calls run()
    try:
        view = check_script(
            message.text,
            Path(message.folder),
            pool,
            message.map_dir,
            message.timeout,
            message.agent,
        )
    except AriseError as error:
        return Failed(error=str(error).splitlines()[0], internal=False)
    except Exception as error:  # noqa: BLE001  (one line to the server, details to stderr)
        logging.getLogger("arise.serve").exception("the script check failed")
        return Failed(
            error=f"internal error ({type(error).__name__}) in the script check", internal=True
        )
    return Done(view=view)


def main() -> None:
    outgoing = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)  # a stray print must not break the protocol
    logging.basicConfig(level=logging.WARNING, stream=sys.stderr)
    import arise.serve.checks  # noqa: F401  (imported before `ready`, not in the first check)

    channel = Channel(sys.stdin.buffer, outgoing)
    channel.send(Ready(pid=os.getpid()))
    while (message := channel.receive()) is not None:
        if isinstance(message, Check):
            channel.send(handle(channel, message))


if __name__ == "__main__":
    main()
