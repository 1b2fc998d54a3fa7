"""A machine's occurrence map over its operating point: belt speed ``V`` and normal load ``W``.

The structure of a machine does not depend on where it runs; the contact does. At belt speed
``V`` [m/s] and normal load ``W`` [N] the contact's groups are (:mod:`stickslip.model.machine`,
``m_ref = M[c, c]``, ``k_ref = K[c, c]``)

    lambda(V, W) = (mu_s - mu_k) W / (V sqrt(m_ref k_ref)),    gamma = mu_k / (mu_s - mu_k),

and ``zeta`` and the dimensionless structure stay fixed. For the paper's Coulomb law that is
all: each cell is one ``lambda``. A velocity-dependent law also changes its *shape* with the
operating point (DESIGN.md section 8): the Stribeck law's ``v_s / V``, the linear law's slope
``delta = sigma W / (2 sqrt(m_ref k_ref))``, a measured table's speeds ``v_i / V``, the viscous
term ``sigma_v W / (2 sqrt(m k))``. Each cell therefore gets its own dimensionless law, built by
:meth:`Machine.with_operating_point(speed=V, load=W).slider() <stickslip.model.machine.Machine>`
from the SI law: the map is correct for every law, not only for Coulomb.

Every cell is one certified run of the exact engine (:func:`stickslip.analysis.simulation.simulate`)
from the start-up state, with the verdict, period [s] and amplitude [m] of its cycle.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.simulation import EngineOptions, simulate
from stickslip.analysis.verdict import VERDICTS
from stickslip.sweep.grid import Axis

if TYPE_CHECKING:
    import xarray as xr

    from stickslip.model.machine import Machine

FloatArray = NDArray[np.float64]

#: Largest number of cells of one operating map: each cell is a full certified run (about 10
#: ms for a 6-DOF machine), so 250,000 cells is about 40 minutes on one core.
MAX_CELLS = 250_000


@dataclass(frozen=True)
class OperatingMap:
    """Verdicts of a machine over belt speed and normal load (:func:`operating_map`).

    Attributes
    ----------
    speed : ndarray, shape (n_speed,)
        Belt speeds ``V``, m/s.
    load : ndarray, shape (n_load,)
        Normal loads ``W``, N.
    lam : ndarray, shape (n_speed, n_load)
        ``lambda`` of each cell.
    verdict : ndarray of str, shape (n_speed, n_load)
        Certified verdict of each cell (:data:`stickslip.analysis.verdict.VERDICTS`).
    period_s, amplitude_m, stick_ratio : ndarray, shape (n_speed, n_load)
        Of the certified cycle (s, m, -); NaN without a cycle.
    machine : dict
        The machine (:meth:`Machine.to_dict`), at its file's operating point.
    zeta, gamma : float
        The fixed groups of the contact.
    friction : str
        The SI law.
    """

    speed: FloatArray
    load: FloatArray
    lam: FloatArray
    verdict: NDArray[np.str_]
    period_s: FloatArray
    amplitude_m: FloatArray
    stick_ratio: FloatArray
    machine: dict[str, Any]
    zeta: float
    gamma: float
    friction: str

    def fractions(self) -> dict[str, float]:
        """Fraction of cells with each verdict."""
        n = self.verdict.size
        return {v: float(np.count_nonzero(self.verdict == v)) / n for v in VERDICTS}

    def to_xarray(self) -> xr.Dataset:
        """Dataset with coordinates ``speed`` [m/s] and ``load`` [N] and one variable per answer."""
        import xarray as xr

        dims = ("speed", "load")
        return xr.Dataset(
            {"verdict": (dims, self.verdict.astype(str)),
             "lambda": (dims, self.lam, {"long_name": "(mu_s - mu_k) W / (V sqrt(m_ref k_ref))"}),
             "period": (dims, self.period_s, {"units": "s"}),
             "amplitude": (dims, self.amplitude_m, {"units": "m",
                                                   "long_name": "half peak-to-peak contact displacement"}),
             "stick_ratio": (dims, self.stick_ratio, {"units": "1"})},
            coords={"speed": ("speed", self.speed, {"units": "m/s", "long_name": "belt speed V"}),
                    "load": ("load", self.load, {"units": "N", "long_name": "normal load W"})},
            attrs={"machine": str(self.machine.get("name")), "n_dof": int(self.machine["n_dof"]),
                   "contact_dof": int(self.machine["contact_dof"]), "zeta": self.zeta,
                   "gamma": self.gamma, "friction": self.friction},
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary: axes, fractions and the groups (no per-cell arrays)."""
        return {"n_speed": int(self.speed.size), "n_load": int(self.load.size),
                "speed_range_m_per_s": [float(self.speed.min()), float(self.speed.max())],
                "load_range_N": [float(self.load.min()), float(self.load.max())],
                "lambda_range": [float(self.lam.min()), float(self.lam.max())],
                "fractions": self.fractions(), "zeta": self.zeta, "gamma": self.gamma,
                "friction": self.friction, "machine": self.machine}

    def summary(self) -> str:
        """One paragraph: the grid and the share of each verdict."""
        parts = ", ".join(f"{k} {v:.1%}" for k, v in self.fractions().items() if v > 0)
        return (f"{self.machine.get('name')}: {self.speed.size} x {self.load.size} operating points, "
                f"V {self.speed.min():.4g} to {self.speed.max():.4g} m/s, W {self.load.min():.4g} "
                f"to {self.load.max():.4g} N (lambda {self.lam.min():.4g} to {self.lam.max():.4g}, "
                f"zeta={self.zeta:.4g}, gamma={self.gamma:.4g}, {self.friction}): {parts}")

    def plot(self, **kwargs: Any) -> Any:
        """The verdict map over speed and load, a ``PlotResult``.

        Drawn by :func:`stickslip.plot.operating.operating_map_plot` (keywords passed on).
        """
        from stickslip.plot.operating import operating_map_plot

        return operating_map_plot(self, **kwargs)


def operating_map(machine: Machine, speeds: Axis, loads: Axis, *,
                  options: EngineOptions | None = None,
                  progress: Callable[[int], None] | None = None) -> OperatingMap:
    """Certified verdict of ``machine`` at every belt speed and normal load of the grid.

    Parameters
    ----------
    machine : Machine
        The structure, contact and friction law in SI (its own speed and load are replaced).
    speeds : Axis
        Belt speeds ``V``, m/s (> 0).
    loads : Axis
        Normal loads ``W``, N (> 0).
    options : EngineOptions, optional
        Horizon and budgets of each run (dimensionless time).
    progress : callable, optional
        Called with the number of cells done after each row of speeds.

    Returns
    -------
    OperatingMap
        Verdict, ``lambda``, period [s], amplitude [m] and stick ratio per cell.

    Raises
    ------
    ValueError
        A speed or load that is not positive and finite, or more than :data:`MAX_CELLS` cells.
    """
    v = np.asarray(speeds.values, dtype=np.float64)
    w = np.asarray(loads.values, dtype=np.float64)
    for name, values, unit in (("speed", v, "m/s"), ("load", w, "N")):
        if not (np.all(np.isfinite(values)) and np.all(values > 0.0)):
            raise ValueError(f"every {name} must be positive and finite [{unit}]")
    if v.size * w.size > MAX_CELLS:
        raise ValueError(f"{v.size} x {w.size} = {v.size * w.size:,} operating points exceed "
                         f"{MAX_CELLS:,} (each is a full certified run); use fewer points")
    structure, _ = machine.to_dimensionless()  # independent of V and W
    shape = (v.size, w.size)
    lam = np.empty(shape)
    verdict = np.empty(shape, dtype=object)
    period, amplitude, stick = (np.full(shape, np.nan) for _ in range(3))
    zeta = gamma = float("nan")
    for i, speed in enumerate(v.tolist()):
        for j, load in enumerate(w.tolist()):
            point = machine.with_operating_point(speed=speed, load=load)
            slider = point.slider()  # lambda and the law's own shape at (V, W)
            result = simulate(structure, slider, options=options, record=False)
            reference = point.reference_system()
            lam[i, j], verdict[i, j] = slider.lam, result.verdict.value
            period[i, j] = result.period * reference.time_scale
            amplitude[i, j] = result.amplitude * reference.length_scale
            stick[i, j] = result.stick_ratio
            zeta, gamma = structure.zeta, slider.gamma
        if progress is not None:
            progress((i + 1) * w.size)
    return OperatingMap(v, w, lam, verdict.astype(str), period, amplitude, stick, machine.to_dict(),
                        float(zeta), float(gamma), machine.friction.law)
