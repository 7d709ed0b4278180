"""Hybrid retrieval: BM25 and embeddings fused by reciprocal rank.

Lexical matching is sharp on the domain words (kerb, red light, T-junction); embeddings
catch paraphrases with no word in common. Fusing the two rankings keeps both strengths.
"""

from __future__ import annotations

from arise.kb.retrieval.base import Hit, Retriever
from arise.kb.schema import Component

RRF_K = 60  # the usual damping constant of reciprocal-rank fusion


class HybridRetriever:
    name = "hybrid"

    def __init__(self, lexical: Retriever, semantic: Retriever, lexical_weight: float = 1.0):
        self.lexical, self.semantic, self.lexical_weight = lexical, semantic, lexical_weight

    def search(self, query: str, component: Component | str, k: int = 2) -> list[Hit]:
        depth = 1000  # rank every entry of the component
        fused: dict[str, float] = {}
        entries = {}
        for retriever, weight in ((self.lexical, self.lexical_weight), (self.semantic, 1.0)):
            for rank, hit in enumerate(retriever.search(query, component, depth)):
                fused[hit.entry.id] = fused.get(hit.entry.id, 0.0) + weight / (RRF_K + rank + 1)
                entries[hit.entry.id] = hit.entry
        order = sorted(fused, key=lambda i: -fused[i])[:k]
        return [Hit(entries[i], fused[i]) for i in order]
