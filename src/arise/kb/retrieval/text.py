"""Turning a description or a query into index terms for lexical retrieval.

People describe the same thing with different words (kerb/curb, lorry/truck, motorway/
highway), and BM25 only matches identical terms, so terms are lower-cased, stripped of
common suffixes and mapped to one word per concept before indexing and searching.
"""

from __future__ import annotations

import re

STOPWORDS = frozenset(["a", "an", "the", "and", "or", "but", "of", "to", "in", "on", "at", "by", "for", "from", "with", "into", "onto", "as", "is", "are", "was", "were", "be", "been", "being", "it", "its", "this", "that", "these", "those", "there", "here", "then", "than", "so", "such", "some", "any", "very", "just", "also", "while", "when", "where", "which", "who", "whom", "whose", "what", "how", "about", "over", "under", "up", "down", "out", "off", "again", "further", "once", "both", "each", "few", "more", "most", "other", "own", "same", "too", "can", "will", "would", "should", "could", "may", "might", "must", "do", "does", "did", "doing", "has", "have", "had", "having", "i", "me", "my", "we", "our", "you", "your", "he", "him", "his", "she", "her", "they", "them", "their", "one", "two"])

# One canonical term per concept, for words scenario descriptions use interchangeably.
SYNONYMS: dict[str, str] = {
    # road users
    "walker": "pedestrian", "person": "pedestrian", "people": "pedestrian",
    "someone": "pedestrian", "man": "pedestrian", "woman": "pedestrian", "lady": "pedestrian",
    "kid": "child", "jogger": "runner",
    "bike": "bicycle", "cyclist": "bicycle", "cycle": "bicycle", "rider": "bicycle",
    "motorbike": "motorcycle", "scooter": "motorcycle", "moped": "motorcycle",
    "lorry": "truck", "hgv": "truck", "goods": "truck",
    "automobile": "car", "vehicle": "car", "driver": "car",
    "adversarial": "adversary",
    # places
    "kerb": "curb", "kerbside": "curb", "roadside": "curb",
    "pavement": "sidewalk", "footpath": "sidewalk", "footway": "sidewalk",
    "motorway": "highway", "freeway": "highway", "expressway": "highway",
    "carriageway": "road", "roadway": "road", "street": "road",
    "crossroad": "intersection", "crossroads": "intersection", "junction": "intersection",
    "crossing": "cross",
    "signals": "signal", "lights": "signal", "signalized": "signal", "signalised": "signal",
    "bend": "curve", "curves": "curve", "curved": "curve",
    "neighbouring": "adjacent", "neighboring": "adjacent", "next": "adjacent",
    "opposing": "oncoming", "opposite": "oncoming",
    "centre": "center", "middle": "center", "central": "center",
    "front": "ahead", "rear": "behind", "back": "behind",
    "t": "tjunction",
    # actions
    "halt": "stop", "halts": "stop", "halted": "stop", "stops": "stop", "stopped": "stop",
    "brakes": "brake", "braking": "brake", "decelerate": "slow", "decelerates": "slow",
    "slows": "slow", "slowly": "slow", "slower": "slow",
    "speeds": "accelerate", "faster": "fast", "quickly": "fast", "speeding": "fast",
    "sprint": "run", "sprints": "run", "dash": "run", "dashes": "run", "darts": "run",
    "bursts": "run",
    "merge": "cut", "merges": "cut", "merging": "cut", "squeezes": "cut",
    "zigzag": "weave", "zigzags": "weave",
    "reverses": "reverse", "reversing": "reverse", "backs": "reverse",
    "later": "eventually", "sometime": "eventually", "finally": "eventually",
    "point": "heading", "pointing": "heading", "face": "heading", "facing": "heading",
    "orientation": "heading", "meter": "metre", "m": "metre",
    # numbers as words
    "five": "5", "ten": "10", "twelve": "12", "fifteen": "15", "twenty": "20",
    "thirty": "30", "forty": "40", "fifty": "50", "sixty": "60", "seventy": "70",
    "eighty": "80", "hundred": "100",
    # weather and light
    "sunny": "clear", "sunshine": "clear", "bright": "clear",
    "overcast": "cloudy", "grey": "cloudy", "gray": "cloudy",
    "drizzle": "light rain", "downpour": "heavy rain", "pouring": "heavy rain",
    "rainy": "rain", "raining": "rain", "shower": "rain",
    "midday": "noon", "daytime": "noon", "daylight": "noon", "day": "noon",
    "evening": "sunset", "dusk": "sunset",
    "dark": "night", "nighttime": "night",
    "misty": "fog", "mist": "fog", "foggy": "fog",
    "sandstorm": "dust", "sand": "dust",
    "dazzle": "glare", "dazzles": "glare", "blinding": "glare",
}

_SUFFIXES = ("ing", "ed", "es", "s", "ly")


def stem(word: str) -> str:
    """A small suffix stripper: enough to match 'crosses'/'crossing'/'crossed'."""
    for suffix in _SUFFIXES:
        if word.endswith(suffix) and len(word) - len(suffix) >= 4:
            base = word[: -len(suffix)]
            if suffix in ("ing", "ed") and len(base) > 2 and base[-1] == base[-2]:
                base = base[:-1]  # stopped -> stop, running -> run
            return base
    return word


def terms(text: str) -> list[str]:
    """Index terms of a text: words, synonyms folded, stop words dropped, suffixes cut."""
    words = re.findall(r"[a-z0-9]+", text.lower().replace("_", " "))
    found = []
    for word in words:
        if word in STOPWORDS:
            continue
        if word not in SYNONYMS:
            word = stem(word)
        found += SYNONYMS.get(word, word).split()
    return found
