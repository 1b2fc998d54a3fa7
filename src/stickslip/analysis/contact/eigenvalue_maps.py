"""Stability of steady sliding over two parameters: (mu, speed), (mu, load) or (mu, any).

Speed and load enter the linearisation of :mod:`stickslip.analysis.contact.friction_coupling` only
through the friction law's slope term ``mu'(V) N_0`` on the tangential DOF: with the Coulomb
law (``mu' = 0``) steady sliding's eigenvalues depend on neither, and a map over speed is
the same at every speed. A structural parameter changes the matrices themselves: build one
:class:`~stickslip.analysis.contact.friction_coupling.FrictionCoupledSystem` per value.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
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
    speed_ranges, load_ranges : list of [float, float]
        Each run of unstable grid values, its ends moved to the boundary (m/s, N) where the
        neighbour beyond is proven stable (Brent's method on the growth rate, to
        ``BOUNDARY_RTOL``); an end at the grid's end or beside a neutral value stays there.
    """

    speeds: FloatArray
    speed_verdicts: NDArray[np.int64]
    loads: FloatArray
    load_verdicts: NDArray[np.int64]
    speed_ranges: list[list[float]]
    load_ranges: list[list[float]]

    def unstable_speeds(self) -> list[list[float]]:
        """``[first, last]`` speeds (m/s) of each unstable range (see ``speed_ranges``)."""
        return [list(r) for r in self.speed_ranges]

    def unstable_loads(self) -> list[list[float]]:
        """``[first, last]`` loads (N) of each unstable range (see ``load_ranges``)."""
        return [list(r) for r in self.load_ranges]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the grids' ends and sizes and the unstable ranges."""
        return {"speed_grid_m_per_s": [float(self.speeds[0]), float(self.speeds[-1]), len(self.speeds)],
                "unstable_speeds_m_per_s": self.unstable_speeds(),
                "load_grid_N": [float(self.loads[0]), float(self.loads[-1]), len(self.loads)],
                "unstable_loads_N": self.unstable_loads()}


#: Relative accuracy of a stability boundary between two grid values (Brent's method).
BOUNDARY_RTOL = 1e-9


def unstable_ranges(grid: FloatArray, verdicts: NDArray[np.int64],
                    growth: Callable[[float], float]) -> list[list[float]]:
    """The runs of unstable grid values, their ends refined to the stability boundary.

    Parameters
    ----------
    grid : ndarray
        Increasing positive values (a speed in m/s or a load in N).
    verdicts : ndarray of int
        +1 proven unstable, -1 proven stable, 0 neutral, at each grid value.
    growth : callable
        The largest real part of the eigenvalues (1/s) at a value: positive where unstable.

    Returns
    -------
    list of [float, float]
        One ``[start, end]`` per run; an end between an unstable and a proven stable grid
        value is the zero of ``growth`` between them (in ``log`` of the value, to
        ``BOUNDARY_RTOL``), otherwise the grid value.
    """
    from scipy.optimize import brentq

    def edge(stable: float, unstable: float) -> float:
        a, b = math.log(stable), math.log(unstable)
        return math.exp(brentq(lambda x: growth(math.exp(x)), min(a, b), max(a, b),
                               xtol=BOUNDARY_RTOL, rtol=BOUNDARY_RTOL))

    out: list[list[float]] = []
    n = len(grid)
    i = 0
    while i < n:
        if verdicts[i] != 1:
            i += 1
            continue
        j = i
        while j + 1 < n and verdicts[j + 1] == 1:
            j += 1
        lo = (edge(float(grid[i - 1]), float(grid[i])) if i > 0 and verdicts[i - 1] == -1
              else float(grid[i]))
        hi = (edge(float(grid[j + 1]), float(grid[j])) if j + 1 < n and verdicts[j + 1] == -1
              else float(grid[j]))
        out.append([lo, hi])
        i = j + 1
    return out


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
        The verdicts on the grids, and the unstable ranges with their ends at the stability
        boundaries (:func:`unstable_ranges`).
    """
    factors = np.logspace(-decades, decades, points)
    speeds, loads = machine.speed * factors, machine.load * factors
    sv = np.array([_verdict_at(machine, contact, normal_dof, speed=float(v)) for v in speeds],
                  dtype=np.int64)
    lv = np.array([_verdict_at(machine, contact, normal_dof, load=float(w)) for w in loads],
                  dtype=np.int64)

    def growth(**point: float) -> float:
        system, mu = coupled_system(machine, contact, normal_dof=normal_dof, **point)
        return float(np.max(system.eigenvalues(mu)[0].real))

    return OperatingRanges(speeds, sv, loads, lv,
                           unstable_ranges(speeds, sv, lambda v: growth(speed=v)),
                           unstable_ranges(loads, lv, lambda w: growth(load=w)))


def _verdict_at(machine: Machine, contact: Contact | None, normal_dof: int | None,
                **point: float) -> int:
    system, mu = coupled_system(machine, contact, normal_dof=normal_dof, **point)
    return verdict_of(*system.eigenvalues(mu))
