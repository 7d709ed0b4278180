"""An agent's trace as arrays, and the geometry of its oriented box.

Velocities come from the positions (the distance between two steps over their time), not
from the recorded `speed`: a metric then depends only on where the agent went, so a
trace cannot claim a stop it did not make. Headings are Scenic's (0 faces +y, counter-
clockwise), so an agent's forward direction is (-sin h, cos h).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from arise.validate.types import AgentTrace

Floats = NDArray[np.float64]
Ints = NDArray[np.int64]


@dataclass(frozen=True)
class Track:
    """One agent's states on its own steps (sorted, one per step)."""

    name: str
    steps: Ints
    x: Floats
    y: Floats
    heading: Floats
    vx: Floats
    vy: Floats
    width: float
    length: float

    @classmethod
    def of(cls, agent: AgentTrace, timestep: float) -> Track:
        """The agent's trajectory in step order; a repeated step keeps its first point."""
        by_step: dict[int, tuple[float, float, float, float]] = {}
        for point in agent.trajectory:
            by_step.setdefault(point.step, (point.x, point.y, point.heading, point.speed))
        steps = np.array(sorted(by_step), dtype=np.int64)
        rows = np.array([by_step[int(s)] for s in steps], dtype=np.float64).reshape(-1, 4)
        x, y, heading, speed = rows.T
        vx, vy = _velocities(steps, x, y, heading, speed, timestep)
        return cls(agent.name, steps, x, y, heading, vx, vy, agent.width, agent.length)

    def __len__(self) -> int:
        return len(self.steps)

    def upto(self, last_step: int) -> Track:
        """The states at steps up to and including `last_step`."""
        keep = self.steps <= last_step
        return replace(
            self,
            steps=self.steps[keep],
            x=self.x[keep],
            y=self.y[keep],
            heading=self.heading[keep],
            vx=self.vx[keep],
            vy=self.vy[keep],
        )

    @property
    def speed(self) -> Floats:
        return np.hypot(self.vx, self.vy)

    @property
    def forward(self) -> tuple[Floats, Floats]:
        return -np.sin(self.heading), np.cos(self.heading)

    def along(self, offset: float) -> tuple[Floats, Floats]:
        """The point `offset` metres ahead of the centre along the heading (behind: < 0)."""
        fx, fy = self.forward
        return self.x + offset * fx, self.y + offset * fy

    def corners(self) -> NDArray[np.float64]:
        """The box's four corners at every step, shape (steps, 4, 2)."""
        fx, fy = self.forward
        sx, sy = fy, -fx  # the right-hand side
        hl, hw = self.length / 2, self.width / 2
        out = np.empty((len(self), 4, 2))
        for index, (along, across) in enumerate(((1, 1), (1, -1), (-1, -1), (-1, 1))):
            out[:, index, 0] = self.x + along * hl * fx + across * hw * sx
            out[:, index, 1] = self.y + along * hl * fy + across * hw * sy
        return out


def _velocities(
    steps: Ints, x: Floats, y: Floats, heading: Floats, speed: Floats, timestep: float
) -> tuple[Floats, Floats]:
    """Each step's velocity over the interval that ends there (the first step takes the
    first interval's; a single point, its recorded speed along its heading)."""
    if len(steps) < 2:
        return -np.sin(heading) * speed, np.cos(heading) * speed
    seconds = np.diff(steps).astype(np.float64) * timestep
    with np.errstate(over="ignore"):  # an absurd timestep: the metric check refuses it
        vx = np.diff(x) / seconds
        vy = np.diff(y) / seconds
    return np.concatenate(([vx[0]], vx)), np.concatenate(([vy[0]], vy))


def common_steps(a: Track, b: Track) -> tuple[Ints, Ints]:
    """Indices into `a` and `b` of the steps both have."""
    _, ia, ib = np.intersect1d(a.steps, b.steps, assume_unique=True, return_indices=True)
    return ia.astype(np.int64), ib.astype(np.int64)


def _axes(heading: Floats) -> tuple[tuple[Floats, Floats], tuple[Floats, Floats]]:
    forward = (-np.sin(heading), np.cos(heading))
    side = (np.cos(heading), np.sin(heading))
    return forward, side


def _reach(axis: tuple[Floats, Floats], half: float, ux: Floats, uy: Floats) -> Floats:
    """How far a box's half extent `half` along `axis` reaches along (ux, uy)."""
    return half * np.abs(axis[0] * ux + axis[1] * uy)


def _separation(a: Track, ia: Ints, b: Track, ib: Ints) -> list[tuple[Floats, Floats, Floats]]:
    """Per axis of the separating-axis test (each box's forward and side), the centres'
    offset along it, their relative velocity along it, and the sum of the boxes' half
    extents along it."""
    (fa, sa), (fb, sb) = _axes(a.heading[ia]), _axes(b.heading[ib])
    dx, dy = b.x[ib] - a.x[ia], b.y[ib] - a.y[ia]
    wx, wy = b.vx[ib] - a.vx[ia], b.vy[ib] - a.vy[ia]
    out = []
    for ux, uy in (fa, sa, fb, sb):
        radius = (
            _reach(fa, a.length / 2, ux, uy)
            + _reach(sa, a.width / 2, ux, uy)
            + _reach(fb, b.length / 2, ux, uy)
            + _reach(sb, b.width / 2, ux, uy)
        )
        out.append((dx * ux + dy * uy, wx * ux + wy * uy, radius))
    return out


def overlapping(a: Track, ia: Ints, b: Track, ib: Ints) -> NDArray[np.bool_]:
    """Whether the two boxes overlap (or touch) at each common step."""
    result = np.ones(len(ia), dtype=bool)
    for offset, _, radius in _separation(a, ia, b, ib):
        result &= np.abs(offset) <= radius
    return result


def contact_times(a: Track, ia: Ints, b: Track, ib: Ints) -> Floats:
    """Seconds until the boxes would first touch if both kept their velocity and heading
    from each common step on (0: touching now, inf: never). Exact for boxes: on each
    axis the overlap is an interval of time, and contact is where all four meet."""
    enter = np.zeros(len(ia))
    leave = np.full(len(ia), np.inf)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for offset, rate, radius in _separation(a, ia, b, ib):
            moving = rate != 0
            still_inside = np.abs(offset) <= radius
            t1 = (-radius - offset) / np.where(moving, rate, 1.0)
            t2 = (radius - offset) / np.where(moving, rate, 1.0)
            first = np.where(moving, np.minimum(t1, t2), np.where(still_inside, -np.inf, np.inf))
            last = np.where(moving, np.maximum(t1, t2), np.where(still_inside, np.inf, -np.inf))
            enter = np.maximum(enter, first)
            leave = np.minimum(leave, last)
    return np.where(enter <= leave, enter, np.inf)
