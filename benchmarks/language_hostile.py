"""How long the language layer takes on hostile descriptions at the size limit.

Run:  .venv/bin/python benchmarks/language_hostile.py [--limit 30]

A description is user input. Every reading rule compiles to a regular expression, so a
description made to make one backtrack (long runs of hyphens, commas, numbers, pronouns,
names) could stall extraction. Each shape here is read in full (`read_description`: the
cast, clauses, pronouns and every rule of every fact) in a child process stopped after
--limit seconds, after one warm-up read that loads the rules; the table gives the time of
the second read. Linear readers take milliseconds at 2,000 characters.
"""

from __future__ import annotations

import argparse
import multiprocessing
import time

from arise.generate.extract import MAX_DESCRIPTION_CHARS


def descriptions(size: int) -> dict[str, str]:
    """Hostile descriptions of `size` characters, by name."""
    return {
        "verb, then hyphens": ("stop " + "a-" * size)[:size],
        "hyphens": ("a-" * size)[:size],
        "commas": ("a, " * size)[:size],
        "articles": ("the " * size)[:size],
        "sides": ("left " * size)[:size],
        "numbered parties": ("V1 " * size)[:size],
        "years and names": ("2017 Abc " * size)[:size],
        "pronouns": ("it, " * size)[:size],
        "one long word": "a" * size,
        "parked and hyphenated": (("parked " + "x-y " * 10) * size)[:size],
        "digits and units": ("20m " * size)[:size],
        "possessives": ("the ego's " * size)[:size],
    }


def _read(text: str, queue: multiprocessing.Queue[float]) -> None:
    from arise.language.readers import read_description

    read_description("The ego turns left.")  # loads the rules
    started = time.perf_counter()
    read_description(text)
    queue.put(time.perf_counter() - started)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limit", type=float, default=30.0)
    args = parser.parse_args()
    print(f"| description ({MAX_DESCRIPTION_CHARS} characters) | seconds |")
    print("|---|---|")
    for name, text in descriptions(MAX_DESCRIPTION_CHARS).items():
        queue: multiprocessing.Queue[float] = multiprocessing.Queue()
        child = multiprocessing.Process(target=_read, args=(text, queue))
        child.start()
        child.join(args.limit)
        if child.is_alive():
            child.kill()
            print(f"| {name} | over {args.limit:.0f} |")
        else:
            print(f"| {name} | {queue.get():.3f} |")


if __name__ == "__main__":
    main()
