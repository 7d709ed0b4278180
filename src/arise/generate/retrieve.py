"""Module B: the knowledge-base entries for a spec, ranked per component and compatible.

Enums narrow the candidates (road type, ego maneuver, adversary class, what names each
entry needs); the spec's words rank what is left. The result keeps the ranked lists, so
the repair loop can fall back to the next candidate of a failing section.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from arise.generate.spec import ScenarioSpec
from arise.kb.loader import KnowledgeBase
from arise.kb.retrieval.base import Retriever
from arise.kb.schema import Component, Entry
from arise.vocabulary import EgoManeuver, RelativePosition, RoadType

ROAD_FEATURES: dict[RoadType, tuple[str, ...]] = {
    RoadType.STRAIGHT: (),
    RoadType.INTERSECTION: ("intersection4",),
    RoadType.T_JUNCTION: ("tjunction",),
    RoadType.HIGHWAY: ("highway",),
}
JUNCTION_FEATURES = {"intersection4", "tjunction"}
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
MAX_MISC = 3
#: Components whose candidate lists are pools to drop from, not ranked fall-backs.
POOLED = (Component.MISC, Component.REQUIREMENTS)


@dataclass
class Retrieval:
    """Ranked compatible candidates per component, and the first consistent choice."""

    candidates: dict[Component, list[Entry]] = field(default_factory=dict)
    chosen: dict[Component, list[Entry]] = field(default_factory=dict)
    map_name: str | None = None
    notes: list[str] = field(default_factory=list)

    def chosen_entries(self) -> list[Entry]:
        return [entry for component in Component for entry in self.chosen.get(component, [])]

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


def _route_agrees(behavior: Entry, geometry: Entry) -> bool:
    """A turning behavior follows the geometry's adversary route: only its own geometries
    give that route the turn its name promises."""
    return "turning_across" not in behavior.tags or geometry.id in behavior.companions


def _geometry_pool(
    spec: ScenarioSpec, entries: list[Entry], placeable: Callable[[Entry], bool]
) -> tuple[list[Entry], list[str]]:
    notes: list[str] = []
    needed = set(ROAD_FEATURES[spec.road_type])

    def road_fits(entry: Entry) -> bool:
        features = set(entry.map_features)
        if spec.road_type is RoadType.STRAIGHT:
            return not features & (JUNCTION_FEATURES | {"highway"})
        return needed <= features

    def maneuver_fits(entry: Entry) -> bool:
        tags = set(entry.tags) | set(entry.id.split(".")[-1].split("_"))
        turns = {"left_turn", "right_turn", "unprotected_left_turn"}
        if spec.ego_maneuver is EgoManeuver.GO_STRAIGHT:
            return not tags & turns
        return bool(tags & set(MANEUVER_TAGS[spec.ego_maneuver]))

    placeable_entries = [e for e in entries if placeable(e)]
    for fits, note in (
        (lambda e: road_fits(e) and maneuver_fits(e), None),
        (
            road_fits,
            f"no geometry entry for {spec.ego_maneuver} on {spec.road_type}; kept the road type",
        ),
        (maneuver_fits, f"no geometry entry for {spec.road_type}; kept the maneuver"),
        (lambda e: True, "no geometry entry matched the road type or maneuver"),
    ):
        pool = [e for e in placeable_entries if fits(e)]
        if pool:
            if note:
                notes.append(note)
            return pool, notes
    return [], notes


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
    one consistent choice of entries."""
    from arise.kb.compose import pick_map as default_pick_map

    choose_map = pick_map or default_pick_map
    adversary = spec.adversary_type.scenic_class
    result = Retrieval()

    def placeable(entry: Entry) -> bool:
        return choose_map([entry], maps) is not None

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
    spawn_tags = set(SPAWN_TAGS[spec.spawn_position])
    for geometry in geometries:
        defined = set(geometry.defines)
        spawns = [
            e
            for e in kb.of(Component.SPAWN)
            if e.suits(adversary) and set(e.needs) <= defined and placeable(e)
        ]
        spawns = _prefer(
            _ranked(
                retriever,
                query(f"{spec.spawn} {spec.spawn_position.value}"),
                Component.SPAWN,
                spawns,
            ),
            lambda e: len(spawn_tags & set(e.tags)),
        )
        for spawn in spawns:
            both = defined | set(spawn.defines)
            behaviors = [
                e
                for e in kb.of(Component.BEHAVIOR)
                if e.suits(adversary) and set(e.needs) <= both and _route_agrees(e, geometry)
            ]
            behaviors = _ranked(retriever, query(spec.behavior), Component.BEHAVIOR, behaviors)
            if not behaviors:
                continue
            if choose_map([geometry, spawn, behaviors[0]], maps) is None:
                continue
            result.candidates[Component.GEOMETRY] = [geometry] + [
                g for g in geometries if g is not geometry
            ]
            result.candidates[Component.SPAWN] = spawns[spawns.index(spawn) :]
            result.candidates[Component.BEHAVIOR] = behaviors
            result.chosen = {
                Component.GEOMETRY: [geometry],
                Component.SPAWN: [spawn],
                Component.BEHAVIOR: [behaviors[0]],
            }
            _add_extras(
                spec,
                kb,
                retriever,
                maps,
                choose_map,
                result,
                both | set(behaviors[0].defines),
                query,
            )
            result.map_name = choose_map(result.chosen_entries(), maps)
            if topk is not None:
                result.keep(topk)
            return result
    result.notes.append(f"no compatible geometry/spawn/behavior for a {adversary}")
    return result


def _add_extras(
    spec: ScenarioSpec,
    kb: KnowledgeBase,
    retriever: Retriever,
    maps: Mapping[str, frozenset[str]],
    choose_map: Callable[[list[Entry], Mapping[str, frozenset[str]]], str | None],
    result: Retrieval,
    defined: set[str],
    query: Callable[[str], str],
) -> None:
    """Weather, other participants and requirements that fit the chosen core."""
    weathers = kb.of(Component.WEATHER)
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
    for participant in spec.participants[:MAX_MISC]:
        for entry in _ranked(retriever, participant, Component.MISC, misc_pool)[:1]:
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
