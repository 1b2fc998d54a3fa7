"""The web app in a real headless Chromium: the page loads, and the verdict follows the input.

A real ``streamlit run`` server on a free localhost port, driven by Playwright through
Debian's Chromium (``/usr/bin/chromium``; Playwright's own browser download is not used).
The test never installs anything: ``make test`` installs Chromium first, visibly (its
``browser`` step: ``apt-get install chromium chromium-driver`` as root when missing), and
Playwright comes with the ``test`` extra. Where either is missing the test is skipped and
says what to install.
"""

from __future__ import annotations

import importlib
import shutil
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("streamlit", reason="the app extra (streamlit) is not installed")

from stickslip.cli.app_command import APP_SCRIPT

CHROMIUM = Path("/usr/bin/chromium")
CHROMIUM_ARGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--disable-dev-shm-usage",
]
SERVER_START_TIMEOUT = 60.0  # s
# The first script run may JIT-compile the engine (numba) when its cache is cold.
PAGE_TIMEOUT_MS = 120_000
INSTALL_TIMEOUT = 600.0  # s, only when a prerequisite is missing


def _tail(text: str, lines: int = 3) -> str:
    return " | ".join(text.strip().splitlines()[-lines:])


def _chromium() -> str:
    """Path of a Chromium binary; skip, saying how to get one, when there is none."""
    found = shutil.which("chromium") or (str(CHROMIUM) if CHROMIUM.exists() else None)
    if found is None:
        pytest.skip("Chromium is not installed (no 'chromium' on PATH, no /usr/bin/chromium): "
                    "run 'make browser' (apt-get install chromium chromium-driver, as root)")
    return found


def _playwright() -> Any:
    """The ``playwright.sync_api`` module; skip, saying how to get it, when it is missing."""
    try:
        return importlib.import_module("playwright.sync_api")
    except ImportError:
        pytest.skip("playwright is not installed: pip install -e '.[test]' (it is in the test "
                    "extra)")


def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def _wait_until_healthy(url: str, process: subprocess.Popen[bytes], log: Path) -> None:
    deadline = time.monotonic() + SERVER_START_TIMEOUT
    while time.monotonic() < deadline:
        if process.poll() is not None:
            pytest.fail(f"streamlit exited with code {process.returncode}: "
                        f"{_tail(log.read_text(errors='replace'), 10)}")
        try:
            with urllib.request.urlopen(f"{url}/_stcore/health", timeout=2) as response:
                if response.read().strip() == b"ok":
                    return
        except (urllib.error.URLError, OSError):
            pass
        time.sleep(0.3)
    pytest.fail(f"streamlit did not answer within {SERVER_START_TIMEOUT:.0f} s: "
                f"{_tail(log.read_text(errors='replace'), 10)}")


@pytest.fixture
def server(tmp_path: Path) -> Iterator[str]:
    """A ``streamlit run`` of the app on a free localhost port; always terminated."""
    port = _free_port()
    url = f"http://127.0.0.1:{port}"
    log = tmp_path / "streamlit.log"
    command = [
        sys.executable, "-m", "streamlit", "run", str(APP_SCRIPT),
        "--server.headless", "true", "--server.address", "127.0.0.1", "--server.port", str(port),
        "--browser.gatherUsageStats", "false", "--server.fileWatcherType", "none",
        "--client.toolbarMode", "viewer",
    ]
    with log.open("wb") as sink:
        process = subprocess.Popen(command, stdout=sink, stderr=subprocess.STDOUT)
        try:
            _wait_until_healthy(url, process, log)
            yield url
        finally:
            process.terminate()
            try:
                process.wait(timeout=15)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()


def test_page_loads_and_the_verdict_follows_the_speed(server: str) -> None:
    chromium = _chromium()
    sync_api = _playwright()
    expect = sync_api.expect
    with sync_api.sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=chromium, args=CHROMIUM_ARGS,
                                             headless=True)
        try:
            page = browser.new_page(viewport={"width": 1400, "height": 1000})
            page.goto(server, wait_until="domcontentloaded", timeout=PAGE_TIMEOUT_MS)
            verdict = (page.locator('[data-testid="stMetric"]')
                       .filter(has_text="Verdict with foundation")
                       .locator('[data-testid="stMetricValue"]'))
            # defaults: 5 cm/s is below the critical speed 0.0619 m/s with the foundation
            expect(verdict).to_have_text("stick-slip", timeout=PAGE_TIMEOUT_MS)

            speed = page.get_by_role("textbox", name="Belt speed V", exact=True)
            speed.fill("10 cm/s")
            speed.press("Enter")
            expect(verdict).to_have_text("steady-sliding", timeout=PAGE_TIMEOUT_MS)

            stiffness = page.get_by_role("textbox", name="Spring stiffness k", exact=True)
            stiffness.fill("5 kg")
            stiffness.press("Enter")
            alert = page.locator('[data-testid="stAlert"]').filter(has_text="wrong unit")
            expect(alert).to_have_count(1, timeout=PAGE_TIMEOUT_MS)
            expect(verdict).to_have_count(0)
            expect(page.locator('[data-testid="stException"]')).to_have_count(0)
        finally:
            browser.close()
