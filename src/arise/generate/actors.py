"""The other actors of a description: each road user or object it names besides the ego and
the adversary, with a role, a class, a count, a start and the words it rests on.

Fixed readers, no model: the same per-actor readers as the adversary's (`readers`), each
looking only at the words about that actor, so "a parked truck" on the right does not lend
its side to the pedestrian. One actor per mention, in the order of `spec.participants`.
"""

from __future__ import annotations

import re

from arise.generate.readers import (
    Reading,
    moves,
    read_compass,
    read_position,
    read_stationary,
    words_of,
)
from arise.generate.spec import Actor
from arise.vocabulary import ActorRole, RelativePosition

# Words that make a named thing hide the adversary ("a parked van hides the pedestrian").
_HIDES = re.compile(
    r"\b(?:hides?|hidden|hiding|blocks? (?:the|its|his|her) (?:view|line of sight)|"
    r"blocking the (?:view|line of sight)|obscur\w*|occlud\w*)\b",
    re.I,
)
# "steps out from behind a parked van", "walked out from in front of the truck": the van
# or the truck hides the adversary.
# ("the ego waits behind a stopped bus" is not one.)
_BEHIND_IT = re.compile(r"\b(?:from|out) (?:behind|in front of)\s*$", re.I)
# Waiting or standing still, for an actor that is not the adversary (whose waiting is the
# calm before its move): it stays put.
_WAITS = re.compile(r"\b(?:waits?|waiting|stands?|standing|queu\w*)\b", re.I)
_PARKED = re.compile(r"\b(?:double[- ])?parked\b", re.I)
_FOLLOWS = re.compile(
    r"\bfollow(?:s|ing)? (?:the |our )?(?:ego|av)\b|\btailgat\w*|\bbehind (?:the )?(?:ego|av)\b",
    re.I,
)
_SLOW = re.compile(r"\bslow(?:er|ly|[- ]moving)?\b|\bcrawl\w*|\bcreep\w*", re.I)
_ROLE_OF_START: dict[RelativePosition, ActorRole] = {
    RelativePosition.ONCOMING: ActorRole.ONCOMING,
    RelativePosition.CROSSING_FROM_LEFT: ActorRole.CROSSING,
    RelativePosition.CROSSING_FROM_RIGHT: ActorRole.CROSSING,
    RelativePosition.BEHIND_SAME_LANE: ActorRole.FOLLOWING,
}


def _role(
    *,
    cls: str,
    prop: bool,
    words: str,
    before: list[str],
    start: RelativePosition | None,
    stationary: bool,
) -> ActorRole:
    """The role the words give an actor; the strongest cue first."""
    if prop:
        return ActorRole.OBSTACLE
    if _HIDES.search(words) or any(_BEHIND_IT.search(b) for b in before):
        return ActorRole.OCCLUDER
    if stationary:
        return ActorRole.PARKED if _PARKED.search(words) else ActorRole.STOPPED
    if start in _ROLE_OF_START:
        return _ROLE_OF_START[start]
    if start is None and _FOLLOWS.search(words):
        return ActorRole.FOLLOWING
    if _SLOW.search(words):
        return ActorRole.SLOW
    if start is RelativePosition.AHEAD_SAME_LANE:
        return ActorRole.LEAD
    if cls == "Pedestrian":
        return ActorRole.CROSSING
    if start in (RelativePosition.ROADSIDE_LEFT, RelativePosition.ROADSIDE_RIGHT):
        return ActorRole.PARKED
    return ActorRole.LEAD


def read_actors(reading: Reading) -> list[Actor]:
    """One actor per thing the description names other than the ego and the adversary, in
    the order of the spec's participants; then, when the text names the adversary with a
    count ("two pedestrians cross"), one more with role adversary for the others of them."""
    cast = reading.cast
    found: list[Actor] = []
    adversary = reading.adversary
    for mention in cast.others:
        if mention is adversary:
            continue
        stretches = words_of(cast, mention)
        words = " ".join(cast.text[a:b] for a, b in stretches)
        before = [cast.text[max(0, a - 20) : a] for a, _ in stretches]
        position = read_compass(cast, mention) or read_position(cast, mention)
        start = RelativePosition(position.value) if position is not None else None
        stationary = read_stationary(cast, mention) is not None or bool(
            _WAITS.search(words) and not any(moves(cast.text, a, b) for a, b in stretches)
        )
        role = _role(
            cls=mention.cls,
            prop=mention.is_prop,
            words=words,
            before=before,
            start=start,
            stationary=stationary,
        )
        found.append(
            Actor(
                role=role,
                scenic_class=mention.cls,
                count=mention.count,
                count_stated=mention.counted,
                start=start,
                stationary=stationary or mention.is_prop,
                quote=mention.quote,
            )
        )
    if adversary is not None and adversary.count > 1:
        found.append(
            Actor(
                role=ActorRole.ADVERSARY,
                scenic_class=adversary.cls,
                count=adversary.count - 1,
                quote=adversary.quote,
            )
        )
    return found
