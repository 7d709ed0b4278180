"""Timed vertices of a trace: few where it runs straight, every bend kept within tolerance."""

from __future__ import annotations

import math

from arise.present.trajectory import osc_heading, simplify
from arise.validate.types import TracePoint
from tests.present.traces import TIMESTEP, braking_then_turning, straight


def _interpolated_gap(points: list[TracePoint], tolerance: float) -> float:
    vertices = simplify(points, TIMESTEP, tolerance)
    worst = 0.0
    for point in points:
        t = point.step * TIMESTEP
        for a, b in zip(vertices, vertices[1:], strict=False):
            if a.time <= t <= b.time:
                share = (t - a.time) / (b.time - a.time)
                x, y = a.x + (b.x - a.x) * share, a.y + (b.y - a.y) * share
                worst = max(worst, math.hypot(x - point.x, y - point.y))
                break
    return worst


def test_constant_motion_is_two_vertices() -> None:
    vertices = simplify(straight(0, 0, 0.3, 7.0), TIMESTEP)
    assert len(vertices) == 2
    assert vertices[0].time == 0 and vertices[-1].time == 8.0


def test_a_bending_braking_path_stays_within_tolerance() -> None:
    points = braking_then_turning()
    for tolerance in (0.005, 0.02, 0.05):
        assert _interpolated_gap(points, tolerance) <= tolerance + 1e-9
    assert len(simplify(points, TIMESTEP, 0.005)) > len(simplify(points, TIMESTEP, 0.05))


def test_zero_tolerance_keeps_every_step() -> None:
    points = braking_then_turning()
    assert len(simplify(points, TIMESTEP, 0)) == len(points)


def test_standing_still_is_two_vertices_at_the_same_place() -> None:
    vertices = simplify(straight(3, 4, 0, 0.0), TIMESTEP)
    assert [(v.x, v.y) for v in vertices] == [(3, 4), (3, 4)]


def test_headings_turn_from_scenic_to_openscenario() -> None:
    assert osc_heading(0.0) == round(math.pi / 2, 4)  # Scenic's +y is OpenSCENARIO's pi/2
    assert osc_heading(-math.pi / 2) == 0.0  # facing +x
    assert osc_heading(math.pi / 2) == round(math.pi, 4) or osc_heading(math.pi / 2) == round(
        -math.pi, 4
    )
    assert str(osc_heading(-math.pi / 2)) == "0.0"  # never "-0.0" in the file


def test_an_empty_trace_has_no_vertices() -> None:
    assert simplify([], TIMESTEP) == []
