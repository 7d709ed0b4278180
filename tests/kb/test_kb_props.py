"""Rows of props in the text's class and number: the copy, and the scene it makes on the real
Scenic compiler and simulator."""

from __future__ import annotations

import pytest

from arise.evaluate.fidelity import Direction, FactKind, LabeledActor, Start, Truth, score_fidelity
from arise.generate.assemble import assemble
from arise.generate.grounding import ground
from arise.generate.retrieve import retrieve
from arise.generate.spec import ExtractionAnswer
from arise.kb.compose import composition_problems
from arise.kb.loader import KnowledgeBase, load_kb
from arise.kb.props import PropRowError, prop_row
from arise.kb.retrieval import BM25Retriever
from arise.maps.registry import MapRegistry
from arise.validate import CheckOptions, WorkerPool, check_text
from arise.vocabulary import ActorClass

ROW = "misc.prop_row_in_lane_ahead"


@pytest.fixture(scope="module")
def kb() -> KnowledgeBase:
    return load_kb(builtin=True)


def test_a_row_copy_takes_the_class_the_count_and_names_of_its_own(kb: KnowledgeBase) -> None:
    row = prop_row(kb.get(ROW), ActorClass.of("Barrel"), 4, "P2", {"OPT_MISC_ROW_LATERAL": "-3.5"})
    assert "new Barrel" in row.snippet and "new Cone" not in row.snippet
    assert "range(4)" in row.snippet
    assert row.defines == ["rowRefP2", "rowSpotP2", "rowPropsP2"]
    assert "param OPT_MISC_ROW_LATERAL_P2 = -3.5" in row.snippet
    assert "globalParameters.OPT_MISC_ROW_AHEAD_P2" in row.snippet
    # two copies compose side by side: no name is shared
    other = prop_row(kb.get(ROW), ActorClass.of("Cone"), 2, "P3")
    assert not set(row.defines) & set(other.defines)
    assert not set(row.params) & set(other.params)
    # and each has a mark of its own, so both may be chosen
    assert (row.label, other.label) == (f"{ROW} as P2", f"{ROW} as P3")
    geometry = kb.get("geometry.straight_road")
    assert not composition_problems([geometry, row, other], None)


def test_a_long_row_is_capped_and_a_road_user_or_another_entry_is_refused(
    kb: KnowledgeBase,
) -> None:
    assert "range(8)" in prop_row(kb.get(ROW), ActorClass.of("Cone"), 40, "P1").snippet
    with pytest.raises(PropRowError):
        prop_row(kb.get(ROW), ActorClass.of("Car"), 2, "P1")
    with pytest.raises(PropRowError):
        prop_row(kb.get("misc.barrels_in_lane_ahead"), ActorClass.of("Cone"), 2, "P1")
    with pytest.raises(PropRowError):
        prop_row(kb.get(ROW), ActorClass.of("Cone"), 2, "p1; import os")


TEXT = (
    "Four plastic drums stand in the ego's lane ahead, and half a dozen cones were set "
    "along the shoulder before them."
)


@pytest.mark.slow
def test_props_stand_in_their_number_where_the_text_puts_them(
    kb: KnowledgeBase, validator_pool: WorkerPool
) -> None:
    answer = ExtractionAnswer.model_validate(
        {
            "adversary": "",
            "adversary_type": "car",
            "behavior": "",
            "road_type": "straight_road",
            "ego_maneuver": "go_straight",
            "geometry": "",
            "spawn_position": "ahead_same_lane",
            "spawn": "",
        }
    )
    spec = ground(TEXT, answer).spec
    maps = {name: entry.features for name, entry in MapRegistry().entries.items()}
    found = retrieve(spec, kb, BM25Retriever(kb), maps, TEXT)
    labels = [e.label for e in found.chosen_entries()]
    assert f"{ROW} as P1" in labels and "misc.prop_row_right_roadside as P2" in labels, labels
    assert spec.no_adversary  # the drums are the hazard, not an adversary that moves
    draft = assemble(found, None, TEXT, params={})
    truth = Truth(
        actors=(
            LabeledActor("Barrel", 4, start=Start.AHEAD, direction=Direction.STATIONARY),
            LabeledActor("Cone", 6, start=Start.RIGHT_FRONT, direction=Direction.STATIONARY),
        )
    )
    for seed in (0, 1):
        result = check_text(draft.script, CheckOptions(seed=seed, timeout=60), pool=validator_pool)
        assert result.ok and result.simulation is not None, (labels, result.diagnostic)
        fidelity = score_fidelity(truth, result, maps[draft.map_name])
        wrong = [
            f"{v.name}: expected {v.expected}, observed {v.observed}"
            for v in fidelity.verdicts
            if v.fact in {FactKind.ACTOR, FactKind.START} and v.match is False
        ]
        assert not wrong, (labels, seed, wrong)


def test_a_copy_name_from_a_data_file_is_one_plain_word(tmp_path) -> None:
    """A row or actor name goes into the script's `# kb:` mark: a crafted one is refused."""
    from arise.kb.loader import KBError, load_file
    from arise.kb.schema import Component

    (tmp_path / "misc.yaml").write_text(
        "entries:\n"
        "  - id: misc.crafted\n"
        "    descriptions: [A crafted entry.]\n"
        "    snippet: 'crafted = new Cone at egoStart'\n"
        "    defines: [crafted]\n"
        "    needs: [egoStart]\n"
        '    row: "P1\\nimport os"\n',
        encoding="utf-8",
    )
    with pytest.raises(KBError, match="plain name"):
        load_file(tmp_path / "misc.yaml", Component.MISC)
