"""A real browser for the page's tests: Debian's chromium driven by Playwright (never a
browser Playwright downloads), and a real server on loopback in a thread."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager

import pytest
from benchmarks.serve_embedded import CHROMIUM, CHROMIUM_ARGS, free_port

__all__ = ["CHROMIUM", "CHROMIUM_ARGS", "free_port", "serving", "skip_without_browser"]


def skip_without_browser() -> None:
    """Skip (with the reason) where Debian's chromium or Playwright is missing."""
    if not CHROMIUM.is_file():
        pytest.skip(
            f"no chromium at {CHROMIUM}: `apt-get install chromium` (.ci/run does) "
            "or set ARISE_CHROMIUM"
        )
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        pytest.skip("playwright is not installed (the dev extra has it)")


@contextmanager
def serving(app: object, port: int) -> Iterator[str]:
    """Serve an ASGI app with uvicorn in a thread; yields its base URL."""
    import uvicorn

    server = uvicorn.Server(
        uvicorn.Config(app, host="127.0.0.1", port=port, log_level="warning")  # type: ignore[arg-type]
    )
    thread = threading.Thread(target=server.run, name="uvicorn", daemon=True)
    thread.start()
    deadline = time.monotonic() + 30
    while not server.started:
        assert thread.is_alive() and time.monotonic() < deadline, "the server did not start"
        time.sleep(0.05)
    try:
        yield f"http://127.0.0.1:{port}"
    finally:
        server.should_exit = True
        thread.join(timeout=30)
