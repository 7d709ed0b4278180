"""Ray, started the one way the bench and the drive both need it.

Both executors start Ray themselves when nothing has (and then shut it down), pass on the
ARISE_* settings to the actors, and keep the dashboard and the workers' logs out of the
user's terminal.
"""

from __future__ import annotations

import os
from typing import Any


def start_ray(ray: Any, address: str | None) -> bool:
    """Start Ray at `address` (None: a local one) unless it runs already; True when this
    call started it, so the caller knows to shut it down."""
    if ray.is_initialized():
        return False
    ray.init(
        address=address,
        include_dashboard=False,
        log_to_driver=False,
        ignore_reinit_error=True,
        runtime_env={"env_vars": {k: v for k, v in os.environ.items() if k.startswith("ARISE_")}},
    )
    return True
