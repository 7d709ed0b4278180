"""The fast tier stays fast: a test without the `slow` marker may not start a validator
worker, load the language model, start the model server or open a browser.

`make check` runs `pytest -m "not slow"` and must finish in about a minute on 2 cores; one
unmarked test that warms a pool (5 s) or loads the model (2 GB) breaks that quietly. This
plugin wraps the few entry points that do those things and fails the unmarked test that
reaches one, naming what it started. The wrappers are installed for the whole session and
look at which test is running, so a session fixture set up on behalf of an unmarked test
is caught too.
"""

from __future__ import annotations

import subprocess
from collections.abc import Callable, Generator
from typing import Any

import pytest

SLOW = "slow"
# Command-line fragments of the child processes only slow tests may start.
_SLOW_CHILDREN = {
    "arise.validate.worker": "a validator worker",
    "arise.validate.map_cache": "a map parse (prepares a map's cache)",
    "llama_cpp.server": "the model server",
    "chromium": "a browser",
}


class _State:
    """Which test is running, and what it started that it should not have."""

    fast_test: str | None = None
    violations: list[str] = []
    reported = False


def _refuse(what: str) -> None:
    if _State.fast_test is not None:
        message = (
            f"{_State.fast_test} is not marked slow but started {what}; "
            "mark it `@pytest.mark.slow` (see the README's development section)"
        )
        _State.violations.append(message)
        raise RuntimeError(message)


def _guarded_popen_init(original: Callable[..., None]) -> Callable[..., None]:
    def init(self: subprocess.Popen[Any], args: Any, *rest: Any, **kwargs: Any) -> None:
        line = " ".join(map(str, args)) if isinstance(args, list | tuple) else str(args)
        for fragment, what in _SLOW_CHILDREN.items():
            if fragment in line:
                _refuse(what)
        original(self, args, *rest, **kwargs)

    return init


def _guarded(original: Callable[..., Any], what: str) -> Callable[..., Any]:
    def call(*args: Any, **kwargs: Any) -> Any:
        _refuse(what)
        return original(*args, **kwargs)

    return call


def pytest_configure(config: pytest.Config) -> None:
    subprocess.Popen.__init__ = _guarded_popen_init(subprocess.Popen.__init__)  # type: ignore[method-assign]
    from arise.llm import local

    local._load = _guarded(local._load, "the local language model")  # type: ignore[assignment]
    try:
        from playwright.sync_api import BrowserType
    except ImportError:
        return
    BrowserType.launch = _guarded(BrowserType.launch, "a browser")  # type: ignore[method-assign]


@pytest.hookimpl(wrapper=True)
def pytest_runtest_protocol(item: pytest.Item, nextitem: pytest.Item | None) -> Generator[None]:
    fast = item.get_closest_marker(SLOW) is None
    _State.fast_test = item.nodeid if fast else None
    _State.violations = []
    _State.reported = False
    try:
        return (yield)
    finally:
        _State.fast_test = None


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(
    item: pytest.Item, call: pytest.CallInfo[None]
) -> Generator[None, pytest.TestReport, pytest.TestReport]:
    """Fail the first phase that saw a violation, even one the code under test swallowed
    (a pool warmed on a background thread)."""
    report = yield
    if _State.violations and not _State.reported:
        _State.reported = True
        report.outcome = "failed"
        report.longrepr = "\n".join(dict.fromkeys(_State.violations))
    return report
