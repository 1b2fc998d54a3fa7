"""CSV export of occurrence maps for spreadsheet users: one row per grid cell.

Columns: ``lambda``, ``zeta``, ``verdict`` (the word), ``verdict_code``, ``certificate``
(the run status word), then the numeric variables (``n_stick``, ``cycle_k``, ``period``,
``amplitude``, ``stick_ratio``, ``max_velocity``, ``t_end``) and, with a foundation, its
``M``, ``K``, ``zeta_a`` at that ``zeta``. Floats are written to full precision
(round-trip ``repr``); an empty field is a value that does not exist (no cycle, no period).

A (lambda, delta) map has the columns ``lambda``, ``delta``, then the same variables, then
its fixed ``zeta`` (and ``M``, ``K``, ``zeta_a`` with a foundation) in every row.
"""

from __future__ import annotations

import csv
import math
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from stickslip.io.atomic import atomic_output

if TYPE_CHECKING:
    import xarray as xr

_CODED = ("verdict", "certificate")


def _meanings(var: xr.DataArray) -> dict[int, str]:
    values = np.asarray(var.attrs["flag_values"]).reshape(-1)
    words = str(var.attrs["flag_meanings"]).split()
    return {int(v): w for v, w in zip(values, words, strict=True)}


def _cell(value: Any) -> str:
    if isinstance(value, (float, np.floating)):
        x = float(value)
        return repr(x) if math.isfinite(x) else ""
    return str(int(value)) if isinstance(value, (np.integer, int)) else str(value)


def write_map_csv(dataset: xr.Dataset, path: str | os.PathLike[str]) -> Path:
    """Write an occurrence map (``lambda`` x ``zeta`` or ``lambda`` x ``delta``) as CSV, atomically.

    Parameters
    ----------
    dataset : xarray.Dataset
        As made by :func:`stickslip.sweep.occurrence.map_dataset`.
    path : path-like
        Target file; replaced if it exists.

    Returns
    -------
    pathlib.Path
    """
    target = Path(path)
    second = "delta" if "delta" in dataset.dims else "zeta"
    lam = np.asarray(dataset["lambda"].values)
    zeta = np.asarray(dataset[second].values)
    grid_vars = [str(n) for n, v in dataset.data_vars.items() if v.dims == ("lambda", second)]
    if second == "zeta":
        zeta_vars = [str(n) for n, v in dataset.data_vars.items() if v.dims == ("zeta",)]
        constants: list[str] = []
    else:  # the fixed zeta and its foundation, the same in every row
        zeta_vars = []
        constants = [_cell(float(dataset.attrs["zeta"]))] + [
            _cell(np.asarray(v.values).item()) for v in dataset.data_vars.values() if v.dims == ()]
    words = {name: _meanings(dataset[name]) for name in _CODED if name in grid_vars}
    header = ["lambda", second]
    for name in grid_vars:
        header += [name, f"{name}_code"] if name == "verdict" else [name]
    header += zeta_vars
    if second == "delta":
        header += ["zeta"] + [str(n) for n, v in dataset.data_vars.items() if v.dims == ()]
    arrays = {name: np.asarray(dataset[name].values) for name in grid_vars + zeta_vars}
    with atomic_output(target) as tmp, open(tmp, "w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(header)
        for i, lam_i in enumerate(lam):
            for j, zeta_j in enumerate(zeta):
                row = [_cell(lam_i), _cell(zeta_j)]
                for name in grid_vars:
                    value = arrays[name][i, j]
                    if name in words:
                        row.append(words[name].get(int(value), str(int(value))))
                        if name == "verdict":
                            row.append(_cell(value))
                    else:
                        row.append(_cell(value))
                row += [_cell(arrays[name][j]) for name in zeta_vars]
                writer.writerow(row + constants)
    return target
