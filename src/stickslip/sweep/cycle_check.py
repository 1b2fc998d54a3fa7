"""The map's cells get the answers :func:`stickslip.simulate` gives: the same minimal, proven
cycle, and no steady sliding certified for a smooth law's interpolant only.

The map kernel certifies a stick-slip candidate when a breakaway state repeats to
``cycle_tol`` after ``k`` stick phases. With one stick phase (``k = 1``) that is the minimal
period; with ``k >= 2`` on a structure of two or more degrees of freedom, ``k`` may be a
multiple of the true period (the return map's multipliers complex or near -1: states two
phases apart agree before neighbours do). Such cells are run again through
:func:`stickslip.simulate`, which proves the minimal cycle
(:mod:`stickslip.analysis.cycle_proof`) or says ``undetermined``; their summaries are
replaced by its answer. Cells of one degree of freedom never need it (the breakaway state is
unique), and the paper's 2-DOF maps have no such cell, so their answers stay bit for bit.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.interpolant_margin import band_slopes_at_belt_speed
from stickslip.analysis.simulation import EngineOptions, simulate
from stickslip.analysis.stability import slip_matrix
from stickslip.analysis.verdict import RunStatus
from stickslip.kernel import engine
from stickslip.model.friction import FrictionLaw
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure
from stickslip.sweep.executors import CellBatch, StructureSet


def cells_to_prove(structures: StructureSet, int_summary: NDArray[np.int64]) -> NDArray[np.int64]:
    """Flat indices of the cells whose candidate spans two or more stick phases on N DOF."""
    if structures.masses.shape[1] < 2:
        return np.zeros(0, dtype=np.int64)
    candidate = ((int_summary[:, engine.I_STATUS] == engine.STATUS_CYCLE)
                 & (int_summary[:, engine.I_CYCLE_K] >= 2))
    return np.flatnonzero(candidate).astype(np.int64)


def prove_map_cycles(structures: StructureSet, batch: CellBatch,
                     float_summary: NDArray[np.float64], int_summary: NDArray[np.int64],
                     options: EngineOptions,
                     progress: Callable[[int, int], None] | None = None) -> int:
    """Replace every multi-phase candidate of a map by :func:`simulate`'s proven cycle, in place.

    Parameters
    ----------
    structures : StructureSet
        The map's structures (contact first).
    batch : CellBatch
        Every cell of the map (``structure_index``, ``lams``, ``gamma``, the law or laws).
    float_summary, int_summary : ndarray
        The kernel's per-cell summaries, changed in place for the cells proven or refused.
    options : EngineOptions
        The map's engine options (the same runs as the map's).
    progress : callable, optional
        ``progress(done, total)`` over the cells checked.

    Returns
    -------
    int
        The number of cells checked.
    """
    cells = cells_to_prove(structures, int_summary)
    for done, c in enumerate(cells.tolist()):
        j = int(batch.structure_index[c])
        structure = Structure(structures.masses[j], structures.dampings[j],
                              structures.stiffnesses[j], name="map cell")
        law = batch.laws[c] if batch.laws is not None else batch.friction
        slider = Slider(float(batch.lams[c]), gamma=float(batch.gamma), friction=law)
        result = simulate(structure, slider, options=options, record=False)
        int_summary[c, engine.I_STATUS] = result.status.code
        int_summary[c, engine.I_CYCLE_K] = result.cycle_length
        float_summary[c, engine.F_PERIOD] = result.period
        float_summary[c, engine.F_AMPLITUDE] = result.amplitude
        float_summary[c, engine.F_XI_MIN], float_summary[c, engine.F_XI_MAX] = result.xi_range
        float_summary[c, engine.F_STICK_RATIO] = result.stick_ratio
        float_summary[c, engine.F_CYCLE_MAX_VELOCITY] = result.cycle_max_velocity
        float_summary[c, engine.F_CYCLE_MISMATCH] = result.cycle_mismatch
        if progress is not None:
            progress(done + 1, cells.size)
    return int(cells.size)


def withhold_interpolant_steady(structures: StructureSet, batch: CellBatch,
                                int_summary: NDArray[np.int64]) -> int:
    """Withhold, in place, the certificates that hold for a law's interpolant only.

    The cells' form of
    :func:`~stickslip.analysis.interpolant_margin.interpolant_mismatch`: with the law's growth
    rate at steady sliding (its exact slope at the belt speed; "stable" beyond ``1000 eps
    ||A||_F``) and the interpolant's (its band's slope), a cell certified steady where the
    law's is not stable and the interpolant's is gets
    :attr:`~stickslip.analysis.verdict.RunStatus.INTERPOLANT_STEADY`, and a cell certified a
    slip oscillation where the law's is stable and the interpolant's is not gets
    :attr:`~stickslip.analysis.verdict.RunStatus.INTERPOLANT_OSCILLATION` (both
    ``undetermined``). Exact laws (Coulomb, linear, tables) are not touched: the engine runs
    the law itself.

    Parameters
    ----------
    structures : StructureSet
        The cells' structures (contact first).
    batch : CellBatch
        Every cell (``structure_index``, ``lams``, ``gamma``, the law or laws).
    int_summary : ndarray
        The kernel's per-cell summaries, changed in place.

    Returns
    -------
    int
        The number of certificates withheld.
    """
    status = int_summary[:, engine.I_STATUS]
    cells = np.flatnonzero((status == engine.STATUS_STEADY) | (status == engine.STATUS_OSCILLATION))
    laws = batch.laws if batch.laws is not None else (batch.friction,)
    if cells.size == 0 or all(law.exact for law in laws):
        return 0
    slopes: dict[tuple[float, FrictionLaw], tuple[float, float]] = {}
    exact_stack, band_stack = [], []
    for c in cells.tolist():
        law = batch.laws[c] if batch.laws is not None else batch.friction
        lam = float(batch.lams[c])
        if (lam, law) not in slopes:
            slopes[(lam, law)] = _exact_and_band_slope(law, lam, float(batch.gamma))
        s_exact, s_band = slopes[(lam, law)]
        j = int(batch.structure_index[c])
        structure = Structure(structures.masses[j], structures.dampings[j],
                              structures.stiffnesses[j], name="map cell")
        exact_stack.append(slip_matrix(structure, s_exact))
        band_stack.append(slip_matrix(structure, s_band))
    exact = np.asarray(exact_stack)
    g_exact = np.max(np.linalg.eigvals(exact).real, axis=1)
    g_band = np.max(np.linalg.eigvals(np.asarray(band_stack)).real, axis=1)
    law_stable = g_exact < -1000.0 * np.finfo(float).eps * np.linalg.norm(exact, axis=(1, 2))
    exact_law = np.array([(batch.laws[c] if batch.laws is not None else batch.friction).exact
                          for c in cells.tolist()], dtype=bool)
    steady = (status[cells] == engine.STATUS_STEADY) & ~law_stable & (g_band < 0.0) & ~exact_law
    oscillation = ((status[cells] == engine.STATUS_OSCILLATION) & law_stable & (g_band >= 0.0)
                   & ~exact_law)
    int_summary[cells[steady], engine.I_STATUS] = RunStatus.INTERPOLANT_STEADY.code
    int_summary[cells[oscillation], engine.I_STATUS] = RunStatus.INTERPOLANT_OSCILLATION.code
    return int(steady.sum() + oscillation.sum())


def _exact_and_band_slope(law: FrictionLaw, lam: float, gamma: float) -> tuple[float, float]:
    """The law's slope at ``u = 1`` and its interpolant's there (the band's; the steeper side
    when ``u = 1`` is a node, as :func:`~stickslip.analysis.stability.one_sided_slopes`)."""
    if law.exact:
        return 0.0, 0.0  # not used: exact laws are skipped
    band = min(band_slopes_at_belt_speed(law, lam, gamma))
    return float(law.slope_at(1.0, lam, gamma)), band
