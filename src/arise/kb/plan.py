"""Which complete scripts prove every entry runs: a small covering set of compositions.

Each script needs one behavior, one geometry and one spawn entry, so the plan first builds
such cores until every behavior, geometry and spawn entry is in one, preferring declared
companions and partners not yet covered, and rotating the adversary class. Weather, misc and
requirements entries are then attached to cores they fit, a few per script, so ~50 scripts
cover 150+ entries.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field

from arise.kb.compose import compose, composition_problems, pick_map
from arise.kb.schema import Component, Entry
from arise.vocabulary import ActorClass, AdversaryType

# How many entries of each attachable component one script carries at most. One
# requirements entry per script: two constraints written separately may exclude each other.
ATTACH_LIMITS = {Component.WEATHER: 1, Component.MISC: 2, Component.REQUIREMENTS: 1}
#: The classes the plan rotates through, in AdversaryType's order.
_ADVERSARIES = tuple(kind.scenic_class for kind in AdversaryType)


@dataclass
class Composition:
    """One script of the plan: the entries it proves, its adversary class and map."""

    name: str
    entries: list[Entry]
    adversary_class: ActorClass
    map_name: str
    notes: list[str] = field(default_factory=list)

    @property
    def ids(self) -> list[str]:
        return [entry.id for entry in self.entries]

    def script(self) -> str:
        return compose(
            self.entries,
            self.adversary_class,
            self.map_name,
            description=f"{self.name}: {', '.join(self.ids)}",
        )


@dataclass
class Plan:
    compositions: list[Composition]
    uncovered: dict[str, str]  # entry id -> why no script could include it

    def covering(self, entry_id: str) -> list[Composition]:
        return [c for c in self.compositions if entry_id in c.ids]


def _fits(
    entries: Sequence[Entry], adversary: ActorClass, maps: Mapping[str, Iterable[str]]
) -> str | None:
    """The map these entries would run on, or None if they do not compose."""
    if composition_problems(entries, adversary):
        return None
    return pick_map(entries, maps)


class _Planner:
    def __init__(self, entries: Sequence[Entry], maps: Mapping[str, Iterable[str]]):
        self.maps = {name: set(features) for name, features in maps.items()}
        self.by_component: dict[Component, list[Entry]] = {c: [] for c in Component}
        for entry in entries:
            self.by_component[entry.component].append(entry)
        self.usage: Counter[str] = Counter()
        self.adversary_usage: Counter[tuple[str, ActorClass]] = Counter()
        self.compositions: list[Composition] = []

    def _score(
        self, target: Entry, core: tuple[Entry, Entry, Entry], adversary: ActorClass
    ) -> tuple[int, int, int, int]:
        companions = sum(1 for e in core if e.id in target.companions or target.id in e.companions)
        fresh = sum(1 for e in core if self.usage[e.id] == 0)
        used = sum(self.usage[e.id] for e in core)
        rotation = sum(self.adversary_usage[(e.id, adversary)] for e in core)
        return (companions, fresh, -rotation, -used)

    def _cores_with(self, target: Entry) -> Iterable[tuple[tuple[Entry, Entry, Entry], ActorClass]]:
        behaviors = self.by_component[Component.BEHAVIOR]
        geometries = self.by_component[Component.GEOMETRY]
        spawns = self.by_component[Component.SPAWN]
        if target.component is Component.BEHAVIOR:
            behaviors = [target]
        elif target.component is Component.GEOMETRY:
            geometries = [target]
        else:
            spawns = [target]
        for geometry in geometries:
            g_names = set(geometry.defines)
            for spawn in spawns:
                if not set(spawn.needs) <= g_names:
                    continue
                gs_names = g_names | set(spawn.defines)
                for behavior in behaviors:
                    if not set(behavior.needs) <= gs_names | set(behavior.defines):
                        continue
                    for adversary in _ADVERSARIES:
                        if spawn.suits(adversary) and behavior.suits(adversary):
                            yield (behavior, geometry, spawn), adversary

    def add_core(self, target: Entry, carrying: Entry | None = None) -> Composition | None:
        """A new script around `target`: the best-scoring core that composes on a map (with
        `carrying` too, when given, so that an entry opening a script can ride on it)."""
        best = None
        for core, adversary in self._cores_with(target):
            score = self._score(target, core, adversary)
            if best is not None and score <= best[0]:
                continue
            on_map = core if carrying is None else [*core, carrying]
            map_name = _fits(on_map, adversary, self.maps)
            if map_name is not None:
                best = (score, list(core), adversary, map_name)
        if best is None:
            return None
        _, entries, adversary, map_name = best
        composition = Composition(
            f"kb-{len(self.compositions) + 1:03d}", entries, adversary, map_name
        )
        self._count(composition, entries)
        self.compositions.append(composition)
        return composition

    def _count(self, composition: Composition, entries: Iterable[Entry]) -> None:
        for entry in entries:
            self.usage[entry.id] += 1
            self.adversary_usage[(entry.id, composition.adversary_class)] += 1

    def attach(self, entry: Entry) -> bool:
        """Add an attachable entry to the best script it fits; False if none."""
        limit = ATTACH_LIMITS[entry.component]

        def companions(c: Composition) -> int:
            return sum(1 for e in c.entries if e.id in entry.companions or entry.id in e.companions)

        def rank(c: Composition) -> tuple[int, int]:
            load = sum(1 for e in c.entries if e.component is entry.component)
            return (-companions(c), load)

        for composition in sorted(self.compositions, key=rank):
            if entry.companions and not companions(composition):
                continue  # written for its companions: prove it with them
            if sum(1 for e in composition.entries if e.component is entry.component) >= limit:
                continue
            candidate = [*composition.entries, entry]
            map_name = _fits(candidate, composition.adversary_class, self.maps)
            if map_name is None:
                continue
            composition.entries = candidate
            composition.map_name = map_name
            self._count(composition, [entry])
            return True
        return False


def plan_validation(
    entries: Sequence[Entry], maps: Mapping[str, Iterable[str]], only: Iterable[str] | None = None
) -> Plan:
    """Compositions that include every entry (or every entry in `only`) at least once.

    entries: the whole knowledge base (partners may come from any of it).
    maps: map name -> features, the maps the scripts may run on.
    only: restrict coverage to these entry ids (e.g. one component).
    """
    wanted = set(only) if only is not None else {entry.id for entry in entries}
    planner = _Planner(entries, maps)
    uncovered: dict[str, str] = {}
    core_components = (Component.BEHAVIOR, Component.SPAWN, Component.GEOMETRY)
    for component in core_components:
        for entry in planner.by_component[component]:
            if entry.id not in wanted or planner.usage[entry.id]:
                continue
            if planner.add_core(entry) is None:
                uncovered[entry.id] = (
                    "no behavior+geometry+spawn combination with this "
                    "entry composes (check needs, adversaries, map features)"
                )
    if not planner.compositions:
        # Attachable entries alone still need a core to ride on.
        for entry in planner.by_component[Component.BEHAVIOR]:
            if planner.add_core(entry) is not None:
                break
    for component in ATTACH_LIMITS:
        # Entries written for particular companions go first, before others fill the slots.
        ordered = sorted(planner.by_component[component], key=lambda e: not e.companions)
        for entry in ordered:
            if entry.id not in wanted:
                continue
            if planner.attach(entry):
                continue
            # Every script is full or unsuitable: open a new one from a fitting core,
            # built around a companion when the entry names one.
            fitted = False
            core_ids = {e.id for c in core_components for e in planner.by_component[c]}
            seeds = [
                planner_entry
                for planner_entry in entries
                if planner_entry.id in entry.companions and planner_entry.id in core_ids
            ]
            for behavior in seeds or planner.by_component[Component.BEHAVIOR]:
                composition = planner.add_core(behavior, carrying=entry)
                if composition is None:
                    continue
                if planner.attach(entry):
                    fitted = True
                    break
                planner.compositions.remove(composition)
                for e in composition.entries:
                    planner.usage[e.id] -= 1
                    planner.adversary_usage[(e.id, composition.adversary_class)] -= 1
            if not fitted:
                uncovered[entry.id] = (
                    f"fits no script: its needs {entry.needs} or map "
                    f"features {entry.map_features} match no core"
                )
    return Plan(planner.compositions, uncovered)
