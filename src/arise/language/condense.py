"""Long inputs: a crash-report paragraph reduced to the scenario it describes.

Collision reports carry a date and time, and sentences about damage, injuries, drivers and
the police; none of them is part of the scenario, and each costs the small model prompt
tokens and attention. Those sentences (and the leading date) are left out before
extraction, and the run's report lists them. A sentence that also tells what a road user
did ("...made contact with the AV's door") is kept, whatever else it says.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

_SENTENCE = re.compile(r"(?<=[.!?])\s+(?=[A-Z])")
_DATE = re.compile(
    r"^\s*On (?:\w+day, )?[A-Z][a-z]+\.? \d{1,2}(?:st|nd|rd|th)?,? \d{4}"
    r"(?:,? at (?:about |approximately )?\d{1,2}(?::\d{2})? ?(?:[AaPp]\.? ?[Mm]\.?)?)?,\s*"
)
_AFTERMATH = re.compile(
    r"\b(?:damag\w*|dent\w*|scuff\w*|scratch\w*|injur\w*|hospital|ambulance|medical|"
    r"pain|police|cited|citation|patrol|officers?|report (?:was )?(?:made|filed)|"
    r"(?:took|filed) a report|declined|walked away|towed|towing|tow truck|airbags?)\b",
    re.I,
)
_ACTION = re.compile(
    r"\b(?:struck|strikes?|hit|hits|contact|touched|collid\w*|sideswip\w*|scraped (?:the|its)|"
    r"turn\w*|cross\w*|brak\w*|travel\w*|merg\w*|swerv\w*|pull\w*|entered|enter\w*|"
    r"approach\w*|ran|runs?|passed|pass\w*|stopp\w*|slow\w*|accelerat\w*|revers\w*)\b",
    re.I,
)


@dataclass
class Condensed:
    """The text the scenario is read from, and what was left out of the input."""

    text: str
    ignored: list[str] = field(default_factory=list)


def condense(description: str) -> Condensed:
    """`description` without its date and its aftermath sentences (damage, injuries,
    police); the input itself when nothing is left out or nothing would remain."""
    text = description.strip()
    ignored: list[str] = []
    date = _DATE.match(text)
    if date:
        ignored.append(date.group(0).strip().rstrip(","))
        rest = text[date.end() :]
        text = rest[:1].upper() + rest[1:]
    kept: list[str] = []
    for sentence in _SENTENCE.split(text):
        if _AFTERMATH.search(sentence) and not _ACTION.search(sentence):
            ignored.append(sentence.strip())
        else:
            kept.append(sentence.strip())
    if not kept or not ignored:
        return Condensed(description.strip())
    return Condensed(" ".join(kept), ignored)
