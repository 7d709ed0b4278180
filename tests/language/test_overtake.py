"""An ego that pulls out to the left while someone comes the other way overtakes through
that one's lane: a bypass on a two-way road (issue 28, two roles in one scene)."""

from __future__ import annotations

import pytest

from arise.language.readers import read_description


@pytest.mark.parametrize(
    "text",
    [
        "Stuck behind a milk float, the ego moves out to overtake while a tractor approaches from the opposite direction.",
        "ego behind slow hearse, overtakes, oncoming estate car closing",
        "I was behind a learner and I pulled out to pass, but a van was coming towards me.",
    ],
)
def test_pulling_out_with_oncoming_traffic_is_a_bypass(text: str) -> None:
    facts = read_description(text).facts
    assert facts["ego_maneuver"].value == "change_lane"
    assert facts["ego_plan"].value == "ego_bypass"


@pytest.mark.parametrize(
    "text",
    [
        # nobody comes the other way
        "Stuck behind a milk float, the ego moves out to overtake it on the empty road.",
        # a highway's left lane runs the ego's way
        "On the motorway the ego moves into the left lane to overtake a coach while a lorry passes on the far carriageway in the opposite direction.",
        # a change to the right is no pass through the oncoming lane
        "The ego changes into the right lane as an oncoming bus goes by.",
    ],
)
def test_no_bypass_without_oncoming_traffic_on_a_two_way_road(text: str) -> None:
    facts = read_description(text).facts
    assert "ego_plan" not in facts or facts["ego_plan"].value != "ego_bypass"
