"""What every retrieval backend offers: the top-k entries of one component for a query."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from arise.errors import AriseError
from arise.kb.loader import KnowledgeBase
from arise.kb.schema import Component, Entry


class RetrieverError(AriseError):
    """A retrieval backend that cannot be used (unknown, or its model is missing)."""


@dataclass(frozen=True)
class Hit:
    entry: Entry
    score: float


class Retriever(Protocol):
    """Ranks the entries of one component by how well they match a query."""

    name: str

    def search(self, query: str, component: Component | str, k: int = 2) -> list[Hit]: ...


def by_component(kb: KnowledgeBase) -> dict[Component, list[Entry]]:
    return {component: kb.of(component) for component in Component}
