"""The static gate on its own: an allow-list of what a script may name (no Scenic run)."""

from __future__ import annotations

import builtins
import math
import operator
import string
import sys
import typing
from pathlib import Path

import numpy
import pytest
from scenic.syntax.parser import parse_string

from arise.validate import identity
from arise.validate.gate import model_refusal, module_exists, scan_tokens, scan_tree

ALLOWED = """
Town = 'Town01'
param map = localPath(f'../maps/{Town}.xodr')
model scenic.simulators.carla.model
import math
import random
import numpy as np
from scenic.simulators.carla.actions import *
from numpy import linalg
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


# Issue 27: names are judged by what they are, not by how they are spelled.
@pytest.mark.parametrize(
    ("source", "word"),
    [
        # public names of Scenic's modules that are other modules
        ("from scenic.domains.driving.roads import enum", "the module 'enum'"),
        ("import scenic.domains.driving.roads as roads\nh = roads.hashlib.md5", "'hashlib'"),
        (
            "import scenic.simulators.carla.simulator as sim\np = sim.errors.pdb",
            "'scenic.core.errors'",
        ),
        ("import scenic.core.vectors as v\nm = v.numpy.random.mtrand", "'numpy.random.mtrand'"),
        ("import scenic.core.vectors\nz = scenic.core.lazy_eval", "'scenic.core.vectors'"),
        # getattr and its kin as attributes of anything
        ("x = thing.getattr(ego, 'speed')", "'.getattr' is not allowed"),
        ("import scenic.domains.driving.roads as r\nr.enum.bltns.setattr", "'.setattr'"),
        # a module is used only as `module.name`: never aliased, passed or stored
        ("import numpy\nn = numpy\nn.polyfit", "'numpy' may only be used as 'numpy.<name>'"),
        ("import numpy as np\nrng = np.random", "'numpy.random' may only be used"),
        ("import math\ndef f(m=math):\n    return m", "'math' may only be used"),
        ("import numpy\nparts = (numpy, 1)", "'numpy' may only be used"),
        ("import random\nu = getattr(random, 'uniform')", "'random' may only be used"),
        ("f = math", "'math' may only be used"),
        ("import numpy\nnumpy.pi = 3", "may not change the module 'numpy'"),
        # format strings and the other walkers of attribute names
        ("f = '{0}'.format", "may only be called at once"),
        ("f = getattr('{0.x}', 'format')", "use an f-string"),
        ("'{0:{1.__class__}}'.format(1, ego)", "format fields"),
        ("f = thing.Formatter()", "'.Formatter'"),
        ("v = thing.get_field('0.x', (), {})", "'.get_field'"),
        ("g = thing.attrgetter('x')", "'.attrgetter'"),
        # what a script sees without importing: builtins, Scenic's language, the world model
        ("p = pathlib.Path('x')", "the module 'pathlib'"),
        ("ns = {}\nmodel(ns, 'os')", "model loader"),
        ("r = File('x.npz')", "recorder to files"),
        ("g = _Scenic_module_namespace['__builtins__']", "compiled internals"),
        ("x = annotations", "'__future__'"),
        ("x = new open", "the builtin 'open'"),
        ("ego = new Car with __class__ 3", "property '__class__'"),
        # a name is the script's own only where Python cannot see the builtin any more
        ("x = dir\ndir = 3", "the builtin 'dir'"),
        ("def f(open=open):\n    return open", "the builtin 'open'"),
        ("y = [open for _ in [1] if (open := 1)]", "the builtin 'open'"),
        ("dir = 3\ndel dir\nx = dir", "the builtin 'dir'"),
        # a later star import rebinds a name (Scenic's CARLA actions export scipy's linalg)
        (
            "from numpy import linalg\nfrom scenic.simulators.carla.actions import *\n"
            "n = linalg.norm([3, 4])",
            "the module 'scipy.linalg'",
        ),
    ],
)
def test_refusals_by_identity(source: str, word: str) -> None:
    refused = _refused(source)
    assert refused and any(word in what for what in refused), refused


@pytest.mark.parametrize(
    "source",
    [
        "def f(type):\n    return type",
        "dir = ego.heading\nturn = dir + 1",
        "model = 'vehicle.tesla.model3'\nlabel = model",
        "import math\ndef f(x):\n    return math.floor(x)",
        "import scenic.domains.driving.roads\nkind = scenic.domains.driving.roads.ManeuverType",
        "from scenic.simulators.carla.actions import *\nfrom numpy import linalg\n"
        "n = linalg.norm([3, 4])",
        "def f(x: Optional[float] = None) -> float:\n    return x or 0.0",
        "car = Uniform(*blueprints.carModels)",
        "import random\nr = random.Random(3).uniform(0, 1)",
        "for _ in range(3):\n    pass",
        "from numpy import random as nr\nx = nr.normal(0, 1)",
        "total = sum(len(lane.centerline) for lane in network.lanes)",
    ],
)
def test_legitimate_names_pass(source: str) -> None:
    assert _refused(source) == []


def test_identity_verdicts() -> None:
    import enum

    from scenic.syntax.veneer import Uniform

    for refused in (
        operator.attrgetter,
        string.Formatter,
        builtins.eval,
        typing.get_type_hints,
        enum,
    ):
        assert identity.problem(refused), refused
    for allowed in (math.floor, numpy, numpy.sqrt, Uniform, len):
        assert identity.problem(allowed) is None, allowed
    assert identity.attribute_builtin(builtins.getattr) == "getattr"


def test_model_lookup_runs_nothing(tmp_path: Path) -> None:
    package = tmp_path / "hostile_model_pkg"
    package.mkdir()
    marker = tmp_path / "imported"
    (package / "__init__.py").write_text(f"open({str(marker)!r}, 'w').close()\n")
    (package / "world.py").write_text("")
    sys.path.insert(0, str(tmp_path))
    try:
        assert module_exists("hostile_model_pkg.world")
        assert not module_exists("hostile_model_pkg.world.x")
        assert not module_exists("hostile_model_pkg.missing")
        assert module_exists("os") and not module_exists("a..b")
    finally:
        sys.path.remove(str(tmp_path))
    assert not marker.exists() and "hostile_model_pkg" not in sys.modules


def test_model_refusal() -> None:
    assert model_refusal("scenic.simulators.carla.model", 1, 1) is None
    refusal = model_refusal("script.hostile.x", 4, 7)
    assert refusal is not None and (refusal.line, refusal.column) == (4, 7)
    assert "not a world model we know" in refusal.what


@pytest.mark.slow
def test_the_world_model_names_are_judged_as_scenic_binds_them() -> None:
    """What the gate reads from the world models' text matches the namespace Scenic
    really gives a script: every name bound to a refused object is refused bare."""
    import scenic

    from arise.maps.registry import MapRegistry

    choice = MapRegistry(None).resolve("arise_straight")
    probe = (
        "model scenic.simulators.carla.model\nimport builtins as B\n"
        "B.arise_probe = dict(globals())\nego = new Car on road\n"
    )
    scenic.scenarioFromString(
        probe,
        params={"map": choice.path, "carla_map": choice.name},
        model="arise.validate.worldmodel.model",
        mode2D=True,
    )
    namespace = vars(builtins).pop("arise_probe")
    refused_objects = [
        name
        for name, value in namespace.items()
        if name.isidentifier() and name not in ("B", "new", "require") and identity.problem(value)
    ]
    assert "pathlib" in refused_objects and "model" in refused_objects
    for name in refused_objects:
        assert _refused(f"x = {name}"), name


def test_a_variable_may_share_a_module_name() -> None:
    assert _refused("code = 1\nutils = code + 1\nio = utils") == []


def test_token_fallback_for_text_that_does_not_parse() -> None:
    broken = (
        "model scenic.simulators.carla.model\nimport os\nego = Car at 3 4 5 (\n"
        "open('x')\nrandom._os\nthing.getattr\n"
    )
    found = scan_tokens(broken)
    assert [r.line for r in found] == [2, 4, 5, 6]
    assert "'os'" in found[0].what and "'open'" in found[1].what and "_os" in found[2].what
    assert "'.getattr'" in found[3].what


def test_refusal_positions_are_one_based() -> None:
    refusal = scan_tree(parse_string("x = 1\ny = eval('2')", "exec"))[0]
    assert (refusal.line, refusal.column) == (2, 5)
