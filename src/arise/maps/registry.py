"""Which map file a script runs on.

A script names its map (`param map = ...`, `Town = 'Town05'`, `param carla_map = ...`).
We resolve that name against the maps we ship and, with --map-dir, the CARLA towns;
a town we do not have is replaced by an available map with the features it is known for,
and the choice says so. Map files are copied into the user cache (`arise.maps.cache`),
because Scenic writes a `.snet` cache next to the map and the map folder may be read-only;
the path in a choice is always that copy.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from arise.maps.cache import cached_copy
from arise.maps.choice import MapChoice, is_safe_map_name
from arise.maps.errors import MapError

__all__ = ["MapChoice", "MapEntry", "MapError", "MapRegistry", "cached_copy"]

DEFAULT_MAP = "arise_intersection4"
GENERIC_NEEDS = ("intersection4", "signalized", "multilane", "sidewalk")
MAP_DIR_ENV = "ARISE_MAP_DIR"


@dataclass(frozen=True)
class MapEntry:
    name: str
    path: Path | None
    features: frozenset[str] = field(default_factory=frozenset)
    description: str = ""
    source: str = "builtin"  # builtin | map-dir | catalogue (known but not present)


def _load_catalogue(filename: str) -> dict[str, dict[str, Any]]:
    try:
        raw = resources.files("arise.maps").joinpath("data", filename).read_text("utf-8")
    except (FileNotFoundError, OSError):
        return {}
    data = json.loads(raw)
    entries = data.values() if isinstance(data, dict) and "name" not in data else data
    if isinstance(data, dict) and "maps" in data:
        entries = data["maps"]
    return {entry["name"]: entry for entry in entries if isinstance(entry, dict)}


def builtin_data_dir() -> Path:
    return Path(str(resources.files("arise.maps").joinpath("data")))


class MapRegistry:
    """All maps a check may use, looked up by name."""

    def __init__(self, map_dir: str | os.PathLike[str] | None = None):
        if map_dir is None:
            map_dir = os.environ.get(MAP_DIR_ENV) or None
        self.map_dir = Path(map_dir).expanduser() if map_dir else None
        self.entries: dict[str, MapEntry] = {}
        towns = _load_catalogue("carla_towns.json")
        self.known_features = {name: frozenset(e.get("features", ())) for name, e in towns.items()}
        data_dir = builtin_data_dir()
        for name, entry in _load_catalogue("maps.json").items():
            path = data_dir / entry.get("file", f"{name}.xodr")
            if path.exists():
                self.entries[name] = MapEntry(
                    name,
                    path,
                    frozenset(entry.get("features", ())),
                    entry.get("description", ""),
                    "builtin",
                )
        if self.map_dir is not None:
            if not self.map_dir.is_dir():
                raise MapError(f"map folder {self.map_dir} does not exist")
            for link in sorted(self.map_dir.glob("*.xodr")):
                name = link.stem
                if not is_safe_map_name(name):
                    continue  # a name that cannot be a file stem everywhere we write it
                # The user's own folder: a link in it is the user's choice of file.
                path = link.resolve() if link.is_symlink() else link
                features = self.known_features.get(name, frozenset())
                description = towns.get(name, {}).get("description", "")
                self.entries[name] = MapEntry(name, path, features, description, "map-dir")

    def exact(self, name: str) -> MapChoice | None:
        """The map of exactly this name, copied into the cache; None when it is not here
        (no substitute: a saved trace must be shown on the map it ran on)."""
        entry = self.entries.get(name)
        if entry is None or entry.path is None:
            return None
        return MapChoice(
            requested=name, name=entry.name, path=str(cached_copy(entry.path, entry.name))
        )

    def names(self) -> list[str]:
        return sorted(self.entries)

    def features_wanted(self, requested: str | None) -> frozenset[str]:
        if requested and requested in self.known_features:
            return self.known_features[requested]
        return frozenset(GENERIC_NEEDS)

    def best_match(self, wanted: frozenset[str], exclude: str | None = None) -> MapEntry:
        """The available map sharing most of the wanted features (CARLA towns win ties)."""
        candidates = [e for e in self.entries.values() if e.name != exclude]
        if not candidates:
            raise MapError(
                "no maps are available: the package data is missing and no --map-dir was given"
            )

        def score(entry: MapEntry) -> tuple[int, int, int, str]:
            shared = len(wanted & entry.features)
            extra = len(entry.features - wanted)
            return (shared, 1 if entry.source == "map-dir" else 0, -extra, entry.name)

        return max(candidates, key=score)

    def resolve(
        self,
        requested: str | None,
        requested_file: str | None = None,
        script_dir: Path | None = None,
    ) -> MapChoice:
        """Choose the map for a script and copy it into the cache."""
        if requested_file:
            for candidate in _file_candidates(requested_file, script_dir):
                if candidate.is_file():
                    return MapChoice(
                        requested=requested_file,
                        name=candidate.stem,
                        path=str(cached_copy(candidate)),
                    )
        if requested and requested in self.entries:
            entry = self.entries[requested]
            assert entry.path is not None
            return MapChoice(
                requested=requested, name=entry.name, path=str(cached_copy(entry.path, entry.name))
            )
        if requested is None:
            entry = self.entries.get(DEFAULT_MAP) or self.best_match(frozenset(GENERIC_NEEDS))
            assert entry.path is not None
            return MapChoice(
                requested=None,
                name=entry.name,
                path=str(cached_copy(entry.path, entry.name)),
                substituted=True,
                reason=f"the script names no map; used {entry.name}",
            )
        wanted = self.features_wanted(requested)
        entry = self.best_match(wanted)
        assert entry.path is not None
        shared = sorted(wanted & entry.features)
        known = "known features" if requested in self.known_features else "assumed features"
        return MapChoice(
            requested=requested,
            name=entry.name,
            path=str(cached_copy(entry.path, entry.name)),
            substituted=True,
            reason=(
                f"map {requested} is not available here; substituted {entry.name}, which "
                f"has {', '.join(shared) or 'none'} of its {known} "
                f"({', '.join(sorted(wanted))})"
            ),
        )


def _file_candidates(name: str, script_dir: Path | None) -> list[Path]:
    path = Path(name).expanduser()
    if path.is_absolute():
        return [path]
    found = [path]
    if script_dir is not None:
        found.insert(0, script_dir / path)
    return found
