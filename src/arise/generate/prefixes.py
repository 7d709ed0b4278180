"""The fixed prompt prefixes of the generator's model calls, for `arise llm warm`."""

from __future__ import annotations

from arise.generate.assemble import adapt_messages
from arise.generate.extract import extraction_messages
from arise.generate.repair import repair_messages
from arise.llm.types import Message


def fixed_prefixes() -> dict[str, list[Message]]:
    """Each call kind's messages but the last (the part that is the same in every run)."""
    return {
        "extract": extraction_messages("")[:-1],
        "adapt": adapt_messages("", "")[:-1],
        "repair": repair_messages("")[:-1],
    }
