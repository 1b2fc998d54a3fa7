"""The machine page with a contact machine, in a real headless Chromium.

The server, browser and helpers are those of ``tests/test_app_browser.py`` (imported: the same
``stickslip app`` server on a free localhost port, the same Playwright page, the same
``STICKSLIP_SCREENSHOTS`` mechanism for ``docs/app-contact.png``). The expected numbers are
those of ``docs/brake_squeal.md`` for ``examples/brake_pad/machine.toml``: steady sliding
UNSTABLE, critical mu 0.30291579, a slip-separation cycle of period 0.00024315 s with the
contact lifting off; ``tests/test_app_contact.py`` checks every number against the
command line's ``--json``.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import pytest

from tests.test_app_browser import (  # noqa: F401  (the fixtures are used by name)
    PAGE_TIMEOUT_MS,
    _playwright,
    _screenshot,
    _upload,
    browser,
    page,
    served,
    server,
)

BRAKE_PAD = Path(__file__).resolve().parents[1] / "examples" / "brake_pad"
#: The paper's slider on a Jenkins element, no normal DOF (tests/test_app_contact.py).
JENKINS = ('mu_s = 0.3\nmu_k = 0.2\nload = "1 N"\nspeed = "0.2 m/s"\nm = "1 kg"\nk = "1 N/m"\n'
           'c = "0 N*s/m"\n\n[contact]\ntangential_stiffness = "1e4 N/m"\n'
           'tangential_damping = "60 N*s/m"\n')


def _metric(tab: Any, label: str) -> Any:
    """The value of the metric labelled ``label`` on the page ``tab``."""
    return (tab.locator('[data-testid="stMetric"]').filter(has_text=label)
            .locator('[data-testid="stMetricValue"]'))


@pytest.mark.slow  # 27 s: out of the default run (kept under ten minutes)
def test_the_machine_page_with_the_brake_pad(server: str, page: Any) -> None:  # noqa: F811
    expect = _playwright().expect
    files = {p.name: p.read_bytes() for p in BRAKE_PAD.iterdir()
             if p.suffix == ".csv" or p.name == "machine.toml"}
    start = time.monotonic()
    _upload(page, server, files)
    expect(_metric(page, "Steady sliding")).to_have_text("UNSTABLE", timeout=PAGE_TIMEOUT_MS)
    expect(_metric(page, "Critical mu (damped)")).to_have_text("0.30291579")
    expect(_metric(page, "Critical mu (undamped)")).to_have_text("0.30833333")
    expect(_metric(page, "Period")).to_have_text("0.00024315 s", timeout=PAGE_TIMEOUT_MS)
    elapsed = time.monotonic() - start
    expect(_metric(page, "Time history")).to_have_text("slip-oscillation")
    expect(_metric(page, "Separated")).to_have_text("yes")
    expect(page.get_by_text("observed, not proven", exact=False)).to_have_count(1)
    # the start line is the command line's (stickslip simulate --config on the same file)
    expect(page.get_by_text("contact at the belt speed), stuck to the belt", exact=False)
           ).to_have_count(1)
    table = page.locator('[data-testid="stDataFrame"]')
    expect(table).to_have_count(1)
    expect(page.locator('[data-testid="stImage"], [data-testid="stImageContainer"], img')
           .first).to_be_visible()
    # one information line says what applies; the analyses without a contact are not offered
    expect(page.get_by_text("do not take a contact in this version", exact=False)).to_have_count(1)
    for absent in ("Verdict at the operating point", "Bifurcation diagram in belt speed"):
        expect(page.get_by_text(absent)).to_have_count(0)
    expect(page.locator('[data-testid="stException"]')).to_have_count(0)
    expect(page.locator('[data-testid="stAlertContentError"]')).to_have_count(0)
    print(f"brake pad page: {elapsed:.1f} s from the upload to the period on the page")
    _screenshot(page, "app-contact.png")


@pytest.mark.slow  # 16 s: out of the default run (kept under ten minutes)
def test_a_jenkins_machine_gets_its_analysis_and_run(server: str, page: Any) -> None:  # noqa: F811
    expect = _playwright().expect
    # a file name Markdown would make bold: the page must not break on it (app/messages.py)
    _upload(page, server, {"__jenkins__.toml": JENKINS.encode()})
    # the undamped slider's pair stays on the axis (tests/test_app_contact.py): marginal
    expect(_metric(page, "Steady sliding")).to_have_text("marginal", timeout=PAGE_TIMEOUT_MS)
    expect(page.get_by_text("not in the complex-eigenvalue analysis", exact=False)).to_have_count(0)
    expect(_metric(page, "Time history")).to_have_text("stick-slip", timeout=PAGE_TIMEOUT_MS)
    expect(_metric(page, "Separated")).to_have_text("no")
    expect(page.locator('[data-testid="stAlertContentError"]')).to_have_count(0)
    expect(page.locator('[data-testid="stException"]')).to_have_count(0)
