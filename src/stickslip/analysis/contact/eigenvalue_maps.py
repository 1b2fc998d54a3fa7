"""Stability of steady sliding over two parameters: (mu, speed), (mu, load) or (mu, any).

Speed and load enter the linearisation of :mod:`stickslip.analysis.contact.friction_coupling` only
through the friction law's slope term ``mu'(V) N_0`` on the tangential DOF: with the Coulomb
law (``mu' = 0``) steady sliding's eigenvalues depend on neither, and a map over speed is
the same at every speed. A structural parameter changes the matrices themselves: build one
:class:`~stickslip.analysis.contact.friction_coupling.FrictionCoupledSystem` per value.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.blas_threads import one_blas_thread
from stickslip.analysis.contact.critical_coefficient import MU_MAX, critical_friction
from stickslip.analysis.contact.friction_coupling import (
    FrictionCoupledSystem,
    coupled_system,
    track_branches,
    verdict_of,
)

if TYPE_CHECKING:
    from stickslip.model.contact import Contact
    from stickslip.model.machine import Machine

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


@dataclass(frozen=True)
class RootLocus:
    """Eigenvalue branches over the friction coefficient, for :func:`root_locus_plot`.

    Attributes
    ----------
    mu : ndarray, shape (k,)
        Friction coefficients, dimensionless.
    eigenvalues : ndarray of complex, shape (k, 2n)
        Column ``j`` is one branch followed by continuity, 1/s.
    critical_mu, critical_mu_undamped : float or None
        Marked on the plot.
    """

    mu: FloatArray
    eigenvalues: ComplexArray
    critical_mu: float | None = None
    critical_mu_undamped: float | None = None

    def plot(self, **kwargs: Any) -> Any:
        """Frequencies and real parts against mu (:func:`stickslip.plot.stability.root_locus_plot`)."""
        from stickslip.plot.stability import root_locus_plot

        return root_locus_plot(self, **kwargs)


@one_blas_thread
def root_locus(system: FrictionCoupledSystem, mus: Sequence[float] | FloatArray) -> RootLocus:
    """Eigenvalues of the linearisation along ``mus``, branches followed by continuity.

    Parameters
    ----------
    system : FrictionCoupledSystem
        The linearisation's data.
    mus : sequence of float
        Increasing friction coefficients, dimensionless.

    Returns
    -------
    RootLocus
        With the critical coefficients of ``system`` and of its undamped version in the range.
    """
    grid = np.asarray(mus, dtype=float)
    top = float(grid[-1]) if grid.size and grid[-1] > 0 else MU_MAX
    return RootLocus(grid, track_branches(system, grid),
                     critical_friction(system, mu_max=top, n_scan=200).mu,
                     critical_friction(system.undamped(), mu_max=top, n_scan=200).mu)


@dataclass(frozen=True)
class StabilityMap:
    """Growth rate of steady sliding over (mu, a second parameter), for :func:`stability_map_plot`.

    Attributes
    ----------
    mu : ndarray, shape (k,)
        Friction coefficients (dimensionless).
    values : ndarray, shape (j,)
        The second parameter's values.
    name : str
        Its name and unit (``"speed [m/s]"``).
    growth : ndarray, shape (j, k)
        Largest real part of the eigenvalues, 1/s (> 0: unstable).
    verdict : ndarray of int, shape (j, k)
        +1 proven unstable, -1 proven stable, 0 neutral within round-off.
    """

    mu: FloatArray
    values: FloatArray
    name: str
    growth: FloatArray
    verdict: NDArray[np.int64]

    def plot(self, **kwargs: Any) -> Any:
        """The map (:func:`stickslip.plot.stability.stability_map_plot`)."""
        from stickslip.plot.stability import stability_map_plot

        return stability_map_plot(self, **kwargs)


@one_blas_thread
def stability_map(systems: Sequence[FrictionCoupledSystem], values: Sequence[float] | FloatArray,
                  mus: Sequence[float] | FloatArray, name: str) -> StabilityMap:
    """Growth rate and verdict of steady sliding on the grid ``systems x mus``.

    Parameters
    ----------
    systems : sequence of FrictionCoupledSystem
        One per value of the second parameter (e.g. :func:`coupled_system` at each speed:
        speed changes only the law's slope; with the Coulomb law every row is the same).
    values : sequence of float
        The second parameter's values, one per system.
    mus : sequence of float
        Friction coefficients, dimensionless.
    name : str
        The second parameter's name and unit.

    Returns
    -------
    StabilityMap
        The grid.
    """
    grid = np.asarray(mus, dtype=float)
    growth = np.empty((len(systems), grid.size))
    verdict = np.empty((len(systems), grid.size), dtype=np.int64)
    for i, system in enumerate(systems):
        for j, mu in enumerate(grid):
            vals, bounds = system.eigenvalues(float(mu))
            growth[i, j] = float(np.max(vals.real))
            verdict[i, j] = verdict_of(vals, bounds)
    return StabilityMap(grid, np.asarray(values, dtype=float), name, growth, verdict)


@dataclass(frozen=True)
class OperatingRanges:
    """Verdict of steady sliding along speed and along load, each with the law's own ``mu(V)``.

    Attributes
    ----------
    speeds, loads : ndarray
        The grids, m/s and N.
    speed_verdicts, load_verdicts : ndarray of int
        +1 proven unstable, -1 proven stable, 0 neutral within round-off, at each grid value.
    """

    speeds: FloatArray
    speed_verdicts: NDArray[np.int64]
    loads: FloatArray
    load_verdicts: NDArray[np.int64]

    @staticmethod
    def _ranges(grid: FloatArray, verdicts: NDArray[np.int64]) -> list[list[float]]:
        out: list[list[float]] = []
        for i, v in enumerate(verdicts):
            if v == 1 and i and verdicts[i - 1] == 1:
                out[-1][1] = float(grid[i])
            elif v == 1:
                out.append([float(grid[i]), float(grid[i])])
        return out

    def unstable_speeds(self) -> list[list[float]]:
        """``[first, last]`` grid speeds (m/s) of each run of unstable grid points."""
        return self._ranges(self.speeds, self.speed_verdicts)

    def unstable_loads(self) -> list[list[float]]:
        """``[first, last]`` grid loads (N) of each run of unstable grid points."""
        return self._ranges(self.loads, self.load_verdicts)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the grids' ends and sizes and the unstable runs."""
        return {"speed_grid_m_per_s": [float(self.speeds[0]), float(self.speeds[-1]), len(self.speeds)],
                "unstable_speeds_m_per_s": self.unstable_speeds(),
                "load_grid_N": [float(self.loads[0]), float(self.loads[-1]), len(self.loads)],
                "unstable_loads_N": self.unstable_loads()}


@one_blas_thread
def operating_ranges(machine: Machine, contact: Contact | None, *, normal_dof: int | None = None,
                     decades: float = 1.0, points: int = 41) -> OperatingRanges:
    """Where along speed and load (the machine's law, ``mu = mu(V)``) steady sliding is unstable.

    Parameters
    ----------
    machine : Machine
        Structure, law and operating point ``(V, W)``.
    contact : Contact or None
        The contact (normal DOF and spring).
    normal_dof : int, optional
        The normal DOF's index when it differs from the contact's (reduction).
    decades : float
        The grids run from ``V / 10**decades`` to ``V * 10**decades`` (same for ``W``), log-spaced.
    points : int
        Grid points along each.

    Returns
    -------
    OperatingRanges
        The verdicts; a run of unstable grid points is resolved to the grid's spacing.
    """
    factors = np.logspace(-decades, decades, points)
    speeds, loads = machine.speed * factors, machine.load * factors
    sv = [_verdict_at(machine, contact, normal_dof, speed=float(v)) for v in speeds]
    lv = [_verdict_at(machine, contact, normal_dof, load=float(w)) for w in loads]
    return OperatingRanges(speeds, np.array(sv, dtype=np.int64), loads, np.array(lv, dtype=np.int64))


def _verdict_at(machine: Machine, contact: Contact | None, normal_dof: int | None,
                **point: float) -> int:
    system, mu = coupled_system(machine, contact, normal_dof=normal_dof, **point)
    return verdict_of(*system.eigenvalues(mu))
