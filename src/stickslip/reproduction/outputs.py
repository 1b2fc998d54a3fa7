"""Small helpers shared by the reproduction steps: saving figures and tables."""

from __future__ import annotations

import csv
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from stickslip.io.atomic import atomic_savefig
from stickslip.plot.figure import PlotResult
from stickslip.reproduction.report import FigureRecord


def save_figure(fig: Figure | PlotResult, out_dir: Path, key: str, title: str,
                data: Sequence[Path] = (), caption: str = "") -> FigureRecord:
    """Write ``key.png`` (150 dpi) and ``key.pdf`` into ``out_dir/figures``, each atomically.

    ``fig`` is a figure or what a ``*_plot`` function returned.
    """
    figure = fig.figure if isinstance(fig, PlotResult) else fig
    folder = out_dir / "figures"
    folder.mkdir(parents=True, exist_ok=True)
    png = atomic_savefig(figure, folder / f"{key}.png", dpi=150)
    pdf = atomic_savefig(figure, folder / f"{key}.pdf")
    return FigureRecord(key, title, png, pdf, list(data), caption)


def save_columns(columns: Mapping[str, np.ndarray | Sequence[float]], path: Path) -> Path:
    """Write equal-length columns as a CSV file with a header row."""
    path.parent.mkdir(parents=True, exist_ok=True)
    names = list(columns)
    arrays = [np.asarray(columns[n]) for n in names]
    with path.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(names)
        for row in zip(*arrays, strict=True):
            writer.writerow([repr(float(x)) if np.ndim(x) == 0 and np.isreal(x) else x
                             for x in row])
    return path
