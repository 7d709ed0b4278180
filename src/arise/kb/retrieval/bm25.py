"""BM25 retrieval (the default): no model, no download, milliseconds per query."""

from __future__ import annotations

import bm25s
import numpy as np

from arise.kb.loader import KnowledgeBase
from arise.kb.retrieval.base import Hit, by_component
from arise.kb.retrieval.text import terms
from arise.kb.schema import Component, Entry


def documents(entry: Entry) -> list[str]:
    """One document per description, each with the entry's tags: a paraphrase that
    matches well is not drowned by the others."""
    tags = " ".join(tag.replace("_", " ") for tag in entry.tags)
    return [f"{description} {tags}" for description in entry.descriptions]


class _Index:
    """One BM25 index over the descriptions of one component's entries."""

    def __init__(self, entries: list[Entry]):
        self.entries = entries
        self.owner: list[int] = []
        corpus: list[list[str]] = []
        for index, entry in enumerate(entries):
            for text in documents(entry):
                corpus.append(terms(text) or ["_empty_"])
                self.owner.append(index)
        whole = [terms(entry.search_text) or ["_empty_"] for entry in entries]
        self.vocabulary = {term for document in corpus for term in document}
        self.model = bm25s.BM25()
        self.whole = bm25s.BM25()
        if corpus:
            self.model.index(corpus, show_progress=False)
            self.whole.index(whole, show_progress=False)

    def search(self, query: str, k: int) -> list[Hit]:
        if not self.entries:
            return []
        wanted = [term for term in terms(query) if term in self.vocabulary]
        k = min(k, len(self.entries))
        if not wanted:
            return [Hit(entry, 0.0) for entry in self.entries[:k]]
        per_document = np.asarray(self.model.get_scores(wanted), dtype=float)
        # The best single paraphrase, plus the entry as a whole (all paraphrases and tags).
        scores = np.asarray(self.whole.get_scores(wanted), dtype=float)
        best = np.zeros(len(self.entries))
        for document, owner in enumerate(self.owner):
            best[owner] = max(best[owner], per_document[document])
        scores = scores + best
        order = sorted(range(len(self.entries)), key=lambda i: (-scores[i], i))[:k]
        return [Hit(self.entries[i], float(scores[i])) for i in order]


class BM25Retriever:
    """Lexical retrieval over each entry's descriptions and tags."""

    name = "bm25"

    def __init__(self, kb: KnowledgeBase):
        self.indexes = {
            component: _Index(entries) for component, entries in by_component(kb).items()
        }

    def search(self, query: str, component: Component | str, k: int = 2) -> list[Hit]:
        return self.indexes[Component(component)].search(query, k)
