"""The reproduction report opens with an introduction and closes with conclusions (issue 32.7).

Before, it began with the quality preset and a table of claims and ended with provenance:
no word on the model or on what is reproduced, no conclusion. Here a report of two figures
and three claims (one of each verdict) is written and read back.
"""

from __future__ import annotations

from pathlib import Path

from stickslip.reproduction.claims import Claim
from stickslip.reproduction.report import FigureRecord, Report, write_html, write_markdown

CLAIMS = [
    Claim("a", "Eq. (31)", "H_max follows the cubic.", "0.85 % at most", "confirmed"),
    Claim("b", "Eqs. (28)-(30)", "The cubic fits give the optimum.", "M off by 16.9 %", "differs"),
    Claim("c", "Figs. 12-13", "The masses move in opposite phase.", "-121 deg", "partly confirmed"),
]


def _report(tmp_path: Path, claims: list[Claim]) -> Report:
    from matplotlib.figure import Figure

    figures = []
    for key in ("fig04", "fig05"):
        png = tmp_path / f"{key}.png"
        Figure(figsize=(1, 1)).savefig(png)
        figures.append(FigureRecord(key, key, png, tmp_path / f"{key}.pdf"))
    return Report(tmp_path, "tiny", figures, claims, {"initial_condition": "startup"}, 1.0)


def test_introduction_and_conclusions_in_markdown_and_html(tmp_path: Path) -> None:
    report = _report(tmp_path, CLAIMS)
    md = write_markdown(report).read_text()
    order = [md.index(h) for h in ("## Introduction", "## Claims", "## Figures", "## Conclusions",
                                   "## Provenance")]
    assert order == sorted(order)
    intro = md.split("## Introduction", 1)[1].split("## Claims", 1)[0]
    assert "lambda = (mu_s - mu_k) W / (V sqrt(m k))" in intro and "dynamic vibration absorber" in intro
    assert "(2 below)" in intro and "checks 3 quantitative claims" in intro
    ending = md.split("## Conclusions", 1)[1].split("## Provenance", 1)[0]
    assert "Of the 3 claims checked, 1 is confirmed, 1 partly confirmed and 1 differs" in ending
    # every claim that does not hold in full is named with both sides; a confirmed one is not
    assert ("* Eqs. (28)-(30) (differs). The paper: The cubic fits give the optimum. "
            "The computation: M off by 16.9 %.") in ending
    assert "* Figs. 12-13 (partly confirmed)." in ending and "Eq. (31)" not in ending
    page = write_html(report).read_text()
    assert page.index("<h2>Introduction</h2>") < page.index("<h2>Claims") < page.index(
        "<h2>Conclusions</h2>") < page.index("<h2>Provenance</h2>")
    assert "<li>Eqs. (28)-(30) (differs)." in page


def test_conclusions_when_every_claim_holds(tmp_path: Path) -> None:
    md = write_markdown(_report(tmp_path, CLAIMS[:1])).read_text()
    ending = md.split("## Conclusions", 1)[1].split("## Provenance", 1)[0]
    assert "1 is confirmed, 0 partly confirmed and 0 differ" in ending
    assert "Every claim checked holds." in ending and "*" not in ending
