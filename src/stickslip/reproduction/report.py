"""The reproduction report: Markdown and a self-contained HTML page with the figures inlined."""

from __future__ import annotations

import base64
import html
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from stickslip.reproduction.claims import Claim

VERDICT_COLORS = {"confirmed": "#1a7f37", "partly confirmed": "#9a6700", "differs": "#cf222e"}


@dataclass
class FigureRecord:
    """A figure written by the reproduction: its files and the data behind it."""

    key: str
    title: str
    png: Path
    pdf: Path
    data: list[Path] = field(default_factory=list)
    caption: str = ""


@dataclass
class Report:
    """Everything ``stickslip reproduce`` produced."""

    out_dir: Path
    quality: str
    figures: list[FigureRecord]
    claims: list[Claim]
    provenance: dict[str, Any]
    seconds: float = 0.0

    @property
    def markdown_path(self) -> Path:
        return self.out_dir / "report.md"

    @property
    def html_path(self) -> Path:
        return self.out_dir / "report.html"

    def counts(self) -> dict[str, int]:
        """Number of claims per verdict."""
        out: dict[str, int] = {}
        for claim in self.claims:
            out[claim.verdict] = out.get(claim.verdict, 0) + 1
        return out

    def to_dict(self) -> dict[str, Any]:
        return {
            "out_dir": str(self.out_dir),
            "quality": self.quality,
            "seconds": self.seconds,
            "report_markdown": str(self.markdown_path),
            "report_html": str(self.html_path),
            "claims": [c.to_dict() for c in self.claims],
            "figures": [
                {"key": f.key, "title": f.title, "png": str(f.png), "pdf": str(f.pdf),
                 "data": [str(p) for p in f.data]}
                for f in self.figures
            ],
            "counts": self.counts(),
            "provenance": self.provenance,
        }


#: The paper, as the report's introduction names it.
PAPER = ("Discussion of Stick-Slip Dynamics of 2DOF Sliding Systems Based on Dynamic Vibration "
         "Absorbers Analysis")


def introduction(report: Report) -> list[str]:
    """The report's opening paragraphs (plain text): the model and what is reproduced."""
    return [
        f"The paper \"{PAPER}\" studies a slider of mass m pressed with a normal load W on a "
        "belt that moves at a constant speed V, with static and kinetic Coulomb friction "
        "coefficients mu_s > mu_k. A spring k and a damper c hold the slider to a foundation of "
        "mass m_a, which a spring k_a and a damper c_a hold to the ground (its Fig. 1). The "
        "foundation works as a dynamic vibration absorber: tuned as one (Eqs. 28-31), it damps "
        "the slider and moves the onset of stick-slip to lower belt speeds and higher loads. "
        "In dimensionless form the motion depends on lambda = (mu_s - mu_k) W / (V sqrt(m k)), "
        "zeta = c / (2 sqrt(m k)), gamma = mu_k / (mu_s - mu_k) and the foundation's "
        "M = m_a / m, K = sqrt(k_a / k) and zeta_a = c_a / (2 sqrt(m k)).",
        f"This report recomputes the paper's figures ({len(report.figures)} below) with "
        "stickslip's exact engine: every run is propagated in closed form between its events "
        "(stick, slip, breakaway), and every verdict, stick-slip or steady sliding, is "
        "certified (a proven cycle or a Lyapunov bound) or reported as undetermined, never read "
        "off a finite simulation. "
        f"It then checks {len(report.claims)} quantitative claims of the paper's text against "
        "the computation (the table below), each with the numbers behind its verdict.",
    ]


def conclusions(report: Report) -> list[str]:
    """The report's closing paragraphs (plain text), from the claims' verdicts."""
    counts = report.counts()
    total = len(report.claims)
    differ = counts.get("differs", 0)
    confirmed = counts.get("confirmed", 0)
    summary = (f"Of the {total} claims checked, {confirmed} {'is' if confirmed == 1 else 'are'} "
               "confirmed, "
               f"{counts.get('partly confirmed', 0)} partly confirmed and {differ} "
               f"{'differs' if differ == 1 else 'differ'} from the computation.")
    open_claims = [c for c in report.claims if c.verdict != "confirmed"]
    if not open_claims:
        return [summary + " Every claim checked holds."]
    return [summary + " Where they do not hold in full:"] + [
        f"{c.source} ({c.verdict}). The paper: {_sentence(c.statement)} "
        f"The computation: {_sentence(c.measured)}" for c in open_claims
    ]


def _sentence(text: str) -> str:
    """``text`` ending in a full stop."""
    text = text.strip()
    return text if text.endswith(".") else text + "."


def _rel(path: Path, base: Path) -> str:
    try:
        return str(path.relative_to(base))
    except ValueError:
        return str(path)


def write_markdown(report: Report) -> Path:
    """Write ``report.md`` next to the figures (relative links)."""
    base = report.out_dir
    counts = report.counts()
    lines = [
        "# Reproduction of the paper with stickslip",
        "",
        f"Quality preset `{report.quality}`, {report.seconds:.0f} s. "
        + ", ".join(f"{v} {k}" for k, v in sorted(counts.items())) + ".",
        "",
        "## Introduction",
        "",
    ]
    for paragraph in introduction(report):
        lines += [paragraph, ""]
    lines += [
        "Initial condition of every simulation: " + str(report.provenance.get("initial_condition")),
        "",
        "## Claims of the paper against our computation",
        "",
        "| # | source | the paper says | we measure | verdict |",
        "| --- | --- | --- | --- | --- |",
    ]
    def cell(text: str) -> str:
        return text.replace("|", "\\|")

    for i, c in enumerate(report.claims, 1):
        lines.append(
            f"| {i} | {cell(c.source)} | {cell(c.statement)} | {cell(c.measured)} | **{c.verdict}** |"
        )
    lines += ["", "## Figures", ""]
    for fig in report.figures:
        lines += [f"### {fig.title}", "", f"![{fig.title}]({_rel(fig.png, base)})", ""]
        if fig.caption:
            lines += [fig.caption, ""]
        links = [f"[PDF]({_rel(fig.pdf, base)})"] + [
            f"[data: {p.name}]({_rel(p, base)})" for p in fig.data
        ]
        lines += [" | ".join(links), ""]
    closing = conclusions(report)
    lines += ["## Conclusions", "", closing[0], ""]
    lines += [f"* {item}" for item in closing[1:]]
    lines += ([""] if closing[1:] else []) + ["## Provenance", "", "```"]
    lines += [f"{k}: {v}" for k, v in report.provenance.items()]
    lines += ["```", ""]
    report.markdown_path.write_text("\n".join(lines), encoding="utf-8")
    return report.markdown_path


def write_html(report: Report) -> Path:
    """Write ``report.html``: one file, figures embedded as base64 PNG."""
    esc = html.escape
    rows = []
    for i, c in enumerate(report.claims, 1):
        color = VERDICT_COLORS.get(c.verdict, "black")
        rows.append(
            f"<tr><td>{i}</td><td>{esc(c.source)}</td><td>{esc(c.statement)}</td>"
            f"<td>{esc(c.measured)}</td><td style='color:{color};font-weight:bold'>"
            f"{esc(c.verdict)}</td></tr>"
        )
    figures = []
    for fig in report.figures:
        encoded = base64.b64encode(fig.png.read_bytes()).decode("ascii")
        figures.append(
            f"<section><h3>{esc(fig.title)}</h3>"
            f"<img alt='{esc(fig.title)}' src='data:image/png;base64,{encoded}'/>"
            f"<p>{esc(fig.caption)}</p></section>"
        )
    prov = "\n".join(f"{esc(str(k))}: {esc(str(v))}" for k, v in report.provenance.items())
    intro = "".join(f"<p>{esc(p)}</p>" for p in introduction(report))
    closing = conclusions(report)
    ending = f"<p>{esc(closing[0])}</p>" + (
        "<ul>" + "".join(f"<li>{esc(item)}</li>" for item in closing[1:]) + "</ul>"
        if closing[1:] else "")
    counts = ", ".join(f"{v} {k}" for k, v in sorted(report.counts().items()))
    page = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>stickslip: reproduction of the paper</title>
<style>
body {{ font-family: system-ui, sans-serif; max-width: 1200px; margin: 2em auto; padding: 0 1em; }}
table {{ border-collapse: collapse; width: 100%; font-size: 0.9em; }}
td, th {{ border: 1px solid #ccc; padding: 0.4em; vertical-align: top; text-align: left; }}
img {{ max-width: 100%; }}
pre {{ background: #f6f8fa; padding: 1em; overflow-x: auto; }}
</style></head><body>
<h1>Reproduction of the paper with stickslip</h1>
<p>Quality preset <code>{esc(report.quality)}</code>, {report.seconds:.0f} s. {esc(counts)}.</p>
<h2>Introduction</h2>
{intro}
<h2>Claims of the paper against our computation</h2>
<table><tr><th>#</th><th>source</th><th>the paper says</th><th>we measure</th><th>verdict</th></tr>
{''.join(rows)}
</table>
<h2>Figures</h2>
{''.join(figures)}
<h2>Conclusions</h2>
{ending}
<h2>Provenance</h2><pre>{prov}</pre>
</body></html>
"""
    report.html_path.write_text(page, encoding="utf-8")
    return report.html_path
