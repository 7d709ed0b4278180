"""Picking entries of a loaded knowledge base by id, with a clear error for a wrong one."""

from __future__ import annotations

from collections.abc import Sequence

from arise.errors import AriseError
from arise.kb.loader import KnowledgeBase
from arise.kb.schema import Component, Entry


class UnknownEntry(AriseError):
    """An entry id the knowledge base (ours plus the user's folders) does not hold."""


def find_entry(kb: KnowledgeBase, entry_id: str) -> Entry:
    """The entry `entry_id`; UnknownEntry names up to five ids it may have meant."""
    if entry_id not in kb:
        close = [e.id for e in kb if entry_id.split(".")[-1] in e.id][:5]
        hint = f"; did you mean {', '.join(close)}?" if close else ""
        raise UnknownEntry(f"no entry {entry_id!r}{hint}")
    return kb.get(entry_id)


def select_ids(
    kb: KnowledgeBase, component: Component | None = None, ids: Sequence[str] = ()
) -> list[str]:
    """Ids of the entries of `component` (all if None) among `ids` (all if empty), in load
    order; UnknownEntry for an id the knowledge base does not hold."""
    unknown = sorted(set(ids) - set(kb.entries))
    if unknown:
        raise UnknownEntry(f"no such entries: {', '.join(unknown)}")
    return [
        e.id
        for e in kb
        if (component is None or e.component is component) and (not ids or e.id in ids)
    ]
