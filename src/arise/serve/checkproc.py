"""The script-check process: where the server reads a pasted script and the worker's
result, so that no parsing of untrusted input runs in the server's own process.

A regular expression that takes minutes on a crafted script holds the interpreter lock
the whole time: in a thread it would freeze every page and `/api/health`. Here it only
holds this process, which the server kills when it does not answer in time.

The process owns no validator: when `check` wants one it asks the server (`run`), which
runs the request on its shared warm pool and sends back the worker's raw result, so the
result, too, is validated here. Messages are JSON lines (never pickles): the server
writes to stdin, this process answers on its original stdout (print() goes to stderr).

    server -> process   {"op": "check", "text", "folder", "map_dir", "timeout"}
    process -> server   {"op": "run", "request"}        (zero or more times)
    server -> process   {"op": "ran", "result"} | {"op": "died", "diagnostic", "sandbox"}
                        | {"op": "refused", "sandbox"} | {"op": "broken", "error"}
    process -> server   {"op": "done", "view"} | {"op": "failed", "error", "internal"}
"""

from __future__ import annotations

import json
import logging
import os
import sys
from enum import StrEnum
from pathlib import Path
from typing import IO, Any, cast

from arise.errors import AriseError


class Op(StrEnum):
    READY = "ready"
    CHECK = "check"
    RUN = "run"
    RAN = "ran"
    DIED = "died"
    REFUSED = "refused"
    BROKEN = "broken"
    DONE = "done"
    FAILED = "failed"


class PoolFailed(AriseError):
    """The server's pool could not run the check (a worker that could not start)."""


class Channel:
    """JSON lines in from the server, out to it."""

    def __init__(self, incoming: IO[bytes], outgoing: IO[bytes]) -> None:
        self.incoming = incoming
        self.outgoing = outgoing

    def send(self, message: dict[str, Any]) -> None:
        self.outgoing.write(json.dumps(message).encode() + b"\n")
        self.outgoing.flush()

    def receive(self) -> dict[str, Any] | None:
        line = self.incoming.readline()
        if not line:
            return None
        message = json.loads(line)
        return message if isinstance(message, dict) else None


class RemotePool:
    """Stands in for `WorkerPool` inside this process: each run is the server's."""

    def __init__(self, channel: Channel) -> None:
        self.channel = channel

    def run(self, request: dict[str, Any], timeout: float, on_stage: Any = None) -> dict[str, Any]:
        from arise.validate.pool import SandboxRequired, WorkerDied
        from arise.validate.types import Diagnostic, SandboxReport

        self.channel.send({"op": Op.RUN.value, "request": request})
        answer = self.channel.receive() or {}
        op = answer.get("op")
        if op == Op.RAN and isinstance(answer.get("result"), dict):
            return dict(answer["result"])
        if op == Op.DIED:
            death = WorkerDied(Diagnostic.model_validate(answer.get("diagnostic")))
            if answer.get("sandbox") is not None:
                death.sandbox = SandboxReport.model_validate(answer["sandbox"])
            raise death
        if op == Op.REFUSED:
            raise SandboxRequired(SandboxReport.model_validate(answer.get("sandbox")))
        raise PoolFailed(str(answer.get("error") or "the server did not run the check"))

    def close(self) -> None:
        """Nothing to close: the pool is the server's."""


def handle(channel: Channel, message: dict[str, Any]) -> dict[str, Any]:
    """One check: its view, or why it failed (one line)."""
    from arise.serve.checks import check_script
    from arise.validate import WorkerPool

    pool = cast(WorkerPool, RemotePool(channel))  # check() only calls run()
    try:
        view = check_script(
            str(message["text"]),
            Path(str(message["folder"])),
            pool,
            message.get("map_dir"),
            float(message["timeout"]),
        )
    except AriseError as error:
        return {"op": Op.FAILED.value, "error": str(error).splitlines()[0], "internal": False}
    except Exception as error:  # noqa: BLE001  (one line to the server, details to stderr)
        logging.getLogger("arise.serve").exception("the script check failed")
        return {
            "op": Op.FAILED.value,
            "error": f"internal error ({type(error).__name__}) in the script check",
            "internal": True,
        }
    return {"op": Op.DONE.value, "view": view}


def main() -> None:
    outgoing = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)  # a stray print must not break the protocol
    logging.basicConfig(level=logging.WARNING, stream=sys.stderr)
    import arise.serve.checks  # noqa: F401  (imported before `ready`, not in the first check)

    channel = Channel(sys.stdin.buffer, outgoing)
    channel.send({"op": Op.READY.value, "pid": os.getpid()})
    while (message := channel.receive()) is not None:
        if message.get("op") == Op.CHECK:
            channel.send(handle(channel, message))


if __name__ == "__main__":
    main()
