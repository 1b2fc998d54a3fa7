"""The linear stability of steady sliding over drive speed and normal load, friction with memory.

Each cell is the eigenvalue problem of :func:`stickslip.analysis.memory.stability.linear_spectrum`
(the linearisation with the state variable, with round-off bounds): a small dense problem per
cell, no simulation, so a 10^4-cell map takes seconds (``benchmarks/bench_state_friction.py``).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.memory.stability import VERDICTS, linear_spectra, spectrum_sign
from stickslip.model.state_friction import MemorySystem

FloatArray = NDArray[np.float64]

#: Most cells of one stability map (each a small eigenvalue problem).
MAX_MAP_CELLS = 4_000_000


@dataclass(frozen=True)
class MemoryStabilityMap:
    """Growth rate of steady sliding over drive speed and normal load (:func:`memory_stability_map`).

    Attributes
    ----------
    speed, load : ndarray
        The axes, m/s and N.
    growth_rate : ndarray, shape (n_speed, n_load)
        Largest real part of the eigenvalues, 1/s.
    verdict : ndarray of str, shape (n_speed, n_load)
        ``stable``, ``unstable`` or ``neutral`` (beyond the round-off bounds).
    """

    system: MemorySystem = field(repr=False)
    speed: FloatArray
    load: FloatArray
    growth_rate: FloatArray = field(repr=False)
    verdict: NDArray[np.str_] = field(repr=False)

    def fractions(self) -> dict[str, float]:
        """Fraction of cells with each verdict."""
        return {name: float(np.mean(self.verdict == name)) for name in VERDICTS.values()}

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (the grids are in the netCDF file)."""
        return {"kind": "linear stability of steady sliding (friction with memory)",
                "n_speed": int(self.speed.size), "n_load": int(self.load.size),
                "speed_range_m_per_s": [float(self.speed.min()), float(self.speed.max())],
                "load_range_N": [float(self.load.min()), float(self.load.max())],
                "fractions": self.fractions(), "friction": self.system.friction.to_dict()}

    def to_xarray(self) -> Any:
        """As an ``xarray.Dataset`` over ``speed`` and ``load`` (CF attributes)."""
        import xarray as xr

        from stickslip.io.provenance import provenance_attributes

        codes = np.select([self.verdict == "stable", self.verdict == "unstable"], [0, 1], 2)
        return xr.Dataset(
            {"growth_rate": (("speed", "load"), self.growth_rate,
                             {"long_name": "largest real part of the eigenvalues of steady sliding",
                              "units": "s-1"}),
             "stability": (("speed", "load"), codes.astype(np.int8),
                           {"long_name": "linear stability of steady sliding",
                            "flag_values": np.array([0, 1, 2], dtype=np.int8),
                            "flag_meanings": "stable unstable neutral"})},
            coords={"speed": ("speed", self.speed, {"long_name": "drive speed", "units": "m s-1"}),
                    "load": ("load", self.load, {"long_name": "normal load", "units": "N"})},
            attrs=provenance_attributes("linear stability of steady sliding, friction with memory",
                                        {"system": self.system.to_dict()}))

    def to_csv(self, path: str | Path) -> Path:
        """One row per cell: ``speed_m_per_s, load_N, growth_rate_per_s, stability``."""
        from stickslip.io.atomic import atomic_write_text

        rows = ["speed_m_per_s,load_N,growth_rate_per_s,stability"]
        for i, v in enumerate(self.speed.tolist()):
            for j, w in enumerate(self.load.tolist()):
                rows.append(f"{v!r},{w!r},{float(self.growth_rate[i, j])!r},{self.verdict[i, j]}")
        atomic_write_text(path, "\n".join(rows) + "\n")
        return Path(path)

    def plot(self, **kwargs: Any) -> Any:
        """The growth-rate map, a ``PlotResult`` (:func:`stickslip.plot.stability.memory_map_plot`)."""
        from stickslip.plot.stability import memory_map_plot

        return memory_map_plot(self, **kwargs)

    def summary(self) -> str:
        """One line per verdict."""
        parts = ", ".join(f"{name} {share:.1%}" for name, share in self.fractions().items())
        return (f"map {self.speed.size}x{self.load.size} (V, W): linear stability of steady "
                f"sliding with {self.system.friction.to_dict().get('law', 'memory')} friction: {parts}")


def memory_stability_map(system: MemorySystem, speeds: FloatArray, loads: FloatArray,
                         progress: Any = None) -> MemoryStabilityMap:
    """The linear stability of steady sliding at every (speed, load) of a grid.

    Parameters
    ----------
    system : MemorySystem
        Structure and law (SI); its load is replaced by each of ``loads``.
    speeds, loads : array_like
        Drive speeds (m/s) and normal loads (N), positive.
    progress : callable, optional
        ``progress(done, total)`` after each load (a column of the map).

    Returns
    -------
    MemoryStabilityMap
        Growth rates and verdicts, shape ``(len(speeds), len(loads))``.
    """
    v_axis = np.asarray(speeds, dtype=np.float64).ravel()
    w_axis = np.asarray(loads, dtype=np.float64).ravel()
    if v_axis.size * w_axis.size > MAX_MAP_CELLS:
        raise ValueError(f"{v_axis.size} x {w_axis.size} cells is more than {MAX_MAP_CELLS:,}")
    rates = np.empty((v_axis.size, w_axis.size))
    verdict = np.empty((v_axis.size, w_axis.size), dtype="<U8")
    for j, w in enumerate(w_axis.tolist()):
        values, bounds = linear_spectra(replace(system, load=w), v_axis)
        rates[:, j] = np.max(values.real, axis=1)
        verdict[:, j] = [VERDICTS[spectrum_sign(v, b)] for v, b in zip(values, bounds, strict=True)]
        if progress is not None:
            progress(j + 1, w_axis.size)
    return MemoryStabilityMap(system, v_axis, w_axis, rates, verdict)
