"""``stickslip reproduce``: every result-carrying figure and claim of the paper, with a report."""

from __future__ import annotations

import json
import platform
import time
from collections.abc import Callable
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from stickslip.model.initial import STARTUP_DESCRIPTION
from stickslip.reproduction import steps_design, steps_dynamics
from stickslip.reproduction.quality import quality as get_quality
from stickslip.reproduction.report import Report, write_html, write_markdown

StepProgress = Callable[[str, int, int], None]


def provenance(quality_name: str) -> dict[str, Any]:
    """Versions, git revision and settings recorded with every reproduction."""
    import matplotlib
    import numba
    import numpy
    import scipy

    from stickslip import __version__

    return {
        "stickslip": __version__,
        "git_revision": git_revision(),
        "date": datetime.now(UTC).isoformat(timespec="seconds"),
        "python": platform.python_version(),
        "numpy": numpy.__version__,
        "scipy": scipy.__version__,
        "numba": numba.__version__,
        "matplotlib": matplotlib.__version__,
        "quality": quality_name,
        "initial_condition": STARTUP_DESCRIPTION,
        "gamma": "2 unless stated",
    }


def git_revision() -> str | None:
    """The git commit of the source tree, when it is a git checkout."""
    import subprocess

    here = Path(__file__).resolve().parent
    try:
        out = subprocess.run(["git", "rev-parse", "HEAD"], cwd=here, capture_output=True,
                             text=True, check=True, timeout=5)
    except (OSError, subprocess.SubprocessError):
        return None
    return out.stdout.strip() or None


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
    q = get_quality(quality)
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

    f, c = steps_absorber.absorber_figures(out_dir, q)
    figures += f
    claims += c
    step("time histories (Figs. 7, 12-15)")
    f, c = steps_dynamics.time_history_figures(out_dir, q)
    figures += f
    claims += c
    step("occurrence maps (Figs. 8, 11)")
    from stickslip.reproduction import steps_maps

    f, c = steps_maps.map_figures(out_dir, q, report_step)
    figures += f
    claims += c
    step("closed forms (Eqs. 34-39)")
    claims += steps_dynamics.closed_form_claims()
    step("design procedure (Fig. 16) and the stick-slip-optimal foundation")
    f, c = steps_design.design_example(out_dir)
    figures += f
    claims += c
    claims.append(steps_design.stick_slip_optimum_claim())
    figures.sort(key=lambda rec: rec.key)
    report = Report(out_dir, q.name, figures, claims, provenance(q.name),
                    time.perf_counter() - start)
    write_markdown(report)
    write_html(report)
    (out_dir / "report.json").write_text(json.dumps(report.to_dict(), indent=2, default=str),
                                         encoding="utf-8")
    if progress is not None:
        progress("done", 1, 1)
    return report
