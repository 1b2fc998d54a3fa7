"""A machine with its contact over belt speed and load: one contact-engine run per cell.

A machine with a contact (a normal DOF with separation, a Jenkins element) has no
dimensionless ``lambda`` that sums up its operating point, so each cell ``(V, W)`` is its own
run of the exact contact engine (:func:`stickslip.analysis.contact.engine.simulate_contact`)
from the start-up state of ``system.at(speed=V, load=W)``: the verdict, the period (s), the
amplitude (m, half the peak-to-peak displacement of the contact DOF over the period) and
whether the contact lifted off. The runs are pure Python and spread over worker processes
(:class:`stickslip.analysis.contact.pool.ContactPool`); their cost is that of one
``simulate --config`` each (milliseconds for the paper's slider on a Jenkins element,
seconds for the brake pad near its flutter point).
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.contact._modes import ContactSystem
from stickslip.analysis.contact.pool import DEFAULT_WORKERS, ContactPool
from stickslip.analysis.verdict import VERDICTS

FloatArray = NDArray[np.float64]

#: Most cells of one contact map (each is a full contact-engine run).
MAX_CONTACT_CELLS = 20_000


@dataclass(frozen=True)
class ContactMap:
    """Start-up verdicts of a contact machine over belt speed and load (:func:`contact_map`).

    Attributes
    ----------
    speed : ndarray, shape (n_speed,)
        Belt speeds ``V``, m/s.
    load : ndarray, shape (n_load,)
        Preloads ``W``, N.
    verdict : ndarray of int8, shape (n_speed, n_load)
        Verdict codes (:attr:`stickslip.analysis.verdict.Verdict.code`).
    period_s, amplitude_m : ndarray, shape (n_speed, n_load)
        Of the repeating motion, s and m; NaN without one.
    separated : ndarray of bool, shape (n_speed, n_load)
        The contact lifted off at least once.
    machine : dict
        The machine's name and contact (SI).
    elapsed_s : float
        Wall time of the runs, s.
    """

    speed: FloatArray
    load: FloatArray
    verdict: NDArray[np.int8]
    period_s: FloatArray
    amplitude_m: FloatArray
    separated: NDArray[np.bool_]
    machine: dict[str, Any]
    elapsed_s: float = 0.0

    def verdict_names(self) -> NDArray[np.str_]:
        """The verdicts as names (``stick-slip``, ...), shape ``(n_speed, n_load)``."""
        names = {v.code: v.value for v in VERDICTS}
        return np.vectorize(names.__getitem__, otypes=[str])(self.verdict)

    def fractions(self) -> dict[str, float]:
        """Fraction of cells with each verdict."""
        n = max(1, self.verdict.size)
        return {v.value: float(np.count_nonzero(self.verdict == v.code)) / n for v in VERDICTS}

    def to_dataset(self) -> Any:
        """As an ``xarray.Dataset`` over ``speed`` [m/s] and ``load`` [N] (CF attributes)."""
        import xarray as xr

        from stickslip.analysis.verdict import verdict_flag_attributes
        from stickslip.io.provenance import provenance_attributes

        dims = ("speed", "load")
        return xr.Dataset(
            {"verdict": (dims, self.verdict, verdict_flag_attributes()),
             "period": (dims, self.period_s, {"units": "s", "long_name": "period of the repeating "
                                              "motion (NaN without one)"}),
             "amplitude": (dims, self.amplitude_m, {"units": "m", "long_name": "half peak-to-peak "
                                                    "displacement of the contact DOF"}),
             "separated": (dims, self.separated.astype(np.int8),
                           {"long_name": "the contact lifted off at least once",
                            "flag_values": np.array([0, 1], dtype=np.int8),
                            "flag_meanings": "no yes"})},
            coords={"speed": ("speed", self.speed, {"units": "m s-1", "long_name": "belt speed V"}),
                    "load": ("load", self.load, {"units": "N", "long_name": "preload W"})},
            attrs=provenance_attributes("start-up verdicts of a machine with its contact "
                                        "(exact contact engine)", {"machine": self.machine}))

    def to_netcdf(self, path: str | os.PathLike[str], *, overwrite: bool = True) -> Path:
        """Write :meth:`to_dataset` (:func:`stickslip.io.netcdf.write_dataset`, atomic)."""
        from stickslip.io.netcdf import write_dataset

        return write_dataset(self.to_dataset(), path, overwrite=overwrite)

    def to_csv(self, path: str | os.PathLike[str]) -> Path:
        """One row per cell, ``speed_m_per_s, load_N, verdict, period_s, amplitude_m,
        separated``, written atomically (:func:`stickslip.io.atomic.atomic_write_text`)."""
        from stickslip.io.atomic import atomic_write_text

        names = self.verdict_names()
        rows = ["speed_m_per_s,load_N,verdict,period_s,amplitude_m,separated"]
        for i, v in enumerate(self.speed.tolist()):
            for j, w in enumerate(self.load.tolist()):
                rows.append(f"{v!r},{w!r},{names[i, j]},{float(self.period_s[i, j])!r},"
                            f"{float(self.amplitude_m[i, j])!r},{str(bool(self.separated[i, j])).lower()}")
        atomic_write_text(path, "\n".join(rows) + "\n")
        return Path(path)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary: axes, fractions, costs (the cells are in the netCDF file)."""
        n = int(self.verdict.size)
        return {"kind": "start-up verdicts of a machine with its contact (contact engine)",
                "n_speed": int(self.speed.size), "n_load": int(self.load.size), "n_cells": n,
                "speed_range_m_per_s": [float(self.speed.min()), float(self.speed.max())],
                "load_range_N": [float(self.load.min()), float(self.load.max())],
                "fractions": self.fractions(),
                "separated_fraction": float(np.mean(self.separated)) if n else 0.0,
                "elapsed_s": self.elapsed_s,
                "seconds_per_run": self.elapsed_s / n if n else None,
                "machine": self.machine}

    def summary(self) -> str:
        """Two lines: the grid and verdict shares, and the cost."""
        parts = ", ".join(f"{k} {v:.1%}" for k, v in self.fractions().items() if v > 0)
        n = max(1, self.verdict.size)
        return (f"map {self.speed.size}x{self.load.size} (V, W) {self.machine.get('name')}: V "
                f"{self.speed.min():.4g} to {self.speed.max():.4g} m/s, W {self.load.min():.4g} to "
                f"{self.load.max():.4g} N: {parts}; separated in {float(np.mean(self.separated)):.1%}"
                f"\ncomputed    {self.verdict.size} contact-engine runs in {self.elapsed_s:.2f} s, "
                f"{n / max(self.elapsed_s, 1e-9):.3g} runs/s")

    def plot(self, **kwargs: Any) -> Any:
        """The verdict map, a ``PlotResult`` (:func:`stickslip.plot.contact.maps.contact_map_plot`)."""
        from stickslip.plot.contact.maps import contact_map_plot

        return contact_map_plot(self, **kwargs)


def contact_map(system: ContactSystem, speeds: FloatArray, loads: FloatArray, *,
                workers: int = DEFAULT_WORKERS, t_max: float | None = None,
                max_events: int = 100_000, machine: dict[str, Any] | None = None,
                progress: Callable[[int, int], None] | None = None) -> ContactMap:
    """The start-up verdict of every ``(speed, load)`` cell of a contact machine.

    Parameters
    ----------
    system : ContactSystem
        The machine (SI); each cell runs ``system.at(speed=V, load=W)``.
    speeds, loads : array_like
        Belt speeds (m/s) and preloads (N), positive and finite.
    workers : int
        Worker processes (1: in this process).
    t_max : float, optional
        Horizon of each run in natural times of the contact DOF (default 5000).
    max_events : int
        Bound on mode switches of each run.
    machine : dict, optional
        Description stored with the map (name, contact); default the system's sizes.
    progress : callable, optional
        ``progress(done, total)`` after each finished cell.

    Returns
    -------
    ContactMap
        Verdict, period, amplitude and separation per cell, shape ``(len(speeds), len(loads))``.
    """
    v_axis = np.asarray(speeds, dtype=np.float64).ravel()
    w_axis = np.asarray(loads, dtype=np.float64).ravel()
    if v_axis.size * w_axis.size > MAX_CONTACT_CELLS:
        raise ValueError(f"{v_axis.size} x {w_axis.size} cells is more than {MAX_CONTACT_CELLS:,} "
                         "(each is a full contact-engine run)")
    if v_axis.size == 0 or w_axis.size == 0:
        raise ValueError("the speed and load axes need at least one value each")
    points = [(v, w) for v in v_axis.tolist() for w in w_axis.tolist()]
    began = time.perf_counter()
    with ContactPool(system, workers=workers, t_max=t_max, max_events=max_events) as pool:
        found = pool.run(points, progress)
    elapsed = time.perf_counter() - began
    shape = (v_axis.size, w_axis.size)
    return ContactMap(
        v_axis, w_axis,
        np.array([p.verdict.code for p in found], dtype=np.int8).reshape(shape),
        np.array([p.period_s for p in found], dtype=np.float64).reshape(shape),
        np.array([p.amplitude_m for p in found], dtype=np.float64).reshape(shape),
        np.array([p.separated for p in found], dtype=bool).reshape(shape),
        machine if machine is not None else {"n_dof": system.n_dof,
                                             "contact_dof": system.tangential_dof},
        elapsed)


__all__ = ["MAX_CONTACT_CELLS", "ContactMap", "contact_map"]
