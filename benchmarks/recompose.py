"""Bench runs with their KB sections written again from the current knowledge base.

A change to a KB entry (a new range, a later commit) reaches the generated scripts only
when they are generated again, which needs the model. This copies the run folders of an
`arise bench` output and rewrites, in each run's `scenario.scenic`, the text under every
`# kb: <id>` mark of the chosen components with that entry's current snippet (placeholders
filled as the composer fills them, an `as actor2` copy renamed as `arise.kb.actors` does),
so that `benchmarks/search.py` or `devset_reach.py` can measure the change on the same
scenes first.

The run's own parameter values (report.json `params`: stated speeds, the model's tuning)
are written into the new text again, except the trigger ranges a timing word narrowed
("at the last moment"): those are narrowed again from the entry's current range, as
`generate/timing.py` does. An entry id the KB no longer has is left as it was.

Run:  .venv/bin/python benchmarks/recompose.py out/s37-short out/s38-short
          [--components behavior,spawn] [--kb-dir DIR]
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import sys
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from arise.errors import AriseError
from arise.generate.timing import TRIGGER_PARAMS, timed_params
from arise.kb.actors import for_actor
from arise.kb.compose import ENTRY_MARK, fill_placeholders
from arise.kb.loader import KnowledgeBase, load_kb
from arise.kb.schema import Component
from arise.sections import MarkerKind, parse_marker
from arise.vocabulary import ActorClass, Timing

SCRIPT = "scenario.scenic"
_NEW = re.compile(r"^\s*(\w+)\s*=\s*new\s+(\w+)\b", re.M)
_PARAM = re.compile(r"^param\s+(OPT_\w+)\s*=")


class RecomposeError(AriseError):
    """A folder or a script cannot be recomposed (named in the message)."""


@dataclass
class Tally:
    scripts: int = 0
    replaced: int = 0
    kept: list[str] = field(default_factory=list)  # "run: entry [as actor]", left as it was


def classes_of(script: str) -> dict[str, str]:
    """Each placed object's Scenic class by its name (`adversary = new Car ...`)."""
    return {name: cls for name, cls in _NEW.findall(script)}


def entry_text(
    kb: KnowledgeBase, entry_id: str, actor: str | None, classes: dict[str, str]
) -> str | None:
    """The current snippet for one mark, or None when it cannot be written again."""
    if entry_id not in kb:
        return None
    entry = kb.get(entry_id)
    if actor is not None:
        cls = ActorClass.of(classes.get(actor, ""))
        if cls is None:
            return None
        entry = for_actor(entry, actor, cls)
    values = {}
    adversary = classes.get("adversary")
    if adversary is not None:
        values["ADVERSARY_CLASS"] = adversary
    try:
        return fill_placeholders(entry.snippet.rstrip("\n"), values, entry.label)
    except AriseError:
        return None


def run_params(report: dict[str, object], kb: KnowledgeBase, script: str) -> dict[str, str]:
    """The values the run gave its parameters, trigger ranges narrowed again by its timing
    word from the adversary's current entries."""
    given = report.get("params")
    params = {str(k): str(v) for k, v in given.items()} if isinstance(given, dict) else {}
    spec = report.get("spec")
    timing = spec.get("timing") if isinstance(spec, dict) else None
    if timing in {t.value for t in Timing}:
        own_entries = []
        for line in script.splitlines():
            mark = ENTRY_MARK.match(line)
            if mark and mark.group(2) is None and mark.group(1) in kb:
                own_entries.append(kb.get(mark.group(1)))
        params = {k: v for k, v in params.items() if k not in TRIGGER_PARAMS}
        params |= timed_params(Timing(str(timing)), own_entries)
    return params


def recompose(
    script: str,
    kb: KnowledgeBase,
    components: set[Component],
    run: str,
    tally: Tally,
    params: dict[str, str] | None = None,
) -> str:
    """The script with each chosen mark's body replaced by the entry's current text (its
    `param OPT_*` lines set to `params` where given)."""
    params = params or {}
    sections = {c.section: c for c in components}
    classes = classes_of(script)
    out: list[str] = []
    section: str | None = None
    skipping = False
    for line in script.splitlines():
        marker = parse_marker(line)
        mark = ENTRY_MARK.match(line)
        if marker is not None:
            section = marker.name if marker.kind is MarkerKind.BEGIN else None
            skipping = False
        elif mark is not None and section in sections:
            entry_id, actor = mark.group(1), mark.group(2)
            text = None
            # A copy's spawn is shifted by its place in a row (unknown here): kept.
            if not (actor is not None and sections[section] is Component.SPAWN):
                text = entry_text(kb, entry_id, actor, classes)
            out.append(line)
            if text is None:
                tally.kept.append(f"{run}: {mark.group(0)[6:]}")
                skipping = False
            else:
                for new in text.splitlines():
                    name = _PARAM.match(new)
                    if name and actor is None and name.group(1) in params:
                        new = f"param {name.group(1)} = {params[name.group(1)]}"
                    out.append(new)
                tally.replaced += 1
                skipping = True
            continue
        if not skipping:
            out.append(line)
    return "\n".join(out) + "\n"


def copy_bench(source: Path, target: Path, kb: KnowledgeBase, components: set[Component]) -> Tally:
    if not (source / "runs").is_dir():
        raise RecomposeError(f"{source}: not an `arise bench` output (no runs/ folder)")
    if target.exists():
        raise RecomposeError(f"{target}: exists; give a new folder")
    shutil.copytree(source, target, ignore=shutil.ignore_patterns("*.gif", "*.html", "attempts"))
    tally = Tally()
    for path in sorted(target.glob(f"runs/*/*/{SCRIPT}")):
        run = str(path.parent.relative_to(target / "runs"))
        script = path.read_text()
        report = path.parent / "report.json"
        params = run_params(json.loads(report.read_text()), kb, script) if report.exists() else {}
        path.write_text(recompose(script, kb, components, run, tally, params))
        tally.scripts += 1
    return tally


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("source", type=Path)
    parser.add_argument("target", type=Path)
    parser.add_argument("--components", default="behavior,spawn")
    parser.add_argument("--kb-dir", action="append", default=[])
    args = parser.parse_args(argv)
    try:
        components = {Component(c.strip()) for c in args.components.split(",") if c.strip()}
    except ValueError:
        print(f"--components: choose from {', '.join(c.value for c in Component)}")
        return 2
    try:
        tally = copy_bench(args.source, args.target, load_kb(args.kb_dir), components)
    except AriseError as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    print(f"{args.target}: {tally.scripts} scripts, {tally.replaced} sections written again")
    for kept in tally.kept:
        print(f"  kept as it was: {kept}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
