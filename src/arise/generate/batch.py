"""Many runs of the generator in one process: what `arise generate` does with its options.

The command line parses its options into a `BatchRequest`, calls `run_batch` and prints
the typed events it sends and the `Batch` it returns; a script or a notebook can do the
same without the command line. One `Generator` serves every run, so the model, the
knowledge base and the validator workers load once.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from arise.errors import AriseError
from arise.generate.events import ProgressEvent
from arise.generate.extract import check_description
from arise.generate.options import GenerateOptions
from arise.generate.pipeline import Generator, slug
from arise.generate.run import Generation, RunStatus


class DescriptionError(AriseError):
    """No description to run, a descriptions file that cannot be read, or a description
    that is not a driving scenario (said before anything loads)."""


@dataclass(frozen=True)
class BatchRequest:
    """What to generate: `description` and/or the lines of `file`, `count` runs of each."""

    description: str | None
    out: Path
    options: GenerateOptions
    file: Path | None = None
    count: int = 1
    #: Refuse a lone description that is no driving scenario before the model, the KB or a
    #: validator worker loads (off for --json, whose report says the refusal instead).
    refuse_early: bool = True


@dataclass(frozen=True)
class RunStarted:
    """A run begins; its files go to `folder`."""

    folder: Path


@dataclass(frozen=True)
class RunProgress:
    """The run writing to `folder` moved on (a stage began, an attempt was checked)."""

    folder: Path
    event: ProgressEvent


@dataclass(frozen=True)
class RunDone:
    """A run ended (executable or not); its files are in `folder`."""

    folder: Path
    run: Generation


BatchEvent = RunStarted | RunProgress | RunDone
OnBatchEvent = Callable[[BatchEvent], None]


@dataclass
class Batch:
    """Every run of a request, in order. `single`: one description, one run, written to
    the output folder itself rather than a sub-folder."""

    single: bool
    runs: list[RunDone] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return all(done.run.ok for done in self.runs)

    @property
    def executed(self) -> int:
        return sum(done.run.ok for done in self.runs)

    @property
    def refusal(self) -> str | None:
        """Why the lone description was refused, if it was (a usage error, not a failure)."""
        if self.single and self.runs and self.runs[0].run.status is RunStatus.REFUSED:
            return self.runs[0].run.message
        return None


def read_descriptions(text: str | None, file: Path | None) -> list[tuple[str, str]]:
    """(id, description) pairs from the argument and/or a .txt (one per line) or .jsonl file
    ({"description", "id"?} per line); blank lines and lines starting with # are skipped."""
    found: list[tuple[str, str]] = []
    if text is not None:
        found.append((slug(text), text))
    if file is None:
        return found
    if not file.is_file():
        raise DescriptionError(f"no such file: {file}")
    try:
        lines = file.read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError) as error:
        raise DescriptionError(f"cannot read {file}: {error}") from None
    for number, line in enumerate(lines, 1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        if file.suffix == ".jsonl":
            try:
                row = json.loads(line)
            except json.JSONDecodeError as error:
                raise DescriptionError(f"{file}:{number}: not JSON ({error.msg})") from None
            if not isinstance(row, dict):
                raise DescriptionError(f"{file}:{number}: not a JSON object")
            description = str(row.get("description", ""))
            ident = str(row.get("id") or f"{number:03d}-{slug(description)}")
        else:
            description, ident = line.strip(), f"{number:03d}-{slug(line)}"
        found.append((ident, description))
    return found


def run_batch(request: BatchRequest, on_event: OnBatchEvent | None = None) -> Batch:
    """Generate every description `count` times; run i of a description uses seed + i.

    Raises DescriptionError before anything loads for no description, an unreadable file
    or (with `refuse_early`) a lone description that is no driving scenario; bad KB or map
    folders raise their own AriseError. A failed run is not an error: its `Generation`
    says why."""
    descriptions = read_descriptions(request.description, request.file)
    if not descriptions:
        raise DescriptionError("give a description or --file")
    batch = Batch(single=len(descriptions) == 1 and request.count == 1)
    if batch.single and request.refuse_early:
        refusal = check_description(descriptions[0][1])
        if refusal:
            raise DescriptionError(refusal)
    options = request.options
    with Generator(options) as generator:
        for ident, text in descriptions:
            for index in range(request.count):
                folder = _folder(request, batch.single, ident, index)
                seed = None if options.seed is None else options.seed + index
                generator.reconfigure(options.model_copy(update={"run_index": index, "seed": seed}))
                if on_event is not None:
                    on_event(RunStarted(folder))
                run = generator.generate(text, folder, _forward(folder, on_event))
                done = RunDone(folder, run)
                batch.runs.append(done)
                if on_event is not None:
                    on_event(done)
    return batch


def _folder(request: BatchRequest, single: bool, ident: str, index: int) -> Path:
    if single:
        return request.out
    return request.out / (ident if request.count == 1 else f"{ident}/run-{index}")


def _forward(folder: Path, on_event: OnBatchEvent | None) -> Callable[[ProgressEvent], None] | None:
    if on_event is None:
        return None
    listener = on_event

    def forward(event: ProgressEvent) -> None:
        listener(RunProgress(folder, event))

    return forward
