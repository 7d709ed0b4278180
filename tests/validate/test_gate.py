"""The static gate on its own: an allow-list of what a script may name (no Scenic run)."""

from __future__ import annotations

import pytest
from scenic.syntax.parser import parse_string

from arise.validate.gate import scan_tokens, scan_tree

ALLOWED = """
Town = 'Town01'
param map = localPath(f'../maps/{Town}.xodr')
model scenic.simulators.carla.model
import math
import random
import numpy as np
from numpy import linalg
from scenic.simulators.carla.actions import *
class Helper:
    def __init__(self):
        self.value = math.pi + np.sqrt(2) + linalg.norm([3, 4]) + random.uniform(0, 1)
behavior Go():
    take SetThrottleAction(getattr(self, 'throttle', 0.5))
code = 3
label = f"speed {code:.1f}" + "{0} {name}".format(1, name=2)
here = network.laneSectionAt(ego)
left = here._laneToLeft if here is not None else None
ok = maneuver.type if False else np.random.normal(0, 1)
ego = new Car with behavior Go()
"""


def _refused(source: str) -> list[str]:
    return [r.what for r in scan_tree(parse_string(source, "exec"))]


def test_scenic_constructs_and_maths_pass() -> None:
    assert _refused(ALLOWED) == []


@pytest.mark.parametrize(
    ("source", "word"),
    [
        # the three escapes of issue 10
        ("import random\nrandom._os.system('touch /tmp/x')", "'._os' starts with '_'"),
        ("import statistics\nstatistics.sys.modules['os'].system('x')", "'statistics'"),
        ("import numpy\nnumpy.ctypeslib.ctypes.CDLL(None).system(b'x')", "'.ctypeslib'"),
        # module allow-lists
        ("import os", "'os'"),
        ("import subprocess as sp", "'subprocess'"),
        ("from socket import socket", "'socket'"),
        ("from . import secrets", "relative"),
        ("import typing", "'typing'"),
        ("import enum\nenum.sys", "'enum'"),
        ("import numpy as np\nnp.save('/tmp/x', [1])", "'.save'"),
        ("import numpy as np\nnp.lib.npyio", "'.lib'"),
        ("from numpy import savetxt", "'savetxt'"),
        ("from numpy import *", "import *"),
        ("import numpy as np\nnp.load('x.npy', allow_pickle=True)", "'.load'"),
        ("import numpy as np\nnp.array([1]).tofile('/tmp/x')", "'.tofile'"),
        ("import numpy as np\nnp.polyfit", "'numpy.polyfit' is not allowed"),
        ("import random\nrandom.SystemRandom", "'random.SystemRandom'"),
        ("import math\nx = math.floor(2)\nimport scenic.syntax.veneer", "'scenic.syntax.veneer'"),
        # names that Scenic's modules re-export, and builtins
        ("x = sys.modules", "'sys'"),
        ("x = pickle.loads(b'')", "'pickle'"),
        ("x = open('/etc/passwd').read()", "'open'"),
        ("eval('1+1')", "'eval'"),
        ("exec('x = 1')", "'exec'"),
        ("m = __import__('os')", "'__import__'"),
        ("t = type('X', (), {})", "'type'"),
        ("c = ().__class__.__bases__", "starts with '_'"),
        ("g = (lambda: 0).__globals__", "starts with '_'"),
        ("b = __builtins__", "'__builtins__'"),
        ("getattr(ego, '__dict__')", "starts with '_'"),
        ("getattr(ego, 'f_globals')", "reaches the interpreter"),
        ("name = 'x'\ngetattr(ego, name)", "computed"),
        (
            "import functools\nimport random\nfunctools.reduce(getattr, ['x', 'y'], random)",
            "passed around as a value",
        ),
        ("fetch = getattr\nfetch(ego, 'x')", "passed around as a value"),
        ("def f():\n    import sys\n    return sys", "'sys'"),
        ("frame = gen.gi_frame", "'.gi_frame'"),
        ("x = random._inst", "starts with '_'"),
        # format strings and annotations
        ("'{0.__init__.__globals__}'.format(ego)", "format fields"),
        ("'{0[x]}'.format({'x': 1})", "format fields"),
        ("t = '{0.x}'\nt.format(ego)", "string literal"),
        ("x: 'os.system(1)' = 1", "string annotations"),
        ("def f(a: 'sys') -> None:\n    pass", "string annotations"),
        ("def f() -> 'x':\n    pass", "string annotations"),
        # maps and models
        ("model os", "model 'os'"),
        ("model scenic.core.utils", "not a world model we know"),
        ("param map = '/etc/passwd'", "absolute"),
        ("param map = localPath('/root/.ssh/id_rsa.xodr')", "absolute"),
        ("param map = localPath('../secret.txt')", "not an OpenDRIVE map"),
        ("param map = localPath(name)", "one literal map path"),
        ("param map = '~/maps/x.xodr'", "absolute"),
        ("import scenic.simulators.carla.actions as a\nx = a._laneToLeft", "of a module"),
    ],
)
def test_refusals(source: str, word: str) -> None:
    refused = _refused(source)
    assert refused and any(word in what for what in refused), refused


def test_a_variable_may_share_a_module_name() -> None:
    assert _refused("code = 1\nutils = code + 1\nio = utils") == []


def test_token_fallback_for_text_that_does_not_parse() -> None:
    broken = (
        "model scenic.simulators.carla.model\nimport os\nego = Car at 3 4 5 (\n"
        "open('x')\nrandom._os\n"
    )
    found = scan_tokens(broken)
    assert [r.line for r in found] == [2, 4, 5]
    assert "'os'" in found[0].what and "'open'" in found[1].what and "_os" in found[2].what


def test_refusal_positions_are_one_based() -> None:
    refusal = scan_tree(parse_string("x = 1\ny = eval('2')", "exec"))[0]
    assert (refusal.line, refusal.column) == (2, 5)
