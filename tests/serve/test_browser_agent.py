"""The agent pick in a real browser (Debian's chromium through Playwright) against a real
server: a pasted script and a finished run's script driven by a built-in agent, with the
driving metrics shown beside the replay."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from arise.drive.report import TABLE
from tests.conftest import EXAMPLES
from tests.serve.test_browser import (  # noqa: F401  (fixtures, shared with the page's tests)
    RUN_TIMEOUT_MS,
    artifacts,
    browser,
    page,
    server,
    submit,
)

pytestmark = pytest.mark.slow


def _metrics(shown: Any) -> dict[str, str]:
    rows = shown.eval_on_selector_all(
        "#check-metrics tbody tr",
        "rows => rows.map(r => [r.dataset.metric, r.querySelector('.value').textContent])",
    )
    return dict(rows)


def test_a_pasted_script_driven_by_an_agent_shows_its_metrics(page: Any, artifacts: Path) -> None:  # noqa: F811
    options = page.eval_on_selector_all("#check-agent option", "os => os.map(o => o.value)")
    assert options == ["", "scripted", "idm", "cautious", "blind"]
    page.fill("#script-text", (EXAMPLES / "pedestrian_crossing.scenic").read_text())
    page.select_option("#check-agent", "blind")
    page.click("#check")
    page.wait_for_selector("#check-driving:not([hidden])", timeout=RUN_TIMEOUT_MS)
    assert page.text_content("#check-driving-agent") == "blind"
    assert page.text_content("#check-driving-verdict") in ("collision", "no collision")
    metrics = _metrics(page)
    assert list(metrics) == [c.metric for c in TABLE]
    assert metrics["collision"] in ("0", "1") and float(metrics["time_spent_s"]) > 0
    # Beside the replay: the frame and the table side by side, both visible.
    frame = page.locator("#check-replay").bounding_box()
    table = page.locator("#check-driving").bounding_box()
    assert frame and table and table["x"] >= frame["x"] + frame["width"] - 1
    page.screenshot(path=str(artifacts / "agent-metrics-beside-replay.png"), full_page=True)
    # No agent: the verdict and replay as before, no metrics.
    page.select_option("#check-agent", "")
    page.click("#check")
    page.wait_for_selector("#check-driving", state="hidden", timeout=RUN_TIMEOUT_MS)


def test_a_finished_run_is_driven_by_the_agent_picked(page: Any) -> None:  # noqa: F811
    submit(page)
    page.wait_for_selector("#drive-form:not([hidden])", timeout=RUN_TIMEOUT_MS)
    assert page.input_value("#drive-agent") == "idm"
    page.select_option("#drive-agent", "cautious")
    page.click("#drive")
    page.wait_for_selector("#check-driving:not([hidden])", timeout=RUN_TIMEOUT_MS)
    assert page.text_content("#check-driving-agent") == "cautious"
    assert page.inner_text("#check-verdict") == "runs"
    assert len(_metrics(page)) == len(TABLE)
    assert not page.locator("#check-replay").is_hidden()
