"""Reaching a real CARLA server: fail in seconds with a clear message when there is none."""

from __future__ import annotations

import socket


def unreachable_reason(host: str, port: int, timeout: float = 3.0) -> str | None:
    """None if something listens at host:port, else a sentence saying what to do."""
    try:
        with socket.create_connection((host, port), timeout=timeout):
            return None
    except OSError as error:
        return (
            f"no CARLA server answers at {host}:{port} ({error.strerror or error}); "
            "start CARLA or pass --carla-host/--carla-port, or use --simulator offline"
        )
