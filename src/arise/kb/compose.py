"""Composing knowledge-base entries into one complete Scenic 3 script.

`compose(entries, adversary_class, map_name)` is the one way a script is put together from
snippets, for the KB validator now and for the generator later. It follows
docs/script-format.md: a HEADER written from the map name, then one section per component in
a fixed order, each snippet preceded by a `# kb: <id>` line so a diagnostic's line number
leads back to the entry that wrote it.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence

from arise.errors import AriseError
from arise.kb.schema import COMPONENT_ORDER, PLACEHOLDER_PATTERN, Component, Entry
from arise.sections import MarkerKind, parse_marker, write_section
from arise.vocabulary import ADVERSARY_CLASSES, ActorClass

SINGLE = (Component.BEHAVIOR, Component.GEOMETRY, Component.SPAWN)  # exactly one each
OPTIONAL_SINGLE = (Component.WEATHER,)  # at most one
ADVERSARY_COMPONENTS = (Component.BEHAVIOR, Component.SPAWN)  # absent when there is none
ENTRY_MARK = re.compile(r"^# kb: (\S+)(?: as (\S+))?\s*$")
DEFAULT_TERMINATE_SECONDS = 20.0


class ComposeError(AriseError):
    """The entries do not fit together; every problem names the entry at fault."""

    def __init__(self, problems: Sequence[str]):
        self.problems = list(problems)
        super().__init__("; ".join(self.problems))


def header(map_name: str) -> str:
    """The HEADER section for one of the registry's maps (resolved by name)."""
    if not re.match(r"^[A-Za-z0-9_.-]+$", map_name):
        raise ComposeError([f"map name {map_name!r} is not a plain map name"])
    return "\n".join(
        write_section(
            "HEADER",
            [
                f"param map = localPath('maps/{map_name}.xodr')",
                f"param carla_map = '{map_name}'",
                "model scenic.simulators.carla.model",
            ],
        )
    )


def composition_problems(entries: Sequence[Entry], adversary_class: ActorClass | None) -> list[str]:
    """Why these entries would not make a script (empty when they would). A scene without
    an adversary (`adversary_class` None) has a geometry and no spawn or behavior."""
    problems: list[str] = []
    if adversary_class is not None:
        known = ActorClass.of(adversary_class)  # also a class name that came in as text
        if known is None or not known.as_adversary.is_adversary:  # a Van plays a Car
            problems.append(
                f"adversary class {str(adversary_class)!r} is not one of "
                f"{', '.join(ADVERSARY_CLASSES)}"
            )
        else:
            adversary_class = known.as_adversary
    ids = [entry.label for entry in entries]
    for duplicate in sorted({i for i in ids if ids.count(i) > 1}):
        problems.append(f"{duplicate}: chosen twice")
    problems += _actor_problems(entries)
    for component in SINGLE + OPTIONAL_SINGLE:
        chosen = [e.id for e in entries if e.component is component and e.actor is None]
        if len(chosen) > 1:
            problems.append(f"{', '.join(chosen)}: only one {component.value} entry fits")
        elif adversary_class is None and chosen and component in ADVERSARY_COMPONENTS:
            problems.append(f"{chosen[0]}: a scene without an adversary has no {component.value}")
        elif (
            not chosen
            and component in SINGLE
            and (adversary_class is not None or component not in ADVERSARY_COMPONENTS)
        ):
            problems.append(f"no {component.value} entry was chosen")
    for entry in entries:
        if entry.actor is not None:
            continue  # checked against the actor's own class
        if adversary_class is not None and not entry.suits(adversary_class):
            problems.append(
                f"{entry.id}: written for {', '.join(entry.adversaries)}, not {adversary_class}"
            )
    problems += _name_problems(_ordered(entries))
    return problems


def _actor_problems(entries: Sequence[Entry]) -> list[str]:
    """Each other actor has one spawn and one behavior, written for its class."""
    problems: list[str] = []
    actors = dict.fromkeys(e.actor for e in entries if e.actor is not None)
    for actor in actors:
        mine = [e for e in entries if e.actor == actor]
        for component in ADVERSARY_COMPONENTS:
            chosen = [e.label for e in mine if e.component is component]
            if len(chosen) != 1:
                problems.append(
                    f"{actor}: needs one {component.value} entry, has "
                    f"{', '.join(chosen) if chosen else 'none'}"
                )
        for entry in mine:
            cls = entry.actor_class
            if entry.component not in ADVERSARY_COMPONENTS:
                problems.append(f"{entry.label}: only spawn and behavior entries place an actor")
            elif cls is None or not cls.is_road_user:
                problems.append(f"{entry.label}: {str(cls)!r} is not a road user's class")
            elif not entry.suits(cls.as_adversary):
                problems.append(
                    f"{entry.label}: written for {', '.join(entry.adversaries)}, not {cls}"
                )
    return problems


def _ordered(entries: Iterable[Entry]) -> list[Entry]:
    """Entries in section order, keeping the given order within a section."""
    rank = {component: index for index, component in enumerate(COMPONENT_ORDER)}
    return sorted(entries, key=lambda entry: rank[entry.component])


def _name_problems(ordered: Sequence[Entry]) -> list[str]:
    """Needs that nothing earlier defines, and names defined twice.

    A behavior's body runs during the simulation, after every section has run, so its
    needs may be defined by any entry; everything else needs names defined above it.
    """
    problems: list[str] = []
    everything = {name for entry in ordered for name in entry.defines}
    owner: dict[str, str] = {}
    defined: set[str] = set()
    for entry in ordered:
        visible = everything if entry.component is Component.BEHAVIOR else defined
        missing = [
            name for name in entry.needs if name not in visible and name not in entry.defines
        ]
        if missing:
            problems.append(
                f"{entry.label}: needs {', '.join(missing)}, which no "
                f"{'chosen' if entry.component is Component.BEHAVIOR else 'earlier'}"
                " entry defines"
            )
        for name in entry.defines:
            if name in owner:
                problems.append(f"{entry.label}: defines {name}, already defined by {owner[name]}")
            owner.setdefault(name, entry.label)
        defined |= set(entry.defines)
    return problems


def fill_placeholders(snippet: str, values: Mapping[str, str], entry_id: str) -> str:
    """Substitute `{{NAME}}`; a placeholder without a value is an error naming the entry."""
    missing = sorted({m for m in PLACEHOLDER_PATTERN.findall(snippet) if m not in values})
    if missing:
        raise ComposeError(
            [
                f"{entry_id}: no value for placeholder(s) "
                f"{', '.join('{{' + m + '}}' for m in missing)}"
            ]
        )
    return PLACEHOLDER_PATTERN.sub(lambda m: values[m.group(1)], snippet)


def compose(
    entries: Sequence[Entry],
    adversary_class: ActorClass | None,
    map_name: str,
    *,
    description: str | None = None,
    placeholders: Mapping[str, str] | None = None,
    terminate_after: float | None = DEFAULT_TERMINATE_SECONDS,
) -> str:
    """Assemble one complete script: HEADER from `map_name`, then the entries' sections.

    entries: exactly one behavior, geometry and spawn entry; at most one weather entry;
        any number of misc and requirements entries (in the order given); and for each
        other actor placed, one spawn and one behavior copy (`arise.kb.actors.for_actor`).
    adversary_class: what `{{ADVERSARY_CLASS}}` becomes (Car, Truck, Motorcycle, Bicycle,
        Pedestrian, or Van and Bus, which fit where a Car and a Truck do); every entry must
        suit it. None: the scene has no adversary (no spawn or behavior entry).
    map_name: a map known to the registry (`arise maps list`); pick one with `pick_map`.
    placeholders: values for any other `{{NAME}}` the entries declare.
    terminate_after: seconds after which the scenario ends, unless a requirements entry
        already says `terminate`; None adds nothing.

    Raises ComposeError (naming the entries) when the entries do not fit together.
    """
    problems = composition_problems(entries, adversary_class)
    if problems:
        raise ComposeError(problems)
    values = dict(placeholders or {})
    if adversary_class is not None:
        values.setdefault("ADVERSARY_CLASS", str(adversary_class))
    lines: list[str] = []
    if description:
        lines += ["# " + line if line else "#" for line in description.strip().splitlines()]
    lines.append(header(map_name))
    ordered = _ordered(entries)
    for component in COMPONENT_ORDER:
        chosen = [entry for entry in ordered if entry.component is component]
        body: list[str] = []
        for entry in chosen:
            body.append(f"# kb: {entry.label}")
            body.append(fill_placeholders(entry.snippet.rstrip("\n"), values, entry.label))
        if (
            component is Component.REQUIREMENTS
            and terminate_after is not None
            and not any(re.search(r"^[^\S\n]*terminate\b", e.snippet, re.M) for e in chosen)
        ):
            body.append(f"terminate after {terminate_after:g} seconds")
        lines += write_section(component.section, body)
    return "\n".join(lines) + "\n"


def entry_at_line(script: str, line: int | None) -> str | None:
    """The id of the entry whose snippet holds this (1-based) line of a composed script."""
    found = mark_at_line(script, line)
    return found[0] if found else None


def actor_at_line(script: str, line: int | None) -> str | None:
    """The other actor ('actor2') whose snippet holds this line; None for the adversary's
    or the scene's entries."""
    found = mark_at_line(script, line)
    return found[1] if found else None


def mark_at_line(script: str, line: int | None) -> tuple[str, str | None] | None:
    """(entry id, actor or None) of the `# kb:` mark above this (1-based) line, within its
    section."""
    if line is None:
        return None
    found: tuple[str, str | None] | None = None
    for number, text in enumerate(script.splitlines(), start=1):
        if number > line:
            break
        mark = ENTRY_MARK.match(text)
        marker = parse_marker(text)
        if mark:
            found = (mark.group(1), mark.group(2))
        elif marker is not None and marker.kind is MarkerKind.END:
            found = None
    return found


def map_features_needed(entries: Iterable[Entry]) -> frozenset[str]:
    return frozenset(feature for entry in entries for feature in entry.map_features)


def pick_map(entries: Iterable[Entry], available: Mapping[str, Iterable[str]]) -> str | None:
    """The map with every feature the entries need and the fewest extra ones.

    available: map name -> its features (e.g. from MapRegistry().entries).
    """
    wanted = map_features_needed(entries)
    fitting = [
        (len(set(features) - wanted), name)
        for name, features in available.items()
        if wanted <= set(features)
    ]
    return min(fitting)[1] if fitting else None
