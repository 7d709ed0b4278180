"""Benchmark prompt files: JSONL, CSV or plain text, each prompt with an optional category."""

from __future__ import annotations

import csv
import json
from dataclasses import dataclass
from pathlib import Path

from arise.errors import AriseError

UNCATEGORISED = "uncategorised"


@dataclass(frozen=True)
class BenchPrompt:
    id: str
    description: str
    category: str = UNCATEGORISED
    # Hand-written truth (a dev-set line's "truth", as canonical JSON): runs of this prompt
    # get a fidelity score read from their traces against it.
    truth: str | None = None


class PromptFileError(AriseError):
    """A prompt file we cannot read, with the file and line in the message."""


def _prompt(
    index: int, description: object, category: object, prompt_id: object, where: str
) -> BenchPrompt:
    if not isinstance(description, str) or not description.strip():
        raise PromptFileError(f"{where}: no description")
    return BenchPrompt(
        id=str(prompt_id or f"p{index:03d}").strip(),
        description=description.strip(),
        category=str(category or UNCATEGORISED).strip() or UNCATEGORISED,
    )


def _with_truth(prompt: BenchPrompt, truth: object, where: str) -> BenchPrompt:
    from dataclasses import replace

    from arise.evaluate.fidelity import parse_truth

    parse_truth(truth, where)  # DevsetError (an AriseError) names what is wrong
    return replace(prompt, truth=json.dumps(truth, sort_keys=True))


def read_prompts(path: Path) -> list[BenchPrompt]:
    """Prompts in file order. JSONL rows: {"description" (or "text"), "category"?, "id"?,
    "truth"? (hand-written facts, as in src/arise/evaluate/devsets)}; CSV with a
    header holding `description` (and optionally `category`, `id`); TXT: one description
    per line, or `category<TAB>description`; blank lines and `#` comments are skipped."""
    if not path.is_file():
        raise PromptFileError(f"{path}: no such file")
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise PromptFileError(f"{path}: cannot read it ({error})") from error
    prompts: list[BenchPrompt] = []
    suffix = path.suffix.lower()
    if suffix in (".jsonl", ".json"):
        for number, line in enumerate(text.splitlines(), 1):
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            try:
                row = json.loads(line)
            except json.JSONDecodeError as error:
                raise PromptFileError(f"{path}:{number}: not JSON ({error.msg})") from error
            if not isinstance(row, dict):
                raise PromptFileError(f"{path}:{number}: expected an object per line")
            prompt = _prompt(
                len(prompts) + 1,
                row.get("description", row.get("text")),
                row.get("category"),
                row.get("id"),
                f"{path}:{number}",
            )
            if row.get("truth") is not None:
                prompt = _with_truth(prompt, row["truth"], f"{path}:{number}")
            prompts.append(prompt)
    elif suffix == ".csv":
        reader = csv.DictReader(text.splitlines())
        if not reader.fieldnames or "description" not in reader.fieldnames:
            raise PromptFileError(f"{path}: the CSV needs a header with a 'description' column")
        for number, row in enumerate(reader, 2):
            prompts.append(
                _prompt(
                    len(prompts) + 1,
                    row.get("description"),
                    row.get("category"),
                    row.get("id"),
                    f"{path}:{number}",
                )
            )
    else:
        for number, line in enumerate(text.splitlines(), 1):
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            category, _, description = line.rpartition("\t")
            prompts.append(
                _prompt(len(prompts) + 1, description, category or None, None, f"{path}:{number}")
            )
    if not prompts:
        raise PromptFileError(f"{path}: no prompts in it")
    seen: set[str] = set()
    for prompt in prompts:
        if prompt.id in seen:
            raise PromptFileError(f"{path}: the id '{prompt.id}' is used twice")
        seen.add(prompt.id)
    return prompts
