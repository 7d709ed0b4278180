"""The page in a real browser (Debian's chromium through Playwright) against a real
server: the model replayed from a cassette of the embedded model, the real validator.

Screenshots are kept as artifacts in $ARISE_TEST_ARTIFACTS/serve, or else in pytest's
base temporary folder under artifacts/serve (printed at the end of the run with -rA).
"""

from __future__ import annotations

import io
import os
import time
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from arise.llm.settings import Settings
from arise.serve.app import create_app, guarded
from arise.serve.config import ServeConfig
from arise.validate import WorkerPool
from tests.generate_cases import CASES
from tests.serve.browser import CHROMIUM, CHROMIUM_ARGS, free_port, serving, skip_without_browser

pytestmark = pytest.mark.slow

CASE = CASES["first_try"]
EXAMPLE_TITLE = "Cyclist brakes ahead"  # the shipped example whose words the cassette holds
RUN_TIMEOUT_MS = 120_000


@pytest.fixture(scope="module")
def artifacts(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = os.environ.get("ARISE_TEST_ARTIFACTS")
    folder = (Path(root) if root else tmp_path_factory.getbasetemp() / "artifacts") / "serve"
    folder.mkdir(parents=True, exist_ok=True)
    return folder


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory, validator_pool: WorkerPool) -> Iterator[str]:
    skip_without_browser()
    config = ServeConfig(
        port=free_port(),
        runs_dir=tmp_path_factory.mktemp("runs"),
        replay=str(CASE.cassette),
        options=CASE.options(),
    )
    app = guarded(config, create_app(config, pool=validator_pool, settings=Settings()))
    with serving(app, config.port) as url:
        yield url


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    skip_without_browser()
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        launched = playwright.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
        yield launched
        launched.close()


@pytest.fixture()
def page(
    browser: Any, server: str, artifacts: Path, request: pytest.FixtureRequest
) -> Iterator[Any]:
    context = browser.new_context(viewport={"width": 1400, "height": 1000}, accept_downloads=True)
    opened = context.new_page()
    errors: list[str] = []
    opened.on("pageerror", lambda error: errors.append(str(error)))
    opened.goto(server)
    opened.wait_for_selector("#model option", state="attached")
    yield opened
    opened.screenshot(path=str(artifacts / f"{request.node.name}.png"), full_page=True)
    context.close()
    assert errors == [], f"the page raised: {errors}"


def submit(page: Any, description: str | None = None) -> str:
    """Submit (an example when no description is given); the new job's id."""
    if description is None:
        page.select_option("#example", label=EXAMPLE_TITLE)
    else:
        page.fill("#description", description)
    before = set(page.eval_on_selector_all("#jobs li", "items => items.map(i => i.dataset.id)"))
    page.click("#generate")
    deadline = time.monotonic() + 20
    while True:
        ids = page.eval_on_selector_all("#jobs li", "items => items.map(i => i.dataset.id)")
        new = [i for i in ids if i not in before]
        if new:
            return str(new[0])
        assert time.monotonic() < deadline, "the new job never showed in the list"
        time.sleep(0.05)


def wait_job(page: Any, job_id: str, state: str) -> None:
    page.wait_for_selector(
        f"#jobs li[data-id='{job_id}'][data-state='{state}']", timeout=RUN_TIMEOUT_MS
    )


def test_submit_an_example_and_see_every_stage(page: Any, artifacts: Path) -> None:
    page.select_option("#example", label=EXAMPLE_TITLE)
    assert page.input_value("#description") == CASE.description
    assert page.input_value("#model") == "replay"
    job = submit(page)
    page.wait_for_selector("#stages li[data-state='done']", timeout=RUN_TIMEOUT_MS)
    stages = page.eval_on_selector_all(
        "#stages li[data-event='stage']", "items => items.map(i => i.dataset.stage)"
    )
    assert stages[:4] == ["extract", "retrieve", "assemble", "validate"]
    assert page.locator("#stages li.attempt.ok").count() >= 1
    assert "finished: executed" in page.inner_text("#stages")
    page.wait_for_selector("#result:not([hidden])")
    assert page.inner_text("#run-state") == "done"
    assert page.locator("#script .line").count() > 20
    sections = set(
        page.eval_on_selector_all("#script .line", "ls => ls.map(l => l.dataset.section)")
    )
    assert {"BEHAVIOR", "GEOMETRY", "SPAWN"} <= sections
    assert "adversary_class" in page.inner_text("#facts")
    assert page.locator("#conformity tbody tr.ok").count() >= 5
    assert page.get_attribute(f"#jobs li[data-id='{job}']", "data-state") == "done"


def poll(frame: Any, expression: str, timeout: float = 60.0) -> None:
    """Wait until `expression` is true in the frame. (The replay's policy forbids eval,
    which Playwright's wait_for_function polls with; evaluate() is not affected.)"""
    deadline = time.monotonic() + timeout
    while not frame.evaluate(expression):
        assert time.monotonic() < deadline, f"never true: {expression}"
        time.sleep(0.05)


def _replay_frame(page: Any) -> Any:
    page.wait_for_selector("#replay:not([hidden])", timeout=RUN_TIMEOUT_MS)
    frame = page.locator("#replay").element_handle().content_frame()
    poll(frame, "window.arise_replay !== undefined")
    return frame


def test_the_replay_plays(page: Any) -> None:
    submit(page)
    page.wait_for_selector("#result:not([hidden])", timeout=RUN_TIMEOUT_MS)
    frame = _replay_frame(page)
    assert frame.evaluate("arise_replay.step()") == 0
    start_clock = frame.inner_text("#clock")
    frame.click("#play")
    poll(frame, "arise_replay.step() > 10")
    assert frame.inner_text("#clock") != start_clock
    assert frame.inner_text("#play") == "Pause"


def test_the_download_holds_the_five_files(page: Any) -> None:
    submit(page)
    page.wait_for_selector("#result:not([hidden])", timeout=RUN_TIMEOUT_MS)
    with page.expect_download() as download:
        page.click("#download-zip")
    data = Path(download.value.path()).read_bytes()
    names = sorted(Path(n).name for n in zipfile.ZipFile(io.BytesIO(data)).namelist())
    assert [n for n in names if not n.endswith(".xodr")] == [
        "replay.html",
        "report.json",
        "scenario.scenic",
        "scenario.xosc",
    ]
    assert len([n for n in names if n.endswith(".xodr")]) == 1


def test_a_bad_description_shows_a_clear_message(page: Any, artifacts: Path) -> None:
    page.fill("#description", "Bake a chocolate cake for twelve.")
    page.click("#generate")
    page.wait_for_selector("#form-error:not([hidden])")
    message = page.inner_text("#form-error")
    assert message.startswith("(422) this does not look like a driving scenario")
    page.screenshot(path=str(artifacts / "bad-description-422.png"))
    page.fill("#description", "The ego car brakes. " * 120)
    page.click("#generate")
    poll(page, "document.getElementById('form-error').textContent.includes('413')")
    assert "the limit is 2000" in page.inner_text("#form-error")
    assert page.locator("#jobs li[data-state='queued']").count() == 0


def test_two_jobs_queue(page: Any, artifacts: Path) -> None:
    first = submit(page)
    second = submit(page)
    page.wait_for_selector(f"#jobs li[data-id='{second}'][data-state='queued']")
    assert "#1 in line" in page.inner_text(f"#jobs li[data-id='{second}']")
    assert "1 waiting" in page.inner_text("#queue")
    page.screenshot(path=str(artifacts / "two-jobs-queued.png"), full_page=True)
    wait_job(page, first, "done")
    wait_job(page, second, "done")


def test_cancel_a_waiting_job_and_a_running_one(page: Any) -> None:
    running = submit(page)
    waiting = submit(page)
    page.wait_for_selector(f"#jobs li[data-id='{waiting}'][data-state='queued']")
    page.click(f"#jobs li[data-id='{waiting}'] .job-cancel")
    wait_job(page, waiting, "cancelled")
    page.click(f"#jobs li[data-id='{running}']")
    page.wait_for_selector("#cancel:not([hidden])")
    page.click("#cancel")
    wait_job(page, running, "cancelled")
    page.wait_for_selector("#stages li[data-state='cancelled']")
    assert "cancelled while running" in page.inner_text("#run-message")
