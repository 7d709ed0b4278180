"""The model's answer schema is part of every extraction request."""

from __future__ import annotations

import hashlib
import json

from arise.generate.spec import ExtractionAnswer, ScenarioSpec

# Recorded cassettes and response caches are keyed on the request, schema included: a change
# to the spec or to its enums in arise.vocabulary (even a docstring) misses all of them.
SCHEMA_DIGEST = "4db59aec0ce4de6b"


def test_the_extraction_schema_is_unchanged() -> None:
    schema = json.dumps(ExtractionAnswer.model_json_schema(), sort_keys=True)
    digest = hashlib.sha256(schema.encode()).hexdigest()[:16]
    assert digest == SCHEMA_DIGEST, (
        "ExtractionAnswer's JSON schema changed: re-record the cassettes "
        "(tests/record_generate_cassettes.py) and update SCHEMA_DIGEST"
    )


def test_free_weather_words_become_a_preset() -> None:
    base = {
        "adversary_type": "car",
        "behavior": "brakes",
        "road_type": "highway",
        "ego_maneuver": "go_straight",
        "geometry": "a highway",
        "spawn_position": "ahead_same_lane",
        "spawn": "ahead",
    }
    assert (
        ScenarioSpec.model_validate({**base, "weather": "heavy rain at night"}).weather
        == "HardRainNight"
    )
    assert ScenarioSpec.model_validate({**base, "weather": "sunny"}).weather == "ClearNoon"
