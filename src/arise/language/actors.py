"""The other actors of a description: each road user or object it names besides the ego and
the adversary, with a role, a class, a count, a start and the words it rests on.

Fixed readers, no model: the same per-actor readers as the adversary's (`readers`), each
looking only at the words about that actor, so "a parked truck" on the right does not lend
its side to the pedestrian. One actor per mention, in the order of `spec.participants`.
The result is this layer's own `CastActor`; generate builds the spec's Actor from it.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from arise.language.cast import Cast, Mention
from arise.language.facts import start_detail
from arise.language.readers import (
    Reading,
    exit_street_walker,
    lane_end,
    moves_in,
    read_start,
    read_stationary,
    someone_comes_out_from,
    words_of,
)
from arise.language.rules import Fact, rulebook
from arise.vocabulary import ActorClass, ActorRole, RelativePosition, StartDetail


@dataclass(frozen=True)
class CastActor:
    """One road user or object besides the ego (and the adversary, but for the rest of a
    counted adversary), as the words give it; the fields are those of the spec's Actor."""

    role: ActorRole
    scenic_class: ActorClass
    count: int = 1
    count_stated: bool = True  # a number or one; False for a plural with no number
    start: RelativePosition | None = None  # seen from the ego; None: not stated
    start_detail: StartDetail | None = None  # a finer point of the start, when the words give one
    stationary: bool = False
    quote: str = ""  # the words of the description that name it


_ROLE_OF_START: dict[RelativePosition, ActorRole] = {
    RelativePosition.ONCOMING: ActorRole.ONCOMING,
    RelativePosition.CROSSING_FROM_LEFT: ActorRole.CROSSING,
    RelativePosition.CROSSING_FROM_RIGHT: ActorRole.CROSSING,
    RelativePosition.BEHIND_SAME_LANE: ActorRole.FOLLOWING,
}


def _cues(text: str, stretches: list[tuple[int, int]]) -> set[str]:
    """The role cues (rules of `role_cue`) in the words about an actor: occluder ("a van
    hides the pedestrian"), waits, parked, follows, slow."""
    book = rulebook()
    return {hit.value for a, b in stretches for hit in book.hits(Fact.ROLE_CUE, text, a, b)}


def _role(
    *,
    cls: str,
    prop: bool,
    cues: set[str],
    hides_behind: bool,
    start: RelativePosition | None,
    stationary: bool,
) -> ActorRole:
    """The role the words give an actor; the strongest cue first. `hides_behind`: the
    words right before it put someone behind it ("steps out from behind a parked van";
    "the ego waits behind a stopped bus" is not one)."""
    if prop:
        return ActorRole.OBSTACLE
    if "occluder" in cues or hides_behind:
        return ActorRole.OCCLUDER
    if stationary:
        return ActorRole.PARKED if "parked" in cues else ActorRole.STOPPED
    if start in _ROLE_OF_START:
        return _ROLE_OF_START[start]
    if start is None and "follows" in cues:
        return ActorRole.FOLLOWING
    if "slow" in cues:
        return ActorRole.SLOW
    if start is RelativePosition.AHEAD_SAME_LANE:
        return ActorRole.LEAD
    if cls is ActorClass.PEDESTRIAN:
        return ActorRole.CROSSING
    if start in (RelativePosition.ROADSIDE_LEFT, RelativePosition.ROADSIDE_RIGHT):
        return ActorRole.PARKED
    return ActorRole.LEAD


#: The lanes beside the ego, whose end (ahead or behind) an actor's words may say.
_BESIDE = frozenset({RelativePosition.ADJACENT_LANE_LEFT, RelativePosition.ADJACENT_LANE_RIGHT})


def read_actor(cast: Cast, mention: Mention) -> CastActor:
    """One actor other than the adversary, from the words about it. Waiting or standing
    still, for an actor that is not the adversary (whose waiting is the calm before its
    move), means it stays put."""
    text = cast.text
    stretches = words_of(cast, mention)
    cues = _cues(text, stretches)
    position = read_start(cast, mention)
    start = RelativePosition(position.value) if position is not None else None
    stationary = read_stationary(cast, mention) is not None or bool(
        "waits" in cues and not moves_in(text, stretches)
    )
    role = _role(
        cls=mention.cls,
        prop=mention.is_prop,
        cues=cues,
        hides_behind=someone_comes_out_from(cast, mention, stretches),
        start=start,
        stationary=stationary,
    )
    detail = start_detail(position)
    if detail is None and start in _BESIDE:
        # "bike in R lane @ 4 o'clock": behind the ego in that lane
        told = lane_end(cast, mention)
        detail = StartDetail(told.value) if told is not None else None
    return CastActor(
        role=role,
        scenic_class=mention.cls,
        count=mention.count,
        count_stated=mention.counted,
        start=start,
        start_detail=detail,
        stationary=stationary or mention.is_prop,
        quote=mention.quote,
    )


def _queued_ahead(cast: Cast, mention: Mention, actor: CastActor) -> bool:
    """A lead in the ego's lane whose own words do not move it, ahead of an ego held still."""
    return (
        actor.role is ActorRole.LEAD
        and actor.start is RelativePosition.AHEAD_SAME_LANE
        and not moves_in(cast.text, words_of(cast, mention))
    )


def read_actors(reading: Reading) -> list[CastActor]:
    """One actor per thing the description names other than the ego and the adversary, in
    the order of the spec's participants; then, when the text names the adversary with a
    count ("two pedestrians cross"), one more with role adversary for the others of them."""
    cast = reading.cast
    found: list[CastActor] = []
    adversary = reading.adversary
    held = "ego_stopped" in reading.facts
    maneuver = reading.facts.get("ego_maneuver")
    for mention in cast.others:
        if mention is not adversary:
            actor = read_actor(cast, mention)
            if actor.start is None and (
                walker := exit_street_walker(cast, mention, maneuver.value if maneuver else None)
            ):
                # "a woman is stepping off the far corner of the street you're turning into"
                actor = replace(actor, start=walker.position, start_detail=walker.detail)
            if held and _queued_ahead(cast, mention, actor):
                # "second in the queue behind a hatchback" at a red: it waits there too
                actor = replace(actor, role=ActorRole.STOPPED, stationary=True)
            found.append(actor)
    if adversary is not None and adversary.count > 1:
        found.append(
            CastActor(
                role=ActorRole.ADVERSARY,
                scenic_class=adversary.cls,
                count=adversary.count - 1,
                quote=adversary.quote,
            )
        )
    return found
