"""Every junction geometry that states a side and a turn really gives them, on our maps.

Each one runs with the adversary on its conflict route (several seeds, since a geometry
draws one of its junction pairs at random), and the trace says where the adversary started
and which way it went.
"""

from __future__ import annotations

import math

import pytest

from arise.generate.conformity import (
    StartRelation,
    find_adversary,
    start_relation,
    travel_heading,
    wrap,
)
from arise.kb.compose import compose, pick_map
from arise.kb.loader import load_kb
from arise.kb.schema import Component
from arise.maps.registry import MapRegistry
from arise.validate import CheckOptions, WorkerPool, check_text
from arise.validate.types import AgentTrace
from arise.vocabulary import ActorClass, AdversaryManeuver, Approach

SEEDS = (1, 2, 3)
TURN_DEGREES = 45.0
# side (None: not lateral) and direction of travel seen from the ego's start
EXPECTED = {
    Approach.LEFT: ("left", "crossing"),
    Approach.RIGHT: ("right", "crossing"),
    Approach.OPPOSITE: (None, "opposite"),
}
SIDED = [e.id for e in load_kb(builtin=True).of(Component.GEOMETRY) if e.approach in EXPECTED]


def adversary_turn(adversary: AgentTrace) -> AdversaryManeuver | None:
    start = travel_heading(adversary)
    if start is None or not adversary.trajectory:
        return None
    turn = math.degrees(wrap(adversary.trajectory[-1].heading - start))
    if turn > TURN_DEGREES:
        return AdversaryManeuver.TURN_LEFT
    if turn < -TURN_DEGREES:
        return AdversaryManeuver.TURN_RIGHT
    return AdversaryManeuver.STRAIGHT


def _run(script: str, seed: int, pool: WorkerPool) -> tuple[AgentTrace, StartRelation]:
    """Validate `script` with `seed`; the adversary and where it started, seen from the ego."""
    result = check_text(script, CheckOptions(seed=seed, timeout=60), pool=pool)
    assert result.ok and result.simulation is not None, result.diagnostic
    agents = result.simulation.agents
    ego = next(a for a in agents if a.is_ego)
    adversary = find_adversary(agents)
    assert adversary is not None
    relation = start_relation(ego, adversary)
    assert relation is not None
    return adversary, relation


def test_the_one_sided_geometries_cover_left_right_and_oncoming() -> None:
    kb = load_kb(builtin=True)
    sides = {e.approach for e in kb.of(Component.GEOMETRY) if e.approach is not None}
    assert sides == set(EXPECTED)
    assert len(SIDED) >= 18


@pytest.mark.slow
@pytest.mark.parametrize("geometry_id", SIDED)
def test_a_sided_geometry_starts_its_adversary_on_that_side(
    geometry_id: str, validator_pool: WorkerPool
) -> None:
    kb = load_kb(builtin=True)
    geometry = kb.get(geometry_id)
    entries = [geometry, kb.get("spawn.junction_conflict_route"), kb.get("behavior.drive_route")]
    maps = {name: entry.features for name, entry in MapRegistry().entries.items()}
    map_name = pick_map(entries, maps)
    assert map_name is not None
    script = compose(entries, "Car", map_name)
    assert geometry.approach is not None
    side, direction = EXPECTED[geometry.approach]
    for seed in SEEDS:
        adversary, relation = _run(script, seed, validator_pool)
        where = (seed, relation.describe())
        assert relation.direction == direction, where
        assert relation.side == side if side else relation.ahead > 0, where
        assert adversary_turn(adversary) is geometry.adversary_maneuver, where


#: Kerb entries on a highway, whose far carriageway Scenic gives a group right edge on the
#: wrong side: a parked car must still stand on the ego's right, whichever way it drives.
KERB_ON_A_HIGHWAY = [
    ("spawn.parked_right_curb_ahead", "behavior.stalled"),
    ("spawn.roadside_right_near", "behavior.cross_and_stop"),
]


@pytest.mark.slow
@pytest.mark.parametrize(("spawn_id", "behavior_id"), KERB_ON_A_HIGHWAY)
def test_a_kerb_spawn_stands_on_the_right_on_either_carriageway(
    spawn_id: str, behavior_id: str, validator_pool: WorkerPool
) -> None:
    kb = load_kb(builtin=True)
    entries = [kb.get("geometry.highway_slow_lane"), kb.get(spawn_id), kb.get(behavior_id)]
    walker = ActorClass.PEDESTRIAN in kb.get(behavior_id).adversaries
    cls = ActorClass.PEDESTRIAN if walker else ActorClass.CAR
    script = compose(entries, cls, "arise_highway")
    sides = {_run(script, seed, validator_pool)[1].side for seed in (0, 1, 2, 3, 4, 5)}
    assert sides == {"right"}
