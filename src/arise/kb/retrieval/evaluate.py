"""Measuring retrieval: top-1 and top-k accuracy per component on the labeled query set."""

from __future__ import annotations

from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

import yaml
from pydantic import BaseModel, Field

from arise.kb.retrieval.base import Retriever
from arise.kb.schema import Component


class LabeledQuery(BaseModel):
    component: Component
    text: str
    expected: list[str] = Field(min_length=1)


def default_set_path() -> Path:
    return Path(str(resources.files("arise.kb") / "eval" / "retrieval_set.yaml"))


def load_queries(path: Path | None = None) -> list[LabeledQuery]:
    data = yaml.safe_load((path or default_set_path()).read_text(encoding="utf-8"))
    return [LabeledQuery.model_validate(item) for item in data["queries"]]


@dataclass
class ComponentScore:
    queries: int = 0
    top1: int = 0
    topk: int = 0
    misses: list[str] = field(default_factory=list)

    def rate(self, hits: int) -> float:
        return hits / self.queries if self.queries else 0.0


def evaluate(
    retriever: Retriever, queries: list[LabeledQuery], k: int = 2
) -> dict[Component, ComponentScore]:
    """Per component: how often the first hit, and any of the top k, is an expected entry."""
    scores: dict[Component, ComponentScore] = {}
    for query in queries:
        score = scores.setdefault(query.component, ComponentScore())
        hits = [hit.entry.id for hit in retriever.search(query.text, query.component, k)]
        score.queries += 1
        score.top1 += bool(hits and hits[0] in query.expected)
        if set(hits) & set(query.expected):
            score.topk += 1
        else:
            score.misses.append(f"{query.text!r}: got {hits}, expected {query.expected}")
    return scores
