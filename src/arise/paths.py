"""Where arise keeps files that are not the user's: caches and configuration."""

from __future__ import annotations

import os
from pathlib import Path

import platformdirs


def cache_dir() -> Path:
    """User cache folder (override with ARISE_CACHE_DIR); created on first use."""
    override = os.environ.get("ARISE_CACHE_DIR")
    # absolute: the validator's workers and map preparation run from other folders
    folder = (
        Path(override).expanduser().resolve()
        if override
        else Path(platformdirs.user_cache_dir("arise"))
    )
    folder.mkdir(parents=True, exist_ok=True)
    return folder


def config_path() -> Path:
    """The user's config file: $ARISE_CONFIG, or <user config dir>/arise/config.toml."""
    override = os.environ.get("ARISE_CONFIG")
    if override:
        return Path(override).expanduser()
    return Path(platformdirs.user_config_dir("arise")) / "config.toml"
