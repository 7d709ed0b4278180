"""How long the readers of a script take on adversarial scripts at the size limit.

Run:  .venv/bin/python benchmarks/parent_parse.py [--kib 256] [--limit 60]

A script is untrusted text. The parent reads it before any worker does (its model line
and map: `script_info`; its sections: `sections`) and again in the judge and the search
(`compact_script`, `find_free_params`); the worker's static gate reads it before Scenic
compiles it. Each reader runs here on scripts made to make regular expressions backtrack
(long runs of spaces, thousands of blank lines or params, unterminated quotes, braces,
markers that never close), each in a child process stopped after --limit seconds, and
the table says how long each took. Linear readers take milliseconds at 256 KiB; a
quadratic one takes minutes (`script_info` before issue 27: 49 s at 40 KB).
"""

from __future__ import annotations

import argparse
import multiprocessing
import time
from collections.abc import Callable
from pathlib import Path

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "pedestrian_crossing.scenic"
MODEL = "model scenic.simulators.carla.model\n"


def scripts(size: int) -> dict[str, str]:
    """Adversarial scripts of about `size` characters, by name."""
    example = EXAMPLE.read_text(encoding="utf-8")
    return {
        "real script, repeated": (example * (size // len(example) + 1))[:size],
        "blank lines": "\n" * size + MODEL,
        "one line of spaces": " " * size + "x\n",
        "spaces in a param": "param weather = a" + " " * size + "b\n",
        "spaces after =": "x =" + " " * size + "\n",
        "many params": "".join(f"param p{i} = {i}\n" for i in range(size // 16)),
        "many 'name:' lines": "a:\n" * (size // 3),
        "unterminated quote": "x = '" + "a" * size + "\n",
        "open braces in a map": "param map = f'" + "{" * size + ".xodr'\n",
        "Town + digits": "t = 'Town" + "1" * size + "!'\n",
        "long identifier": "a" * size + " = 1\n",
        "unclosed sections": "".join(f"# BEGIN S{i}\n" for i in range(size // 24))
        + "".join(f"# END T{i}\n" for i in range(size // 24)),
        "nested parentheses": "x = " + "(" * size + "\n",
        "inline comment after spaces": "x = 1" + " " * size + "y # c\n",
    }


def _script_info(text: str) -> None:
    from arise.validate.script_info import read_script_info

    read_script_info(text)


def _sections(text: str) -> None:
    from arise.sections import find_sections, sections_by_line

    find_sections(text)
    sections_by_line(text)


def _judge(text: str) -> None:
    from arise.evaluate.judge import compact_script

    compact_script(text)


def _search(text: str) -> None:
    from arise.evaluate.search.space import find_free_params

    find_free_params(text)


def _gate(text: str) -> None:
    """The worker's static gate as the worker runs it: on the tree Scenic parses, or on
    the tokens when the text does not parse."""
    from scenic.core.errors import ScenicSyntaxError
    from scenic.syntax.parser import parse_string

    from arise.validate import gate

    gate.warm()
    try:
        tree = parse_string(text, "exec", filename="bench.scenic")
    except (ScenicSyntaxError, SyntaxError, RecursionError, MemoryError):
        gate.scan_tokens(text)
        return
    gate.scan_tree(tree)


READERS: dict[str, Callable[[str], None]] = {
    "script_info": _script_info,
    "sections": _sections,
    "judge": _judge,
    "search": _search,
    "gate (+parse)": _gate,
}


def _child(reader: str, text: str, out: multiprocessing.Queue) -> None:  # type: ignore[type-arg]
    READERS[reader]("x")  # imports and warm-up outside the clock
    started = time.perf_counter()
    try:
        READERS[reader](text)
    except Exception as error:  # noqa: BLE001  (a reader's own error is a result too)
        out.put(f"{type(error).__name__}")
        return
    out.put(time.perf_counter() - started)


def measure(reader: str, text: str, limit: float) -> str:
    """The reader's time on `text` in a fresh process, or how it failed."""
    queue: multiprocessing.Queue = multiprocessing.Queue()  # type: ignore[type-arg]
    child = multiprocessing.Process(target=_child, args=(reader, text, queue))
    child.start()
    deadline = time.monotonic() + limit + 30  # imports of Scenic come first
    while child.is_alive() and queue.empty() and time.monotonic() < deadline:
        time.sleep(0.05)
    if queue.empty():
        child.terminate()
        child.join()
        return f">{limit:.0f} s"
    result = queue.get()
    child.join()
    if isinstance(result, str):
        return result
    return f"{result * 1000:.0f} ms" if result < 10 else f"{result:.0f} s"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kib", type=int, default=256, help="size of each script")
    parser.add_argument("--limit", type=float, default=60.0, help="seconds per reader")
    args = parser.parse_args()
    cases = scripts(args.kib * 1024)
    width = max(len(name) for name in cases)
    print(
        f"{'script (' + str(args.kib) + ' KiB)':<{width}}  "
        + "  ".join(f"{r:>13}" for r in READERS)
    )
    for name, text in cases.items():
        cells = [measure(reader, text, args.limit) for reader in READERS]
        print(f"{name:<{width}}  " + "  ".join(f"{c:>13}" for c in cells), flush=True)


if __name__ == "__main__":
    main()
