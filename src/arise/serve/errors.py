"""What the server refuses, each with the HTTP status the page shows it under."""

from __future__ import annotations

from arise.errors import AriseError


class ServeError(AriseError):
    """A request the server cannot honour; `status` is its HTTP status code."""

    status: int = 400


class InputTooLarge(ServeError):
    """A description or a script over its size limit."""

    status = 413


class BadInput(ServeError):
    """A request whose content cannot be used (an empty script, a refused description)."""

    status = 422


class NotFound(ServeError):
    """No such run, job or file."""

    status = 404


class Conflict(ServeError):
    """The request does not fit the job's state (cancelling a finished job)."""

    status = 409


class QueueFull(ServeError):
    """Too many jobs are waiting already."""

    status = 503


class Unauthorized(ServeError):
    """A request without the server's access token."""

    status = 401


class UnsafeBinding(ServeError):
    """A non-loopback address without an access token: refused at start-up."""


class JobCancelled(ServeError):
    """Raised inside a running job, at its next progress event, when it was cancelled."""

    status = 409
