"""``stickslip reproduce``: every result-carrying figure and claim of the paper, with a report."""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from stickslip.io.provenance import git_revision, library_versions, package_version, utc_now
from stickslip.model.initial import STARTUP_DESCRIPTION
from stickslip.reproduction import steps_design, steps_dynamics
from stickslip.reproduction.quality import quality as get_quality
from stickslip.reproduction.report import Report, write_html, write_markdown

StepProgress = Callable[[str, int, int], None]


def provenance(quality_name: str) -> dict[str, Any]:
    """Versions, git revision and settings recorded with every reproduction."""
    return {
        "stickslip": package_version(),
        "git_revision": git_revision() or None,
        "date": utc_now(),
        **{name: version for name, version in library_versions().items()},
        "quality": quality_name,
        "initial_condition": STARTUP_DESCRIPTION,
        "gamma": "2 unless stated",
    }


def reproduce(out_dir: Path, quality: str = "default",
              progress: StepProgress | None = None) -> Report:
    """Recompute every figure and claim of the paper into ``out_dir``.

    Parameters
    ----------
    out_dir : Path
        Created if missing; receives ``figures/`` (PNG and PDF), ``data/`` (CSV, netCDF,
        JSON), ``report.md``, ``report.html`` and ``report.json``.
    quality : {"tiny", "default", "high"}
        Resolution preset (see :mod:`stickslip.reproduction.quality`).
    progress : callable, optional
        ``progress(step, done, total)`` called as the work advances.
    """
    preset = get_quality(quality)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()

    def report_step(name: str) -> Callable[[int, int], None] | None:
        if progress is None:
            return None
        return lambda done, total: progress(name, done, total)

    def step(name: str) -> None:
        if progress is not None:
            progress(name, 0, 1)

    figures = []
    claims = []
    step("absorber: optimal tuning (Figs. 4, 5, 6, 10)")
    from stickslip.reproduction import steps_absorber

    f, c = steps_absorber.absorber_figures(out_dir, preset)
    figures += f
    claims += c
    step("time histories (Figs. 7, 12-15)")
    f, c = steps_dynamics.time_history_figures(out_dir, preset)
    figures += f
    claims += c
    step("occurrence maps (Figs. 8, 11)")
    from stickslip.reproduction import steps_maps

    f, c = steps_maps.map_figures(out_dir, preset, report_step)
    figures += f
    claims += c
    step("closed forms (Eqs. 34-39)")
    claims += steps_dynamics.closed_form_claims()
    step("design procedure (Fig. 16) and the stick-slip-optimal foundation")
    f, c = steps_design.design_example(out_dir)
    figures += f
    claims += c
    optimum = steps_design.stick_slip_optimum_claim()
    claims.append(optimum)
    step("disturbed starts: stick-slip cycles of the stick-slip-optimal foundation")
    claims.append(steps_design.disturbed_starts_claim(optimum, seeds=2 if preset.name == "tiny" else 8))
    figures.sort(key=lambda rec: rec.key)
    report = Report(out_dir, preset.name, figures, claims, provenance(preset.name),
                    time.perf_counter() - start)
    write_markdown(report)
    write_html(report)
    (out_dir / "report.json").write_text(json.dumps(report.to_dict(), indent=2, default=str),
                                         encoding="utf-8")
    if progress is not None:
        progress("done", 1, 1)
    return report
