"""One error root: every exception class arise defines derives from `arise.errors.AriseError`.

The command line catches that root once and prints it as one line; an exception class
outside it would reach the user as a crash report. The walk imports every Python module
of the package (not the Scenic world-model files, which define no exceptions), so a
class inherited through another module is judged by its real ancestry.
"""

from __future__ import annotations

import importlib
import inspect
from pathlib import Path

import arise
from arise.errors import AriseError

# Classes that may stay outside the root, each with its reason. Keep it short.
ALLOWED: dict[str, str] = {}


def _module_names() -> list[str]:
    root = Path(arise.__file__).parent
    names = []
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(root.parent).with_suffix("").parts
        if parts[-1] == "__main__":  # importing it runs the command line
            continue
        names.append(".".join(parts[:-1] if parts[-1] == "__init__" else parts))
    return names


def _exception_classes() -> dict[str, type[BaseException]]:
    found: dict[str, type[BaseException]] = {}
    for name in _module_names():
        module = importlib.import_module(name)
        for obj in vars(module).values():
            if (
                inspect.isclass(obj)
                and issubclass(obj, BaseException)
                and obj.__module__ == module.__name__
            ):
                found[f"{obj.__module__}.{obj.__qualname__}"] = obj
    return found


def test_every_exception_class_derives_from_arise_error() -> None:
    found = _exception_classes()
    outside = sorted(
        f"{name} ({', '.join(base.__name__ for base in cls.__bases__)})"
        for name, cls in found.items()
        if not issubclass(cls, AriseError) and name not in ALLOWED
    )
    assert outside == [], "derive these from arise.errors.AriseError: " + "; ".join(outside)
    # The walk really saw the package: classes from the lowest and the highest layers.
    assert {"arise.llm.types.ProviderError", "arise.evaluate.store.BenchStoreError"} <= set(found)
    assert "arise.validate.worldmodel.weather.WeatherError" in found


def test_the_allow_list_is_not_stale() -> None:
    found = _exception_classes()
    stale = sorted(
        name for name in ALLOWED if name not in found or issubclass(found[name], AriseError)
    )
    assert stale == [], f"remove from ALLOWED (gone, or under AriseError now): {stale}"
