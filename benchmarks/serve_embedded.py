"""`arise serve` as a new user meets it: the real command, the embedded default model, a
real browser (Debian's chromium), and nothing typed in a terminal after the start.

Starts `arise serve` on a free loopback port with an empty runs folder, opens the page,
keeps the preselected model (the embedded one), types a description, presses Generate,
waits for the run to finish, plays the replay, downloads the zip, and saves a screenshot.
Prints what it saw and how long each step took. Needs the `local`/`model` extras and
/usr/bin/chromium; it runs the local model, so never beside another model process.

Run:  .venv/bin/python benchmarks/serve_embedded.py [--shot docs/serve-embedded.png]
"""

from __future__ import annotations

import argparse
import io
import os
import platform
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request
import zipfile
from pathlib import Path

CHROMIUM = Path(os.environ.get("ARISE_CHROMIUM", "/usr/bin/chromium"))
CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
DESCRIPTION = "The ego drives along a straight road when a cyclist ahead in its lane brakes hard."
RUN_TIMEOUT_S = 600


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def _wait_up(url: str, server: subprocess.Popen[bytes], seconds: float = 120) -> None:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if server.poll() is not None:
            raise SystemExit(f"arise serve exited with {server.returncode}")
        try:
            with urllib.request.urlopen(url, timeout=2):
                return
        except OSError:
            time.sleep(0.5)
    raise SystemExit("arise serve did not answer in time")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shot", type=Path, default=None, help="where to save a screenshot")
    parser.add_argument("--description", default=DESCRIPTION)
    parser.add_argument(
        "--replay", default=None, help="a cassette instead of the model (a dry run of this check)"
    )
    args = parser.parse_args()
    from playwright.sync_api import sync_playwright

    arise = Path(sys.executable).parent / "arise"
    port = free_port()
    url = f"http://127.0.0.1:{port}/"
    with tempfile.TemporaryDirectory(prefix="arise-serve-") as runs:
        started = time.perf_counter()
        command = [str(arise), "serve", "--port", str(port), "--runs-dir", runs]
        if args.replay:
            command += ["--replay", args.replay]
        server = subprocess.Popen(
            command,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        try:
            _wait_up(url, server)
            up_s = time.perf_counter() - started
            with sync_playwright() as playwright:
                browser = playwright.chromium.launch(
                    executable_path=str(CHROMIUM), args=CHROMIUM_ARGS
                )
                context = browser.new_context(
                    viewport={"width": 1400, "height": 1000}, accept_downloads=True
                )
                page = context.new_page()
                page.goto(url)
                page.wait_for_selector("#model option", state="attached")
                model = page.input_value("#model")
                page.fill("#description", args.description)
                clicked = time.perf_counter()
                page.click("#generate")
                page.wait_for_selector(
                    "#stages li[data-state='done']", timeout=RUN_TIMEOUT_S * 1000
                )
                run_s = time.perf_counter() - clicked
                stages = page.eval_on_selector_all(
                    "#stages li[data-event='stage']", "items => items.map(i => i.dataset.stage)"
                )
                finished = page.inner_text("#stages").splitlines()[-1]
                page.wait_for_selector("#result:not([hidden])")
                frame = page.locator("#replay").element_handle().content_frame()
                deadline = time.monotonic() + 20
                while not frame.evaluate("window.arise_replay !== undefined"):
                    assert time.monotonic() < deadline, "the replay never loaded"
                    time.sleep(0.05)
                frame.click("#play")
                deadline = time.monotonic() + 20
                while frame.evaluate("arise_replay.step()") <= 10:
                    assert time.monotonic() < deadline, "the replay never played"
                    time.sleep(0.05)
                with page.expect_download() as download:
                    page.click("#download-zip")
                names = sorted(
                    Path(n).name
                    for n in zipfile.ZipFile(
                        io.BytesIO(Path(download.value.path()).read_bytes())
                    ).namelist()
                )
                if args.shot is not None:
                    args.shot.parent.mkdir(parents=True, exist_ok=True)
                    page.screenshot(path=str(args.shot), full_page=False)
                context.close()
                browser.close()
        finally:
            server.terminate()
            server.wait(timeout=30)
    print(f"machine: {platform.node()} ({os.cpu_count()} cores), {time.strftime('%Y-%m-%d %H:%M')}")
    print(f"server up in {up_s:.1f} s; preselected model: {model}")
    print(f"run: {run_s:.0f} s from Generate to done; stages: {', '.join(stages)}")
    print(f"last line: {finished}")
    print("replay played past step 10 in the page")
    print(f"download: {', '.join(names)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
