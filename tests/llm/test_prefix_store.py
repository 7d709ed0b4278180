"""The prefix store on its own: entries round-trip, damage is caught, the bound holds."""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

from arise.llm.prefix_store import PrefixStore, entry_key, file_sha256

TOKENS = [151644, 8948, 198, 2610, 525, 264]


def _store(tmp_path: Path, limit_mb: int = 8) -> PrefixStore:
    return PrefixStore(tmp_path / "store", limit_mb)


def test_an_entry_round_trips(tmp_path: Path) -> None:
    store = _store(tmp_path)
    key = entry_key("abc", {"n_ctx": 8192}, TOKENS)
    assert store.get(key, TOKENS) is None
    assert store.put(key, TOKENS, b"state bytes" * 100) == store.path(key)
    found = store.get(key, TOKENS)
    assert found is not None and found.state == b"state bytes" * 100
    assert found.tokens == tuple(TOKENS)
    assert not list(store.root.glob(".tmp-*")), "no temporary file left behind"


def test_the_key_depends_on_model_settings_and_every_token() -> None:
    base = entry_key("abc", {"n_ctx": 8192}, TOKENS)
    assert entry_key("abd", {"n_ctx": 8192}, TOKENS) != base
    assert entry_key("abc", {"n_ctx": 4096}, TOKENS) != base
    assert entry_key("abc", {"n_ctx": 8192}, [*TOKENS[:-1], 7]) != base
    assert entry_key("abc", {"n_ctx": 8192}, list(TOKENS)) == base


def test_a_damaged_entry_is_deleted_not_trusted(tmp_path: Path) -> None:
    store = _store(tmp_path)
    key = entry_key("abc", {}, TOKENS)
    path = store.put(key, TOKENS, bytes(range(256)) * 40)
    assert path is not None
    blob = bytearray(path.read_bytes())
    blob[-10] ^= 0xFF  # one flipped payload byte
    path.write_bytes(bytes(blob))
    assert store.get(key, TOKENS) is None
    assert not path.exists()
    assert store.discarded == [f"{path.name}: checksum mismatch"]


def test_truncated_foreign_and_mismatched_entries_are_refused(tmp_path: Path) -> None:
    store = _store(tmp_path)
    key = entry_key("abc", {}, TOKENS)
    path = store.put(key, TOKENS, b"x" * 5000)
    assert path is not None
    whole = path.read_bytes()
    path.write_bytes(whole[:-100])
    assert store.get(key, TOKENS) is None
    store.root.joinpath(f"{key}.kvstate").write_bytes(b"not ours at all")
    assert store.get(key, TOKENS) is None
    path.write_bytes(whole)  # the right file, asked for with other tokens
    assert store.get(key, [*TOKENS, 1]) is None
    assert [note.split(": ", 1)[1] for note in store.discarded] == [
        "truncated",
        "not a prefix-store entry",
        "written for other tokens or settings",
    ]


def test_the_size_bound_drops_the_least_recently_used(tmp_path: Path) -> None:
    store = _store(tmp_path, limit_mb=1)
    payload = b"k" * 400_000
    keys = [entry_key("m", {}, [i]) for i in range(3)]
    store.put(keys[0], [0], payload)
    store.put(keys[1], [1], payload)
    old = store.path(keys[0]).stat().st_mtime - 100
    os.utime(store.path(keys[1]), (old - 100, old - 100))
    os.utime(store.path(keys[0]), (old, old))  # 0 was used after 1
    store.put(keys[2], [2], payload)
    assert store.size_bytes() <= 1 << 20
    assert store.get(keys[1], [1]) is None, "the least recently used entry goes first"
    assert store.get(keys[0], [0]) is not None and store.get(keys[2], [2]) is not None
    assert store.put(entry_key("m", {}, [9]), [9], b"z" * (2 << 20)) is None, "too big"
    assert store.clear() == 2 and store.entries() == []


def test_the_model_hash_is_computed_once_per_file_version(tmp_path: Path) -> None:
    model = tmp_path / "model.gguf"
    model.write_bytes(b"weights" * 1000)
    expected = hashlib.sha256(model.read_bytes()).hexdigest()
    assert file_sha256(model, tmp_path / "store") == expected
    memo = tmp_path / "store" / "model-hashes.json"
    assert expected in memo.read_text()
    model.write_bytes(b"other weights")
    os.utime(model, ns=(1, 1))  # a new mtime: the memo no longer applies
    assert file_sha256(model, tmp_path / "store") == hashlib.sha256(b"other weights").hexdigest()
