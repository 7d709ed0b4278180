"""Against a real CARLA server, when one is reachable (ARISE_CARLA_HOST / ARISE_CARLA_PORT)."""

from __future__ import annotations

import os

import pytest

from arise.validate import CheckOptions, check
from arise.validate.carla_server import unreachable_reason
from tests.conftest import EXAMPLES

HOST = os.environ.get("ARISE_CARLA_HOST", "127.0.0.1")
PORT = int(os.environ.get("ARISE_CARLA_PORT", "2000"))


@pytest.mark.carla
def test_category_runs_in_real_carla() -> None:
    reason = unreachable_reason(HOST, PORT, timeout=2)
    if reason:
        pytest.skip(reason)
    result = check(
        EXAMPLES / "categories" / "straight_obstacle.scenic",
        CheckOptions(simulator="carla", carla_host=HOST, carla_port=PORT, seed=1, timeout=300),
    )
    assert result.ok, result.diagnostic
