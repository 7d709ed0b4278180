"""The tuning call's parameter listing: every parameter with its default, under the one
description of the knowledge-base entry that declares it."""

from __future__ import annotations

from arise.generate.assemble import declared_params, parameter_listing
from arise.kb.loader import load_kb


def test_each_entry_is_described_once_above_its_parameters() -> None:
    kb = load_kb()
    entries = [
        kb.entries["behavior.accelerate_through_junction"],
        kb.entries["geometry.junction_straight_cross_traffic"],
        kb.entries["spawn.junction_conflict_route"],
    ]
    declared = declared_params(entries)
    listing = parameter_listing(entries, declared).splitlines()
    for entry in entries:
        assert listing.count(entry.descriptions[0]) == 1
    for name, (default, entry_id) in declared.items():
        line = f"- {name} (default {default})"
        assert listing.count(line) == 1
        # the parameter sits in its own entry's block
        header = next(e.descriptions[0] for e in entries if e.id == entry_id)
        above = [text for text in listing[: listing.index(line)] if not text.startswith("- ")]
        assert above[-1] == header
    assert len(declared) >= 5, "the three entries declare the usual junction parameters"
