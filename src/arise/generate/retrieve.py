"""Module B: the knowledge-base entries for a spec, ranked per component and compatible.

Enums narrow the candidates (road type, ego maneuver, adversary class, what names each
entry needs, the adversary's side and turn); the spec's words rank what is left. The result
keeps the ranked lists, so the repair loop can fall back to the next candidate of a failing
section.

Side and turn filter, they never just rank: a geometry and spawn pair is graded by how well
the side it gives the adversary (`Entry.approach`; a spawn on the geometry's conflict route
takes the geometry's) and the turn (`Entry.adversary_maneuver`) fit the spec, and only pairs
of the best grade found are kept, so that a candidate swap cannot bring the wrong side back.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from enum import IntEnum

from arise.generate.spec import Actor, ScenarioSpec
from arise.kb.actors import for_actor, spawn_span
from arise.kb.loader import KnowledgeBase
from arise.kb.props import PROP_ROW_TAG, prop_row
from arise.kb.retrieval.base import Retriever
from arise.kb.schema import CONFLICT_ROUTE, Component, Entry
from arise.kb.weather import weather_choice
from arise.language.facts import FactSource
from arise.vocabulary import (
    CROSSING_STARTS,
    POINT_CLASSES,
    ActorClass,
    ActorRole,
    AdversaryManeuver,
    Approach,
    EgoManeuver,
    EgoPlan,
    RelativePosition,
    RoadType,
    StartDetail,
)

ROAD_FEATURES: dict[RoadType, tuple[str, ...]] = {
    RoadType.STRAIGHT: (),
    RoadType.INTERSECTION: ("intersection4",),
    RoadType.T_JUNCTION: ("tjunction",),
    RoadType.HIGHWAY: ("highway",),
    RoadType.MERGE: ("merge",),
}
JUNCTION_FEATURES = {"intersection4", "tjunction"}
#: A geometry whose ego changes lanes (tagged also ego_changes_left or _right).
EGO_LANE_CHANGE_TAG = "ego_lane_change"
#: A geometry whose ego comes up the on-ramp; only an ego the text puts there gets one.
EGO_ON_RAMP_TAG = "ego_on_ramp"
#: Geometry tags of what the ego does besides driving its route (`EgoPlan`).
PLAN_TAGS = frozenset(plan.value for plan in EgoPlan)
#: A geometry whose ego stands still for the whole scene; only a stopped ego gets one.
EGO_STOPPED_TAG = "ego_stopped"
#: A geometry whose ego takes any route through a junction: not for an ego said to go
#: straight, which it may turn off.
ANY_ROUTE_TAG = "any_route"
#: A walker that goes along the kerb before it turns to cross.
ALONG_FIRST_TAG = "sudden_turn"
EXIT_DETAILS = frozenset({StartDetail.EXIT_CROSSING, StartDetail.EXIT_FAR_CORNER})
#: A spawn for the other road users only (traffic on a junction's far approach): the
#: adversary's start at a junction comes with its conflict route.
TRAFFIC_ONLY_TAG = "traffic_only"
MANEUVER_TAGS: dict[EgoManeuver, tuple[str, ...]] = {
    EgoManeuver.TURN_LEFT: ("left_turn", "unprotected_left_turn"),
    EgoManeuver.TURN_RIGHT: ("right_turn",),
    EgoManeuver.CHANGE_LANE: ("lane_changing", "multilane", "cut_in"),
    EgoManeuver.GO_STRAIGHT: (
        "straight",
        "cross_traffic",
        "straight_obstacle",
        "red_light_running",
        "crossing_negotiation",
        "highway",
        "two_way",
    ),
}
SPAWN_TAGS: dict[RelativePosition, tuple[str, ...]] = {
    RelativePosition.AHEAD_SAME_LANE: ("ahead", "same_lane", "lead_vehicle"),
    RelativePosition.BEHIND_SAME_LANE: ("behind", "rear"),
    RelativePosition.ADJACENT_LANE_LEFT: ("adjacent_lane", "left"),
    RelativePosition.ADJACENT_LANE_RIGHT: ("adjacent_lane", "right"),
    RelativePosition.ONCOMING: ("oncoming", "opposite_lane", "conflict"),
    RelativePosition.ROADSIDE_RIGHT: ("roadside", "right", "parked", "sidewalk", "corner"),
    RelativePosition.ROADSIDE_LEFT: ("roadside", "left", "far_side"),
    RelativePosition.CROSSING_FROM_LEFT: ("conflict", "cross_traffic", "crossing", "left"),
    RelativePosition.CROSSING_FROM_RIGHT: ("conflict", "cross_traffic", "crossing", "right"),
}
#: Per spec position: the approaches that are that position, then the ones next best (a
#: pedestrian "crossing from the right" may start on the right pavement and walk along).
SIDE_APPROACHES: dict[RelativePosition, tuple[frozenset[Approach], frozenset[Approach]]] = {
    RelativePosition.AHEAD_SAME_LANE: (frozenset({Approach.AHEAD}), frozenset()),
    RelativePosition.BEHIND_SAME_LANE: (frozenset({Approach.BEHIND}), frozenset()),
    RelativePosition.ADJACENT_LANE_LEFT: (frozenset({Approach.ADJACENT_LEFT}), frozenset()),
    RelativePosition.ADJACENT_LANE_RIGHT: (frozenset({Approach.ADJACENT_RIGHT}), frozenset()),
    RelativePosition.ONCOMING: (frozenset({Approach.OPPOSITE}), frozenset()),
    RelativePosition.ROADSIDE_RIGHT: (
        frozenset({Approach.ROADSIDE_RIGHT, Approach.RIGHT}),
        frozenset(),
    ),
    RelativePosition.ROADSIDE_LEFT: (
        frozenset({Approach.ROADSIDE_LEFT, Approach.LEFT}),
        frozenset(),
    ),
    RelativePosition.CROSSING_FROM_LEFT: (
        frozenset({Approach.LEFT}),
        frozenset({Approach.ROADSIDE_LEFT}),
    ),
    RelativePosition.CROSSING_FROM_RIGHT: (
        frozenset({Approach.RIGHT}),
        frozenset({Approach.ROADSIDE_RIGHT}),
    ),
}
MAX_MISC = 3
#: Behavior tags of an adversary that does not move (stalled, parked as a hazard).
STATIONARY_TAGS = frozenset({"static", "stalled"})
#: Behavior tag of a road user that goes back the way it came (a walker stepping back).
TURNS_BACK_TAG = "turns_back"
#: A behavior that stands still until the ego comes near (`while (distance from ego to X) >`).
WAITS_FOR_EGO = re.compile(r"while \(distance from (?:ego to \w+|self to ego)\) >")
#: Components whose candidate lists are pools to drop from, not ranked fall-backs.
POOLED = (Component.MISC, Component.REQUIREMENTS)


@dataclass(frozen=True)
class PlacedActor:
    """One other road user of the spec placed by its own spawn and behavior, copied from
    the adversary's entries under its own names (`arise.kb.actors.for_actor`)."""

    index: int  # in spec.actors (and spec.participants)
    name: str  # the script's name for it: actor2, actor3, ...
    actor: Actor
    spawn: Entry
    behavior: Entry

    @property
    def entries(self) -> list[Entry]:
        return [self.spawn, self.behavior]


@dataclass
class Retrieval:
    """Ranked compatible candidates per component, and the first consistent choice."""

    candidates: dict[Component, list[Entry]] = field(default_factory=dict)
    chosen: dict[Component, list[Entry]] = field(default_factory=dict)
    map_name: str | None = None
    notes: list[str] = field(default_factory=list)
    actors: list[PlacedActor] = field(default_factory=list)

    def chosen_entries(self) -> list[Entry]:
        """The chosen entries in section order; the other actors' after the adversary's."""
        placed = [entry for actor in self.actors for entry in actor.entries]
        return [
            entry
            for component in Component
            for entry in [
                *self.chosen.get(component, []),
                *(e for e in placed if e.component is component),
            ]
        ]

    def keep(self, topk: int) -> None:
        """Keep the first `topk` candidates of each ranked component (the chosen entry is
        always first); misc and requirements keep their whole pools."""
        for component, entries in self.candidates.items():
            if component not in POOLED:
                self.candidates[component] = entries[: max(topk, 1)]

    def ids(self) -> dict[str, list[str]]:
        return {c.value: [e.id for e in entries] for c, entries in self.candidates.items()}


def _ranked(
    retriever: Retriever, query: str, component: Component, pool: list[Entry]
) -> list[Entry]:
    """`pool` in retrieval order (entries the retriever did not rank keep their order last)."""
    if not pool:
        return []
    wanted = {entry.id for entry in pool}
    hits = retriever.search(query, component, k=10_000)
    order = [hit.entry for hit in hits if hit.entry.id in wanted]
    seen = {entry.id for entry in order}
    return order + [entry for entry in pool if entry.id not in seen]


def _prefer(entries: list[Entry], key: Callable[[Entry], int]) -> list[Entry]:
    """Stable re-ranking: a higher key first, retrieval order within equal keys."""
    return sorted(entries, key=lambda entry: -key(entry))


class Fit(IntEnum):
    """How well a geometry and spawn pair puts the adversary where the spec says; lower is
    better, and only the best grade available is kept."""

    EXACT = 0  # the side (and the turn, when stated) the spec asks for
    NEAR = 1  # the next best side (e.g. the right pavement for "crossing from the right")
    UNSPECIFIC = 2  # the entries do not fix the side or the turn
    CONTRADICTS = 3  # another side or turn: used only when nothing else composes


def pair_approach(geometry: Entry, spawn: Entry) -> Approach | None:
    """Where this pair starts the adversary: the spawn says (on the street a turning ego
    enters: the side the geometry's ego turns to), or a spawn on the geometry's conflict
    route comes from the side the geometry states."""
    if spawn.approach is Approach.TURN_SIDE:
        tags = set(geometry.tags)
        if "right_turn" in tags:
            return Approach.ROADSIDE_RIGHT
        if tags & {"left_turn", "unprotected_left_turn"}:
            return Approach.ROADSIDE_LEFT
        return None
    if spawn.approach is not None:
        return spawn.approach
    return geometry.approach if CONFLICT_ROUTE in spawn.needs else None


def pair_maneuver(geometry: Entry, spawn: Entry) -> AdversaryManeuver | None:
    """Which way this pair's adversary route goes through the junction, if fixed."""
    if spawn.adversary_maneuver is not None:
        return spawn.adversary_maneuver
    return geometry.adversary_maneuver if CONFLICT_ROUTE in spawn.needs else None


def approach_fit(position: RelativePosition, approach: Approach | None) -> Fit:
    """Grade one approach against the spec's start position."""
    if approach is None:
        return Fit.UNSPECIFIC
    exact, near = SIDE_APPROACHES[position]
    if approach in exact:
        return Fit.EXACT
    return Fit.NEAR if approach in near else Fit.CONTRADICTS


def maneuver_fit(wanted: AdversaryManeuver, maneuver: AdversaryManeuver | None) -> Fit:
    """Grade one adversary maneuver against the spec's. An unstated one fits anything, but a
    road user whose turn the text does not mention goes straight: a route that turns is the
    next best."""
    if wanted is AdversaryManeuver.UNSTATED:
        turns = maneuver in (AdversaryManeuver.TURN_LEFT, AdversaryManeuver.TURN_RIGHT)
        return Fit.NEAR if turns else Fit.EXACT
    if maneuver is None:
        return Fit.UNSPECIFIC
    return Fit.EXACT if maneuver is wanted else Fit.CONTRADICTS


#: Spawn tags that say a start detail (`StartDetail`) of the text.
DETAIL_TAGS: dict[StartDetail, frozenset[str]] = {
    StartDetail.FROM_BEHIND: frozenset({"behind", "rear"}),
    StartDetail.AHEAD: frozenset({"ahead"}),
    StartDetail.EXIT_CROSSING: frozenset({"exit_road"}),
    StartDetail.EXIT_FAR_CORNER: frozenset({"far_corner"}),
    StartDetail.EXIT_LANE: frozenset({"exit_lane"}),
}


def _detail_tags(spec: ScenarioSpec) -> frozenset[str]:
    """The spawn tags the spec's start detail asks for; "from behind" and "ahead" only sort
    the lanes beside the ego (its own lane has positions of their own)."""
    detail = spec.start_detail
    if detail is None:
        return frozenset()
    if detail in (StartDetail.FROM_BEHIND, StartDetail.AHEAD) and spec.spawn_position not in (
        RelativePosition.ADJACENT_LANE_LEFT,
        RelativePosition.ADJACENT_LANE_RIGHT,
    ):
        return frozenset()
    return DETAIL_TAGS[detail]


def pair_fit(spec: ScenarioSpec, geometry: Entry, spawn: Entry) -> Fit:
    """The worse of the side grade and the turn grade of a geometry and spawn pair."""
    return max(
        approach_fit(spec.spawn_position, pair_approach(geometry, spawn)),
        maneuver_fit(spec.adversary_maneuver, pair_maneuver(geometry, spawn)),
    )


def turn_agrees(spec: ScenarioSpec, behavior: Entry, route: AdversaryManeuver | None) -> bool:
    """A behavior that acts out a turn needs a route known to turn that way, and a stated
    adversary maneuver it does not contradict."""
    turn = behavior.adversary_maneuver
    if turn is None:
        return True
    stated = spec.adversary_maneuver
    return turn is route and stated in (AdversaryManeuver.UNSTATED, turn)


def _fit_note(spec: ScenarioSpec, fit: Fit) -> str | None:
    """What the report says when the best pair is not an exact fit."""
    wanted = spec.spawn_position.value.replace("_", " ")
    turn = spec.adversary_maneuver
    if turn is not AdversaryManeuver.UNSTATED:
        wanted += " and " + (
            "going straight"
            if turn is AdversaryManeuver.STRAIGHT
            else turn.value.replace("_", "ing ")
        )
    if fit is Fit.NEAR:
        return f"no entry starts the adversary exactly {wanted}; kept the closest side"
    if fit is Fit.UNSPECIFIC:
        return f"no entry is specific about {wanted}; kept entries that do not fix the side"
    if fit is Fit.CONTRADICTS:
        return f"no entry puts the adversary {wanted}; its side or turn is not honoured"
    return None


def _geometry_pool(
    spec: ScenarioSpec, entries: list[Entry], placeable: Callable[[Entry], bool]
) -> tuple[list[Entry], list[str]]:
    notes: list[str] = []
    needed = set(ROAD_FEATURES[spec.road_type])

    def road_fits(entry: Entry) -> bool:
        features = set(entry.map_features)
        if "merge" in features and spec.road_type is not RoadType.MERGE:
            return False  # an on-ramp scene only where the text has one
        if spec.road_type is RoadType.STRAIGHT:
            return not features & (JUNCTION_FEATURES | {"highway"})
        return needed <= features

    straight_stated = any(
        fact.name == "ego_maneuver" and fact.source is FactSource.TEXT for fact in spec.grounding
    )

    def maneuver_fits(entry: Entry) -> bool:
        tags = set(entry.tags) | set(entry.id.split(".")[-1].split("_"))
        if spec.road_type is RoadType.MERGE and (EGO_ON_RAMP_TAG in tags) != spec.ego_on_ramp:
            return False  # the ego on the ramp only when the text puts it there
        if spec.ego_plan is EgoPlan.BYPASS and spec.ego_maneuver in (
            EgoManeuver.GO_STRAIGHT,
            EgoManeuver.CHANGE_LANE,
        ):
            return True  # a bypass reads as a lane change, or as going straight past
        turns = {"left_turn", "right_turn", "unprotected_left_turn"}
        changes = EGO_LANE_CHANGE_TAG in tags
        if spec.ego_maneuver is EgoManeuver.GO_STRAIGHT:
            # an ego that may take any route goes straight only when the text leaves it open
            any_route = ANY_ROUTE_TAG in tags and straight_stated
            return not tags & turns and not changes and not any_route
        if spec.ego_maneuver is EgoManeuver.CHANGE_LANE:
            # Only a geometry whose ego really changes lanes, to the stated side if any.
            side = spec.ego_lane_side
            return changes and (side is None or f"ego_changes_{side}" in tags)
        return bool(tags & set(MANEUVER_TAGS[spec.ego_maneuver])) and not changes

    def stop_fits(entry: Entry) -> bool:
        return (EGO_STOPPED_TAG in entry.tags) == spec.ego_stopped

    def drives(entry: Entry) -> bool:
        return EGO_STOPPED_TAG not in entry.tags

    def plan_fits(entry: Entry) -> bool:
        # An ego that stops, yields, pulls over or goes round only when the text says.
        plans = set(entry.tags) & PLAN_TAGS
        return spec.ego_plan.value in plans if spec.ego_plan else not plans

    road, maneuver = spec.road_type, spec.ego_maneuver
    placeable_entries = [e for e in entries if placeable(e) and plan_fits(e)]
    if spec.ego_plan is not None and not any(road_fits(e) for e in placeable_entries):
        notes.append(f"no geometry entry acts out {spec.ego_plan.value} on {road}; left out")
        placeable_entries = [e for e in entries if placeable(e) and not set(e.tags) & PLAN_TAGS]
    for fits, note in (
        (lambda e: road_fits(e) and maneuver_fits(e) and stop_fits(e), None),
        (
            lambda e: road_fits(e) and stop_fits(e),
            f"no geometry entry for {maneuver} on {road}; kept the road type",
        ),
        # A stopped ego on a road no stopped geometry has: keep the road, let it drive.
        (
            lambda e: road_fits(e) and maneuver_fits(e) and drives(e),
            f"no geometry entry keeps the ego stopped on {road}; it drives",
        ),
        (
            lambda e: maneuver_fits(e) and stop_fits(e),
            f"no geometry entry for {road}; kept the maneuver",
        ),
        (stop_fits, "no geometry entry matched the road type or maneuver"),
        (lambda e: True, "no geometry entry matched the road type or maneuver"),
    ):
        pool = [e for e in placeable_entries if fits(e)]
        if pool:
            if note:
                notes.append(note)
            return pool, notes
    return [], notes


@dataclass(frozen=True)
class _Core:
    """The chosen geometry, spawn and the behaviors that fit them, at one grade of fit."""

    geometry: Entry
    spawn: Entry
    behaviors: list[Entry]
    fit: Fit


def _first_core(
    spec: ScenarioSpec,
    geometries: list[Entry],
    spawns: list[Entry],
    behaviors: list[Entry],
    fit: Fit,
    fits_a_map: Callable[[list[Entry]], bool],
) -> _Core | None:
    """The first geometry, spawn and behavior in rank order that compose on a map, using
    only pairs that fit the spec at `fit` or better."""
    for geometry in geometries:
        defined = set(geometry.defines)
        for spawn in spawns:
            if not set(spawn.needs) <= defined or pair_fit(spec, geometry, spawn) > fit:
                continue
            both = defined | set(spawn.defines)
            route = pair_maneuver(geometry, spawn)
            usable = [b for b in behaviors if set(b.needs) <= both and turn_agrees(spec, b, route)]
            if route in (AdversaryManeuver.TURN_LEFT, AdversaryManeuver.TURN_RIGHT) or (
                CONFLICT_ROUTE in spawn.needs and not spec.adversary_stationary
            ):
                # A route that turns, or one laid across the ego's through a junction, is
                # only driven by a behavior that follows it: a lane follower would take any
                # turn and cross at no time set by the ego (issue 31).
                usable = [b for b in usable if "advRoute" in b.needs] or usable
            if usable and fits_a_map([geometry, spawn, usable[0]]):
                return _Core(geometry, spawn, usable, fit)
    return None


def retrieve(
    spec: ScenarioSpec,
    kb: KnowledgeBase,
    retriever: Retriever,
    maps: Mapping[str, frozenset[str]],
    description: str = "",
    pick_map: Callable[[list[Entry], Mapping[str, frozenset[str]]], str | None] | None = None,
    topk: int | None = None,
) -> Retrieval:
    """Candidates per component for `spec` (the first `topk` of each, all when None), and
    one consistent choice of entries.

    Geometry and spawn candidates that start the adversary on another side, or send it
    another way than the spec states, are left out; entries that do not say are kept only
    when no entry that does fits (`notes` says so)."""
    from arise.kb.compose import pick_map as default_pick_map

    choose_map = pick_map or default_pick_map
    adversary = spec.adversary_type.scenic_class
    result = Retrieval()

    def placeable(entry: Entry) -> bool:
        return choose_map([entry], maps) is not None

    def fits_a_map(entries: list[Entry]) -> bool:
        return choose_map(entries, maps) is not None

    def query(text: str) -> str:
        return f"{text} {text} {description}".strip()

    geometry_pool, notes = _geometry_pool(spec, kb.of(Component.GEOMETRY), placeable)
    result.notes += notes
    geometries = _ranked(
        retriever,
        query(f"{spec.geometry} {spec.ego_maneuver.value} {spec.road_type.value}"),
        Component.GEOMETRY,
        geometry_pool,
    )
    hosted = [a for a in spec.actors if _own_spawn(a, spec.spawn_position)]
    bypassed = spec.ego_plan is EgoPlan.BYPASS
    if hosted and not spec.no_adversary:
        # Among equals, the geometry where the other road users have a spawn of their own
        # (an oncoming bus needs an oncoming lane); the adversary's fit still decides first.
        spawn_pool = kb.of(Component.SPAWN)
        geometries = _prefer(
            geometries,
            lambda g: sum(
                1
                for a in hosted
                if _actor_spawns(a, _actor_start(a, bypassed), spawn_pool, g, set(), False)
            ),
        )
    if spec.no_adversary:
        return _scene_without_adversary(
            spec, kb, retriever, maps, choose_map, result, geometries, query, topk
        )
    spawn_tags = set(SPAWN_TAGS[spec.spawn_position])
    detail_tags = _detail_tags(spec)
    spawns = _prefer(
        _ranked(
            retriever,
            query(f"{spec.spawn} {spec.spawn_position.value}"),
            Component.SPAWN,
            [
                e
                for e in kb.of(Component.SPAWN)
                if e.suits(adversary) and placeable(e) and TRAFFIC_ONLY_TAG not in e.tags
            ],
        ),
        lambda e: len(spawn_tags & set(e.tags)) + (10 if detail_tags & set(e.tags) else 0),
    )
    behaviors = _ranked(
        retriever,
        query(spec.behavior),
        Component.BEHAVIOR,
        [e for e in kb.of(Component.BEHAVIOR) if e.suits(adversary)],
    )
    if spec.ego_stopped:
        # An ego that never moves never comes near: a behavior that waits for it would too.
        moving = [e for e in behaviors if not WAITS_FOR_EGO.search(e.snippet)]
        behaviors = moving or behaviors
    if spec.spawn_position in CROSSING_STARTS or spec.start_detail in EXIT_DETAILS:
        # Said to cross from a side or a corner: it crosses from the start, it does not walk
        # along the kerb first (the trace would read it going the ego's way).
        behaviors = _prefer(behaviors, lambda e: -int(ALONG_FIRST_TAG in e.tags))
    # Going back the way it came only where the text says so: a walker who steps out and
    # is read as stepping back looks, in the trace, like one who turned round.
    if spec.adversary_turns_back:
        behaviors = _prefer(behaviors, lambda e: int(TURNS_BACK_TAG in e.tags))
    elif not all(TURNS_BACK_TAG in e.tags for e in behaviors):
        behaviors = [e for e in behaviors if TURNS_BACK_TAG not in e.tags]
    pools = [behaviors]
    if spec.adversary_stationary:
        # Parked, stalled or stopped in the text: a behavior that stays put, if one fits.
        pools.insert(0, [e for e in behaviors if set(e.tags) & STATIONARY_TAGS])
    core = next(
        (
            found
            for pool in pools
            for fit in Fit
            if (found := _first_core(spec, geometries, spawns, pool, fit, fits_a_map))
        ),
        None,
    )
    if (
        core is not None
        and spec.adversary_stationary
        and not set(core.behaviors[0].tags) & STATIONARY_TAGS
    ):
        result.notes.append("no behavior that stays put fits; the adversary moves")
    if core is None:
        result.notes.append(f"no compatible geometry/spawn/behavior for a {adversary}")
        return result
    note = _fit_note(spec, core.fit)
    if note:
        result.notes.append(note)
    geometry, spawn = core.geometry, core.spawn
    defined = set(geometry.defines)
    pair_spawns = [
        s for s in spawns if set(s.needs) <= defined and pair_fit(spec, geometry, s) <= core.fit
    ]
    result.candidates[Component.GEOMETRY] = [geometry] + [
        g for g in geometries if g is not geometry and pair_fit(spec, g, spawn) <= core.fit
    ]
    result.candidates[Component.SPAWN] = pair_spawns[pair_spawns.index(spawn) :]
    result.candidates[Component.BEHAVIOR] = core.behaviors
    result.chosen = {
        Component.GEOMETRY: [geometry],
        Component.SPAWN: [spawn],
        Component.BEHAVIOR: [core.behaviors[0]],
    }
    result.actors = place_actors(spec, kb, retriever, maps, choose_map, result, geometry, query)
    _add_extras(
        spec,
        kb,
        retriever,
        maps,
        choose_map,
        result,
        defined
        | set(spawn.defines)
        | set(core.behaviors[0].defines)
        | {name for placed in result.actors for e in placed.entries for name in e.defines},
        query,
        placed={placed.index for placed in result.actors},
    )
    result.map_name = choose_map(result.chosen_entries(), maps)
    if topk is not None:
        result.keep(topk)
    return result


def _scene_without_adversary(
    spec: ScenarioSpec,
    kb: KnowledgeBase,
    retriever: Retriever,
    maps: Mapping[str, frozenset[str]],
    choose_map: Callable[[list[Entry], Mapping[str, frozenset[str]]], str | None],
    result: Retrieval,
    geometries: list[Entry],
    query: Callable[[str], str],
    topk: int | None,
) -> Retrieval:
    """The text names no road user that causes the danger (debris, cones, a slippery road):
    a geometry, the named objects and the weather; no spawn, no behavior."""
    if not geometries:
        result.notes.append("no geometry entry fits")
        return result
    geometry = geometries[0]
    result.candidates[Component.GEOMETRY] = geometries
    result.chosen = {Component.GEOMETRY: [geometry]}
    result.notes.append("the description names no adversary: the scene has none")
    _add_extras(spec, kb, retriever, maps, choose_map, result, set(geometry.defines), query)
    result.chosen[Component.REQUIREMENTS] = []  # requirements are about an adversary
    result.map_name = choose_map(result.chosen_entries(), maps)
    if topk is not None:
        result.keep(topk)
    return result


_NEW_OBJECT = re.compile(r"\bnew (\w+)")


def _created(entry: Entry) -> list[str]:
    """The class of each road user and prop an entry's snippet creates, once per object."""
    return [name for name in _NEW_OBJECT.findall(entry.snippet) if name not in POINT_CLASSES]


def _created_classes(entry: Entry) -> frozenset[str]:
    """The classes of road users and props an entry's snippet creates."""
    return frozenset(_created(entry))


def _misc_fit(actor: Actor) -> Callable[[Entry], int]:
    """How well a misc entry suits the actor beyond its words: where the text puts it (in
    the lane a turning ego enters), an occluder entry for an occluder, and as many objects
    as the text counts (one parked car is not a row of three; "several cars" are)."""

    detail = _actor_detail_tags(actor)

    def fit(entry: Entry) -> int:
        made = len(_created(entry))
        count = 2 * (made == actor.count or (actor.count > 1 and made > 1))
        occluder = actor.role is ActorRole.OCCLUDER and "occluder" in entry.tags
        return count + occluder + 3 * bool(detail & set(entry.tags))

    return fit


#: The kerb beside a lane: a bus "occupying the right lane" at its stop, which no spawn of
#: the geometry can put in that lane, stands at the right kerb rather than nowhere.
KERB_OF_LANE = {
    RelativePosition.ADJACENT_LANE_RIGHT: Approach.ROADSIDE_RIGHT,
    RelativePosition.ADJACENT_LANE_LEFT: Approach.ROADSIDE_LEFT,
}


def _misc_side_fits(start: RelativePosition | None, approach: Approach | None) -> bool:
    """Whether a misc entry puts an actor said to start at `start` on its side of the road."""
    if start is None or approach_fit(start, approach) <= Fit.UNSPECIFIC:
        return True
    return approach is not None and approach is KERB_OF_LANE.get(start)


#: Where a row of props stands for each start the text gives it: the row entry and its
#: parameters (the lane to the left is a row 3.5 m left of the ego's lane).
PROP_ROW_PLACES: dict[RelativePosition | None, tuple[str, dict[str, str]]] = {
    None: ("misc.prop_row_in_lane_ahead", {}),
    RelativePosition.AHEAD_SAME_LANE: ("misc.prop_row_in_lane_ahead", {}),
    RelativePosition.ADJACENT_LANE_LEFT: (
        "misc.prop_row_in_lane_ahead",
        {"OPT_MISC_ROW_LATERAL": "-3.5"},
    ),
    RelativePosition.ROADSIDE_LEFT: (
        "misc.prop_row_in_lane_ahead",
        {"OPT_MISC_ROW_LATERAL": "-3.5"},
    ),
    RelativePosition.ONCOMING: ("misc.prop_row_in_lane_ahead", {"OPT_MISC_ROW_LATERAL": "-3.5"}),
    RelativePosition.ADJACENT_LANE_RIGHT: ("misc.prop_row_right_roadside", {}),
    RelativePosition.ROADSIDE_RIGHT: ("misc.prop_row_right_roadside", {}),
}


def _prop_row(actor: Actor, index: int, rows: list[Entry]) -> list[Entry]:
    """A row of the actor's props in its number, where its start puts it (none for a road
    user, or a start no row stands at)."""
    if actor.scenic_class.is_road_user or actor.start not in PROP_ROW_PLACES:
        return []
    entry_id, settings = PROP_ROW_PLACES[actor.start]
    entry = next((e for e in rows if e.id == entry_id), None)
    if entry is None:
        return []
    return [prop_row(entry, actor.scenic_class, actor.count, f"P{index + 1}", settings)]


def _add_extras(
    spec: ScenarioSpec,
    kb: KnowledgeBase,
    retriever: Retriever,
    maps: Mapping[str, frozenset[str]],
    choose_map: Callable[[list[Entry], Mapping[str, frozenset[str]]], str | None],
    result: Retrieval,
    defined: set[str],
    query: Callable[[str], str],
    placed: set[int] | None = None,
) -> None:
    """Weather, other participants and requirements that fit the chosen core; a
    participant already `placed` as an actor of its own (by index) gets no misc entry."""
    weathers = kb.of(Component.WEATHER)
    if spec.weather_parameters is not None:  # fog, dusk, glare: no preset says it all
        weathers = [weather_choice(spec.weather_parameters, weathers)]
    exact = [e for e in weathers if f"'{spec.weather}'" in e.snippet]
    ranked = exact or _ranked(retriever, spec.weather, Component.WEATHER, weathers)
    if ranked:
        result.candidates[Component.WEATHER] = ranked
        result.chosen[Component.WEATHER] = [ranked[0]]

    def fits(entry: Entry) -> bool:
        return (
            set(entry.needs) <= defined
            and entry.suits(spec.adversary_type.scenic_class)
            and choose_map([*result.chosen_entries(), entry], maps) is not None
        )

    misc_pool = [e for e in kb.of(Component.MISC) if fits(e)]
    chosen_misc: list[Entry] = []
    unplaced = [
        (i, spec.participants[i], actor)
        for i, actor in enumerate(spec.actors[: len(spec.participants)])
        if i not in (placed or set())
    ]
    rows = [e for e in misc_pool if PROP_ROW_TAG in e.tags]
    for index, participant, actor in unplaced[:MAX_MISC]:
        # Only an entry that places the class the cast gave this participant: a bus stop
        # is a prop, not a bus; nothing is added for a thing no entry places.
        named = {actor.scenic_class}
        same_kind = [
            e
            for e in misc_pool
            if PROP_ROW_TAG not in e.tags
            and _created_classes(e)
            and _created_classes(e) <= named
            # nor one that puts it where the text does not: an oncoming cyclist is no
            # cyclist riding ahead
            and _misc_side_fits(actor.start, e.approach)
        ]
        ranked = _ranked(retriever, participant, Component.MISC, same_kind)
        picked = _prefer(ranked, _misc_fit(actor))[:1]
        if not picked or (actor.count_stated and len(_created(picked[0])) != actor.count):
            # a prop no entry places (or not in the number the text says): a row of its own
            picked = _prop_row(actor, index, rows) or picked
        if not picked:
            result.notes.append(f"misc: no entry places {participant!r}; left out")
        for entry in picked:
            if entry not in chosen_misc and not set(entry.defines) & defined:
                chosen_misc.append(entry)
                defined |= set(entry.defines)
    result.candidates[Component.MISC] = misc_pool
    result.chosen[Component.MISC] = chosen_misc

    requirement_pool = [e for e in kb.of(Component.REQUIREMENTS) if fits(e)]
    chosen_requirements: list[Entry] = []
    for requirement in spec.requirements:
        text = f"{requirement.kind.value.replace('_', ' ')} {requirement.text}"
        for entry in _ranked(retriever, text, Component.REQUIREMENTS, requirement_pool)[:1]:
            if entry not in chosen_requirements:
                chosen_requirements.append(entry)
    result.candidates[Component.REQUIREMENTS] = requirement_pool
    result.chosen[Component.REQUIREMENTS] = chosen_requirements


# -- the other actors -----------------------------------------------------------------------

#: At most this many other actors get a spawn of their own (copies of a count included).
MAX_ACTORS = 4
#: Roles whose actor is placed by a misc entry, not a spawn: an occluder stands by the
#: adversary, an obstacle is a prop.
MISC_ROLES = frozenset({ActorRole.OCCLUDER, ActorRole.OBSTACLE})
#: Starts on the carriageway. An occluder the text puts there is traffic (a bus coming the
#: other way, a truck in the next lane) and is placed like any road user; a misc occluder
#: stands parked at the kerb, which is not where the text put it.
ON_ROAD_STARTS = frozenset(
    {
        RelativePosition.AHEAD_SAME_LANE,
        RelativePosition.BEHIND_SAME_LANE,
        RelativePosition.ADJACENT_LANE_LEFT,
        RelativePosition.ADJACENT_LANE_RIGHT,
        RelativePosition.ONCOMING,
    }
)
#: Where an actor starts when its words do not say, by its role.
ROLE_STARTS: dict[ActorRole, RelativePosition] = {
    ActorRole.LEAD: RelativePosition.AHEAD_SAME_LANE,
    ActorRole.SLOW: RelativePosition.AHEAD_SAME_LANE,
    ActorRole.STOPPED: RelativePosition.AHEAD_SAME_LANE,
    ActorRole.PARKED: RelativePosition.ROADSIDE_RIGHT,
    ActorRole.ONCOMING: RelativePosition.ONCOMING,
    ActorRole.FOLLOWING: RelativePosition.BEHIND_SAME_LANE,
    ActorRole.CROSSING: RelativePosition.ROADSIDE_RIGHT,
}
#: Behavior tags preferred for an actor of each role (it keeps to its lane or route).
ROLE_BEHAVIOR_TAGS: dict[ActorRole, frozenset[str]] = {
    ActorRole.SLOW: frozenset({"slow_vehicle"}),
    ActorRole.CROSSING: frozenset({"crossing"}),
}
STEADY_TAGS = frozenset({"steady", "cruise", "route"})
#: Rough length of each class (metres): copies of a counted actor stand this far apart,
#: plus a margin.
CLASS_LENGTHS = {
    ActorClass.BUS: 12.0,
    ActorClass.TRUCK: 9.0,
    ActorClass.VAN: 6.0,
    ActorClass.CAR: 5.0,
    ActorClass.MOTORCYCLE: 2.5,
}
COPY_MARGIN = 3.0


#: Where a parked vehicle said to be in a lane stands: at the kerb on that side ("parked
#: in the lane ahead" at the near kerb, "parked on the right, partly in the lane" at the
#: right kerb), since no spawn parks a car in a lane of traffic.
PARKED_AT_KERB = {
    RelativePosition.AHEAD_SAME_LANE: RelativePosition.ROADSIDE_RIGHT,
    RelativePosition.ADJACENT_LANE_RIGHT: RelativePosition.ROADSIDE_RIGHT,
    RelativePosition.ADJACENT_LANE_LEFT: RelativePosition.ROADSIDE_LEFT,
}


def _actor_detail_tags(actor: Actor) -> frozenset[str]:
    """The entry tags the actor's start detail asks for (none without one)."""
    return DETAIL_TAGS[actor.start_detail] if actor.start_detail else frozenset()


def _actor_start(actor: Actor, bypassed: bool = False) -> RelativePosition | None:
    """Where to place the actor: its start, else its role's; a parked vehicle said to be
    in a lane is at that side's kerb (`PARKED_AT_KERB`), but one on the street a turning
    ego enters stays there (the exit lane's spawn), and so does one ahead that the ego
    goes round through the oncoming lane (`bypassed`): at the kerb, it would block nothing."""
    if (
        actor.role is ActorRole.PARKED
        and actor.start in PARKED_AT_KERB
        and actor.start_detail is not StartDetail.EXIT_LANE
        and not (bypassed and actor.start is RelativePosition.AHEAD_SAME_LANE)
    ):
        return PARKED_AT_KERB[actor.start]
    return actor.start or ROLE_STARTS.get(actor.role)


#: The side of the road each start is on, seen from the ego (the lane ahead is taken as
#: the kerb side).
ROAD_SIDE_OF_START: dict[RelativePosition, str] = {
    RelativePosition.ROADSIDE_RIGHT: "right",
    RelativePosition.CROSSING_FROM_RIGHT: "right",
    RelativePosition.ADJACENT_LANE_RIGHT: "right",
    RelativePosition.AHEAD_SAME_LANE: "right",
    RelativePosition.ROADSIDE_LEFT: "left",
    RelativePosition.CROSSING_FROM_LEFT: "left",
    RelativePosition.ADJACENT_LANE_LEFT: "left",
    RelativePosition.ONCOMING: "left",
}


def _across_from_adversary(actor: Actor, adversary: RelativePosition | None) -> bool:
    """Whether the text puts the actor on the other side of the road from the adversary:
    then a misc occluder, which stands by the adversary, would stand where the text does
    not put it (a van parked at the right kerb is not beside a cyclist coming the other
    way)."""
    if actor.start is None or adversary is None:
        return False
    mine, theirs = ROAD_SIDE_OF_START.get(actor.start), ROAD_SIDE_OF_START.get(adversary)
    return mine is not None and theirs is not None and mine != theirs


def _own_spawn(actor: Actor, adversary: RelativePosition | None) -> bool:
    """Whether the actor is a road user placed by a spawn of its own (not a misc entry;
    the others of a counted adversary take copies of the adversary's). An occluder is a
    misc entry by the `adversary`'s start, unless the text puts it on the road or across
    from the adversary."""
    by_misc = actor.role in MISC_ROLES and not (
        actor.role is ActorRole.OCCLUDER
        and (actor.start in ON_ROAD_STARTS or _across_from_adversary(actor, adversary))
    )
    return (
        actor.road_user
        and not by_misc
        and actor.role is not ActorRole.ADVERSARY
        and _actor_start(actor) is not None
    )


def _actor_spawns(
    actor: Actor,
    start: RelativePosition | None,
    spawns: list[Entry],
    geometry: Entry,
    used: set[str],
    conflict_taken: bool,
) -> list[Entry]:
    """The spawns that can place `actor`, starting at `start` (`_actor_start`), on this
    geometry, on its side or the next best."""
    if start is None:
        return []
    cls = actor.scenic_class.as_adversary
    defined = set(geometry.defines)
    return [
        e
        for e in spawns
        if e.suits(cls)
        and e.id not in used
        and set(e.needs) <= defined
        and not (conflict_taken and CONFLICT_ROUTE in e.needs)
        and approach_fit(start, pair_approach(geometry, e)) <= Fit.NEAR
    ]


def place_actors(
    spec: ScenarioSpec,
    kb: KnowledgeBase,
    retriever: Retriever,
    maps: Mapping[str, frozenset[str]],
    choose_map: Callable[[list[Entry], Mapping[str, frozenset[str]]], str | None],
    result: Retrieval,
    geometry: Entry,
    query: Callable[[str], str],
) -> list[PlacedActor]:
    """A spawn and a behavior of its own for each other road user of the spec (its
    `count` of them, in a row), copied under names that do not collide.

    The spawn must put the actor on the side the spec gives it (or the next best side);
    it is never a spawn another actor already uses, nor the adversary's junction route
    when the adversary is on it. A stopped or parked actor gets a behavior that stays put,
    any other one that keeps to its lane or route. An actor no spawn fits is left to the
    misc entries, with a note."""
    placed: list[PlacedActor] = []
    bypassed = spec.ego_plan is EgoPlan.BYPASS
    used = {e.id for e in result.chosen.get(Component.SPAWN, [])}
    conflict_taken = any(CONFLICT_ROUTE in e.needs for e in result.chosen.get(Component.SPAWN, []))

    def fits_a_map(entries: list[Entry]) -> bool:
        so_far = [*result.chosen_entries(), *(e for p in placed for e in p.entries)]
        return choose_map([*so_far, *entries], maps) is not None

    for index, actor in enumerate(spec.actors):
        if actor.role is ActorRole.ADVERSARY:
            placed += _adversary_copies(index, actor, result, len(placed))
            continue
        if not _own_spawn(actor, spec.spawn_position):
            continue
        room = MAX_ACTORS - len(placed)
        if room <= 0:
            result.notes.append(f"actors: only {MAX_ACTORS} placed; {actor.quote!r} left out")
            break
        start = _actor_start(actor, bypassed)
        if start is None:
            continue
        words = spec.participants[index] if index < len(spec.participants) else actor.quote
        pair = _actor_entries(
            actor,
            start,
            words,
            kb,
            retriever,
            geometry,
            query,
            used,
            conflict_taken,
            fits_a_map,
        )
        if pair is None:
            result.notes.append(
                f"actors: no spawn and behavior place {actor.quote!r} "
                f"{start.value.replace('_', ' ')}; left to the misc entries"
            )
            continue
        spawn, behavior = pair
        used.add(spawn.id)
        conflict_taken |= CONFLICT_ROUTE in spawn.needs
        count = min(actor.count, room)
        if count < actor.count:
            result.notes.append(f"actors: placed {count} of the {actor.count} {actor.quote!r}")
        placed += _copies(index, actor, spawn, behavior, len(placed) + 2, range(count))
    return placed


def _copies(
    index: int, actor: Actor, spawn: Entry, behavior: Entry, first_number: int, copies: range
) -> list[PlacedActor]:
    """`actor`'s spawn and behavior copied under the names actor<first_number>, ...; copy k
    is spaced k rows out along its spawn (copy 0 stands where the spawn puts it)."""
    spacing = spawn_span(spawn) + CLASS_LENGTHS.get(actor.scenic_class, 2.0) + COPY_MARGIN
    placed = []
    for number, copy in enumerate(copies, start=first_number):
        name = f"actor{number}"
        placed.append(
            PlacedActor(
                index=index,
                name=name,
                actor=actor,
                spawn=for_actor(spawn, name, actor.scenic_class, copy=copy, spacing=spacing),
                behavior=for_actor(behavior, name, actor.scenic_class),
            )
        )
    return placed


def _adversary_copies(
    index: int, actor: Actor, result: Retrieval, placed_so_far: int
) -> list[PlacedActor]:
    """The others of a counted adversary ("two pedestrians cross"): the adversary's own
    spawn and behavior, copied under their own names and spaced out beyond it."""
    spawns = result.chosen.get(Component.SPAWN, [])
    behaviors = result.chosen.get(Component.BEHAVIOR, [])
    if not spawns or not behaviors:
        return []
    spawn, behavior = spawns[0], behaviors[0]
    count = min(actor.count, MAX_ACTORS - placed_so_far)
    if count < actor.count:
        result.notes.append(f"actors: placed {count} more of {actor.quote!r}, not {actor.count}")
    return _copies(index, actor, spawn, behavior, placed_so_far + 2, range(1, count + 1))


def _actor_entries(
    actor: Actor,
    start: RelativePosition,
    words: str,
    kb: KnowledgeBase,
    retriever: Retriever,
    geometry: Entry,
    query: Callable[[str], str],
    used: set[str],
    conflict_taken: bool,
    fits_a_map: Callable[[list[Entry]], bool],
) -> tuple[Entry, Entry] | None:
    """The best spawn and behavior (as written, not yet copied) for one actor."""
    cls = actor.scenic_class.as_adversary
    defined = set(geometry.defines)

    def side(spawn: Entry) -> Fit:
        return approach_fit(start, pair_approach(geometry, spawn))

    spawns = _actor_spawns(actor, start, kb.of(Component.SPAWN), geometry, used, conflict_taken)
    tags = set(SPAWN_TAGS[start])
    # "stopped in the exit lane" of a turning ego: the exit lane's spawn, where one fits.
    detail = _actor_detail_tags(actor)
    spawns = _prefer(
        _prefer(
            _ranked(retriever, query(f"{words} {start.value}"), Component.SPAWN, spawns),
            lambda e: len(tags & set(e.tags)) + 10 * bool(detail & set(e.tags)),
        ),
        lambda e: -side(e),
    )
    still = actor.stationary or actor.role in (ActorRole.STOPPED, ActorRole.PARKED)
    wanted = STATIONARY_TAGS if still else ROLE_BEHAVIOR_TAGS.get(actor.role, STEADY_TAGS)
    behaviors = [
        e
        for e in kb.of(Component.BEHAVIOR)
        if e.suits(cls)
        and e.adversary_maneuver is None
        and (not still or set(e.tags) & STATIONARY_TAGS)
    ]
    behaviors = _prefer(
        _ranked(retriever, query(words), Component.BEHAVIOR, behaviors),
        lambda e: (
            10 * len(wanted & set(e.tags))
            + len(STEADY_TAGS & set(e.tags))
            - 20 * int(ALONG_FIRST_TAG in e.tags and actor.role is ActorRole.CROSSING)
        ),
    )
    for spawn in spawns:
        both = defined | set(spawn.defines)
        for behavior in behaviors:
            if set(behavior.needs) <= both and fits_a_map([spawn, behavior]):
                return spawn, behavior
    return None
