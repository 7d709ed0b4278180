"""The static gate on its own: what it refuses and what it lets through (no Scenic run)."""

from __future__ import annotations

import pytest
from scenic.syntax.parser import parse_string

from arise.validate.gate import scan_tokens, scan_tree

ALLOWED = """
param map = localPath('maps/Town01.xodr')
model scenic.simulators.carla.model
import math
from scenic.simulators.carla.actions import *
class Helper:
    def __init__(self):
        self.value = math.pi
behavior Go():
    take SetThrottleAction(getattr(self, 'throttle', 0.5))
ego = new Car with behavior Go()
"""


def _refused(source: str) -> list[str]:
    return [r.what for r in scan_tree(parse_string(source, "exec"))]


def test_scenic_constructs_pass() -> None:
    assert _refused(ALLOWED) == []


@pytest.mark.parametrize(("source", "word"), [
    ("import os", "'os'"),
    ("import subprocess as sp", "'subprocess'"),
    ("from socket import socket", "'socket'"),
    ("from . import secrets", "relative"),
    ("import urllib.request", "'urllib.request'"),
    ("model os", "model 'os'"),
    ("x = open('/etc/passwd').read()", "'open'"),
    ("eval('1+1')", "'eval'"),
    ("exec('x = 1')", "'exec'"),
    ("m = __import__('os')", "'__import__'"),
    ("c = ().__class__.__bases__", "dunder"),
    ("g = (lambda: 0).__globals__", "dunder"),
    ("b = __builtins__", "__builtins__"),
    ("getattr(ego, '__dict__')", "private attribute"),
    ("name = 'x'\ngetattr(ego, name)", "computed"),
    ("def f():\n    import sys\n    return sys", "'sys'"),
    ("frame = gen.gi_frame", "frame attribute"),
])
def test_refusals(source: str, word: str) -> None:
    refused = _refused(source)
    assert refused and any(word in what for what in refused), refused


def test_token_fallback_for_text_that_does_not_parse() -> None:
    broken = "import os\nego = Car at 3 4 5 (\nopen('x')\n"
    found = scan_tokens(broken)
    assert [r.line for r in found] == [1, 3]
    assert "'os'" in found[0].what and "'open'" in found[1].what


def test_refusal_positions_are_one_based() -> None:
    refusal = scan_tree(parse_string("x = 1\ny = eval('2')", "exec"))[0]
    assert (refusal.line, refusal.column) == (2, 5)
