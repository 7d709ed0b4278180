"""Timed vertices of a trace: few where it runs straight, every bend kept within tolerance."""

from __future__ import annotations

import math
import random

from arise.present.trajectory import TOLERANCE_M, Vertex, osc_heading, simplify
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


def _gap_in_one_pass(points: list[TracePoint], vertices: list[Vertex]) -> float:
    """The farthest any step is from the exported path (both walked in time order)."""
    worst, segment = 0.0, 0
    for point in points:
        t = round(point.step * TIMESTEP, 4)
        while segment + 2 < len(vertices) and vertices[segment + 1].time < t:
            segment += 1
        a, b = vertices[segment], vertices[segment + 1]
        share = (t - a.time) / (b.time - a.time) if b.time > a.time else 0.0
        x, y = a.x + (b.x - a.x) * share, a.y + (b.y - a.y) * share
        worst = max(worst, math.hypot(x - point.x, y - point.y))
    return worst


def _one_at_a_time(points: list[TracePoint], tolerance: float) -> int:
    """How many vertices extending each segment one point at a time keeps (the old way)."""

    def deviation(first: int, last: int) -> float:
        a, b = points[first], points[last]
        worst = 0.0
        for p in points[first + 1 : last]:
            share = (p.step - a.step) / (b.step - a.step)
            x, y = a.x + (b.x - a.x) * share, a.y + (b.y - a.y) * share
            worst = max(worst, math.hypot(p.x - x, p.y - y))
        return worst

    kept, start = 1, 0
    while start < len(points) - 1:
        end = start + 1
        while end + 1 < len(points) and deviation(start, end + 1) <= tolerance:
            end += 1
        kept, start = kept + 1, end
    return kept


def _wandering(count: int, seed: int) -> list[TracePoint]:
    """A car that weaves and changes speed at random: bends everywhere, some sharp."""
    rng = random.Random(seed)
    points, x, y, heading, speed = [], 0.0, 0.0, 0.0, 8.0
    for i in range(count):
        points.append(
            TracePoint(step=i, x=round(x, 3), y=round(y, 3), heading=heading, speed=speed)
        )
        heading += rng.gauss(0, 0.02)
        speed = min(20.0, max(0.0, speed + rng.gauss(0, 0.05)))
        x += -math.sin(heading) * speed * TIMESTEP
        y += math.cos(heading) * speed * TIMESTEP
    return points


def test_no_more_vertices_than_one_point_at_a_time() -> None:
    for seed in range(3):
        points = _wandering(400, seed)
        for tolerance in (0.005, 0.02, 0.1):
            vertices = simplify(points, TIMESTEP, tolerance)
            assert len(vertices) <= _one_at_a_time(points, tolerance)
            assert _gap_in_one_pass(points, vertices) <= tolerance + 1e-9


def test_twenty_thousand_steps_straight_jagged_and_wandering() -> None:
    # A forged trace of 30,000 points took minutes when every extension of a segment
    # measured the whole segment again; the result must stay exact at the longest trace
    # the schema accepts (20,000 steps).
    count = 20_001
    assert len(simplify(straight(0, 0, 0.3, 7.0, steps=count - 1), TIMESTEP)) == 2
    zigzag = [
        TracePoint(step=i, x=float(i % 2), y=i * 0.5, heading=0.0, speed=5.0) for i in range(count)
    ]
    vertices = simplify(zigzag, TIMESTEP)
    assert len(vertices) == count and [v.x for v in vertices[:4]] == [0.0, 1.0, 0.0, 1.0]
    points = _wandering(count, seed=7)
    vertices = simplify(points, TIMESTEP)
    assert 2 < len(vertices) <= _one_at_a_time(points, TOLERANCE_M) < count // 2
    assert (vertices[0].x, vertices[-1].x) == (points[0].x, points[-1].x)
    assert _gap_in_one_pass(points, vertices) <= TOLERANCE_M + 1e-9
