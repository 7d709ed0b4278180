"""The static gate's allow-list: which modules a script may import and which of their names.

Data only, read by `arise.validate.gate` (the walk over a script's syntax tree) and
`arise.validate.identity` (what a name resolves to). Names here are judged by what they
ARE wherever the gate can resolve them; the name lists are the floor for values only known
at run time (an attribute of a lane, of a sampled object).
"""

from __future__ import annotations

from arise.validate.script_info import KNOWN_MODELS

# --- what a script may import, and which names of each module it may use ---------------
_MATH_NAMES = None  # every public name of math is pure arithmetic
_RANDOM_NAMES = frozenset(
    {
        "random",
        "uniform",
        "gauss",
        "normalvariate",
        "lognormvariate",
        "expovariate",
        "vonmisesvariate",
        "gammavariate",
        "betavariate",
        "paretovariate",
        "weibullvariate",
        "triangular",
        "choice",
        "choices",
        "sample",
        "shuffle",
        "randint",
        "randrange",
        "seed",
        "Random",
    }
)
_NUMPY_NAMES = frozenset(
    {
        "array",
        "asarray",
        "zeros",
        "ones",
        "full",
        "arange",
        "linspace",
        "eye",
        "pi",
        "e",
        "inf",
        "nan",
        "sqrt",
        "exp",
        "log",
        "log10",
        "log2",
        "sin",
        "cos",
        "tan",
        "arcsin",
        "arccos",
        "arctan",
        "arctan2",
        "hypot",
        "degrees",
        "radians",
        "deg2rad",
        "rad2deg",
        "abs",
        "absolute",
        "sign",
        "floor",
        "ceil",
        "round",
        "rint",
        "clip",
        "minimum",
        "maximum",
        "min",
        "max",
        "amin",
        "amax",
        "argmin",
        "argmax",
        "mean",
        "median",
        "std",
        "var",
        "sum",
        "prod",
        "cumsum",
        "diff",
        "dot",
        "cross",
        "outer",
        "interp",
        "where",
        "isclose",
        "allclose",
        "isnan",
        "isfinite",
        "sort",
        "argsort",
        "unique",
        "concatenate",
        "stack",
        "vstack",
        "hstack",
        "reshape",
        "transpose",
        "mod",
        "fmod",
        "power",
        "square",
        "cbrt",
        "percentile",
        "quantile",
        "all",
        "any",
        "count_nonzero",
        "float64",
        "float32",
        "int64",
        "int32",
        "random",
        "linalg",
    }
)
_NUMPY_RANDOM_NAMES = frozenset(
    {
        "rand",
        "randn",
        "random",
        "uniform",
        "normal",
        "choice",
        "randint",
        "seed",
        "shuffle",
        "permutation",
        "exponential",
        "poisson",
        "triangular",
        "beta",
        "gamma",
        "lognormal",
        "default_rng",
    }
)
_NUMPY_LINALG_NAMES = frozenset({"norm", "det", "inv", "solve", "eig", "eigvals"})
_ITERTOOLS_NAMES = frozenset(
    {
        "chain",
        "product",
        "permutations",
        "combinations",
        "cycle",
        "islice",
        "repeat",
        "accumulate",
        "pairwise",
        "zip_longest",
        "count",
    }
)
_FUNCTOOLS_NAMES = frozenset({"partial", "reduce", "lru_cache", "cache"})
_COLLECTIONS_NAMES = frozenset({"deque", "namedtuple", "OrderedDict", "defaultdict", "Counter"})

#: Module -> the names a script may use from it (None: every public name).
MODULE_NAMES: dict[str, frozenset[str] | None] = {
    "math": _MATH_NAMES,
    "random": _RANDOM_NAMES,
    "numpy": _NUMPY_NAMES,
    "numpy.random": _NUMPY_RANDOM_NAMES,
    "numpy.linalg": _NUMPY_LINALG_NAMES,
    "itertools": _ITERTOOLS_NAMES,
    "functools": _FUNCTOOLS_NAMES,
    "collections": _COLLECTIONS_NAMES,
}
#: Scenic modules a script may import from; their public names pass unless listed below.
SCENIC_MODULE_PREFIXES = (
    "scenic.simulators.carla",
    "scenic.simulators.newtonian",
    "scenic.domains.driving",
    "scenic.core.vectors",
    "scenic.core.regions",
    "scenic.core.distributions",
)
STAR_IMPORTABLE = frozenset({"math", "random"})

#: Scenic's documented non-rejecting accessors of road-network elements (roads.py says
#: to use `_laneToLeft` where `laneToLeft` would reject the sample). Data, not internals.
SCENIC_PRIVATE_ACCESSORS = frozenset(
    {
        "_laneToLeft",
        "_laneToRight",
        "_fasterLane",
        "_slowerLane",
        "_lane",
        "_laneSection",
        "_laneGroup",
        "_road",
        "_intersection",
        "_crossing",
        "_element",
        "_sidewalk",
        "_opposite",
        "_successor",
        "_predecessor",
    }
)

#: Names that lead to the interpreter, files, processes or the network: refused as bare
#: names and as attributes of anything (Scenic's modules re-export some of them).
DANGEROUS_NAMES = frozenset(
    {
        # modules
        "os",
        "sys",
        "subprocess",
        "shutil",
        "socket",
        "ctypes",
        "ctypeslib",
        "importlib",
        "builtins",
        "pickle",
        "marshal",
        "shelve",
        "dbm",
        "io",
        "pathlib",
        "tempfile",
        "glob",
        "signal",
        "threading",
        "multiprocessing",
        "asyncio",
        "selectors",
        "select",
        "mmap",
        "fcntl",
        "resource",
        "pty",
        "posix",
        "gc",
        "inspect",
        "code",
        "codeop",
        "runpy",
        "pkgutil",
        "zipimport",
        "urllib",
        "http",
        "ftplib",
        "smtplib",
        "webbrowser",
        "sqlite3",
        "zipfile",
        "tarfile",
        "gzip",
        "bz2",
        "lzma",
        "logging",
        "atexit",
        "faulthandler",
        "sysconfig",
        "linecache",
        "types",
        "ast",
        "dis",
        "veneer",
        "translator",
        "compiler",
        "syntax",
        "typing",
        "lib",
        "f2py",
        "distutils",
        "testing",
        "ma",
        "scipy",
        "arise",
        "pygame",
        "matplotlib",
        "trimesh",
        "shapely",
        "attr",
        "weakref",
        "warnings",
        "utils",
        "type_support",
        # functions and attributes that open files, run programs or evaluate code
        "open",
        "eval",
        "exec",
        "compile",
        "__import__",
        "globals",
        "locals",
        "vars",
        "breakpoint",
        "input",
        "exit",
        "quit",
        "help",
        "memoryview",
        "system",
        "popen",
        "spawn",
        "spawnv",
        "spawnl",
        "execv",
        "execve",
        "execl",
        "execlp",
        "fork",
        "forkpty",
        "kill",
        "modules",
        "load",
        "loads",
        "save",
        "savez",
        "savez_compressed",
        "savetxt",
        "loadtxt",
        "genfromtxt",
        "fromfile",
        "tofile",
        "dump",
        "dumps",
        "memmap",
        "DataSource",
        "fromregex",
        "get_type_hints",
        "mro",
        "format_map",
        "gi_frame",
        "gi_code",
        "cr_frame",
        "f_globals",
        "f_locals",
        "f_back",
        "f_builtins",
        "tb_frame",
        "tb_next",
        "func_globals",
        "func_code",
        "im_func",
        "co_code",
        "getattribute",
        # attribute walkers: they take attribute names as strings
        "attrgetter",
        "methodcaller",
        "Formatter",
        "get_field",
        "vformat",
        # Scenic's loaders of pickled road networks and of mesh files
        "fromPickle",
        "dumpPickle",
        "fromFile",
    }
)
#: Builtins refused as bare names only (as attributes they are ordinary data, e.g.
#: `maneuver.type`): they build classes or list what an object hides.
BARE_BUILTINS = frozenset(
    {"object", "type", "super", "classmethod", "staticmethod", "property", "dir"}
)
#: Builtins that take an attribute name as a string: only called by their own name, with a
#: literal name (`getattr(x, 'speed')`), never as a value or as an attribute of anything.
ATTRIBUTE_BUILTINS = frozenset({"getattr", "setattr", "delattr", "hasattr"})


#: Names Scenic's compiler puts in a script's namespace or its behaviors (the module's own
#: globals dict among them): refused unless the script binds the name itself first.
SCENIC_INJECTED_NAMES = frozenset(
    {
        "_Scenic_module_namespace",
        "_Scenic_current_behavior",
        "_Scenic_interrupt",
        "_Scenic_temporary_name",
        "_scenario",
        "_scenarios",
        "_compileOptions",
        "_astHash",
        "_locals",
        "_args",
        "_kwargs",
        "_setup",
        "_compose",
        "_invokeSubBehavior",
        "_scenic_properties",
    }
)

#: The world models whose names a script sees without importing them: the ones a `model`
#: line may name, and arise's offline CARLA model that replaces them when checking.
AMBIENT_MODELS = ("arise.validate.worldmodel.model", *KNOWN_MODELS)


def module_allowed(name: str) -> bool:
    """May a script import this module?"""
    return name in MODULE_NAMES or any(
        name == prefix or name.startswith(prefix + ".") for prefix in SCENIC_MODULE_PREFIXES
    )


def is_scenic(module: str) -> bool:
    return module.startswith("scenic.")


def path_components(package: str) -> frozenset[str]:
    """The submodule names that lead from a package to an allowed module ('scenic' ->
    {'core', 'domains', 'simulators'}): the only attributes of a package on the way."""
    prefix = package + "."
    return frozenset(
        allowed[len(prefix) :].split(".")[0]
        for allowed in (*MODULE_NAMES, *SCENIC_MODULE_PREFIXES)
        if allowed.startswith(prefix)
    )


def name_of_module_allowed(module: str, name: str) -> bool:
    """May a script use `name` of an allowed `module` (by its name; its identity is judged
    by `arise.validate.identity`)?"""
    if name.startswith("_") or name in DANGEROUS_NAMES:
        return False
    if is_scenic(module):
        return True
    allowed = MODULE_NAMES.get(module, frozenset())
    return allowed is None or name in allowed or f"{module}.{name}" in MODULE_NAMES
