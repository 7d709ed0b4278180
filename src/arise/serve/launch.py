"""Starting the web app on this machine: what `arise serve` does with its config."""

from __future__ import annotations

from collections.abc import Callable

from arise.serve.config import ServeConfig
from arise.serve.errors import ServeError


def address(config: ServeConfig) -> str:
    """The page's URL, with the token when there is one (an IPv6 host in brackets)."""
    shown = f"[{config.host}]" if ":" in config.host else config.host
    return f"http://{shown}:{config.port}/" + (f"?token={config.token}" if config.token else "")


def serve(config: ServeConfig, on_ready: Callable[[], None] | None = None) -> None:
    """Serve the app behind its guard (token, host and size checks) until stopped;
    `on_ready` is called once the app is built, before it listens. ServeError, saying
    how to install them, when the web packages are missing."""
    try:
        import uvicorn

        from arise.serve.app import create_app, guarded
    except ImportError as error:
        raise ServeError(
            f"arise serve needs the web packages ({error.name} is missing): "
            "pip install 'arise[serve]' (make serve and make demo install them)"
        ) from None
    app = guarded(config, create_app(config))
    if on_ready is not None:
        on_ready()
    uvicorn.run(app, host=config.host, port=config.port, log_level="warning", access_log=False)
