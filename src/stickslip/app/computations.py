"""The web app's computations, cached by Streamlit: all of them calls of the public API.

Each function takes hashable SI or dimensionless values (:func:`stickslip.app.inputs.si_key`)
so that Streamlit's ``cache_data`` recognises a computation it has done.
"""

from __future__ import annotations

import math
from typing import Any, Literal

import numpy as np
import streamlit as st

from stickslip.analysis.continuation import ContinuationResult, ContinuationSystem, continue_cycles
from stickslip.analysis.design import design_foundation
from stickslip.analysis.simulation import EngineOptions, SimulationResult, simulate
from stickslip.analysis.stick_slip_tuning import optimal_foundation_stick_slip
from stickslip.app.inputs import FoundationKey, SiKey, system_from_key
from stickslip.model.dva import DvaSpec
from stickslip.model.friction import CoulombFriction, FrictionLaw
from stickslip.model.parameters import Foundation, Slider
from stickslip.model.physical import PhysicalSystem
from stickslip.model.structure import Structure, elastic_foundation, rigid_base
from stickslip.sweep.basin import BasinResult, basin_stability, equilibrium_state, sample_box
from stickslip.sweep.execution import ExecutionOptions
from stickslip.sweep.occurrence import OccurrenceMap, occurrence_map

#: Occurrence map around the operating point: lambda from lam/SPAN to lam*SPAN (log-spaced),
#: zeta from 0 to twice the operating zeta.
MAP_SHAPE = (30, 12)
MAP_LAMBDA_SPAN = 10.0
MAP_ZETA_FLOOR = 0.05  # zeta range used when the slider has no damping
#: Time horizon of the time-history figures, dimensionless tau.
PLOT_HORIZON = (40.0, 3000.0)
#: Disturbed starts per basin, and their box about steady sliding (dimensionless, the knocks of
#: docs/disturbances.md): ``xi - xi_eq`` in units of V/omega_n, ``xi'`` in units of V.
BASIN_SAMPLES = 4000
BASIN_XI = 6.0
BASIN_V = (-4.0, 1.5)
#: Bifurcation diagram in lambda: from half the smallest to twice the largest of the operating
#: lambda and the onsets of stick-slip, within a factor BIFURCATION_LIMIT of the operating lambda.
BIFURCATION_MARGIN = 2.0
BIFURCATION_LIMIT = 100.0
#: Bounds of each continuation (those of ``stickslip continue``): random starts of the cycle
#: search, longest cycle (stick phases), steps per branch.
BIFURCATION_SEEDS = 12
BIFURCATION_MAX_PERIOD = 2
BIFURCATION_MAX_STEPS = 400

@st.cache_data(show_spinner="Running the design procedure (Fig. 16)...", max_entries=128)
def design_report(key: SiKey) -> dict[str, Any]:
    """:func:`design_foundation` of the system, as its JSON dictionary (SI units)."""
    return design_foundation(system_from_key(key)).to_dict()


@st.cache_data(show_spinner="Simulating the operating point...", max_entries=64)
def operating_point_runs(lam: float, zeta: float, gamma: float, foundation: FoundationKey,
                         friction: FrictionLaw | None = None) -> dict[str, SimulationResult]:
    """Rigid base and foundation runs from the startup state, recorded for the figures.

    ``friction`` is the dimensionless law of the contact (the paper's Coulomb law by default).

    Both run to a common horizon: one and a half times the longer of the two times needed
    to certify the verdict (so a stick-slip cycle shows at least twice), within
    :data:`PLOT_HORIZON`.
    """
    slider = Slider(lam, gamma=gamma, friction=friction or CoulombFriction())
    structures = _structures(zeta, foundation)
    certified = max(simulate(s, slider, record=False).t_end for s in structures.values())
    horizon = min(max(PLOT_HORIZON[0], 1.5 * certified), PLOT_HORIZON[1])
    return {name: simulate(s, slider, options=EngineOptions(t_max=horizon),
                           run_to_t_max=True)
            for name, s in structures.items()}


def _structures(zeta: float, foundation: FoundationKey) -> dict[str, Structure]:
    """The machine without and with its foundation (dimensionless)."""
    return {"rigid base": rigid_base(zeta),
            "with foundation": elastic_foundation(zeta, Foundation(*foundation))}


@st.cache_data(show_spinner="Sampling disturbed starts...", max_entries=16)
def basin_runs(lam: float, zeta: float, gamma: float, foundation: FoundationKey,
               friction: FrictionLaw | None = None) -> dict[str, BasinResult]:
    """Certified verdicts of :data:`BASIN_SAMPLES` disturbed starts, without and with the foundation.

    The starts are uniform in ``xi - xi_eq`` in ``[-BASIN_XI, BASIN_XI]`` and ``xi'`` in
    :data:`BASIN_V` about steady sliding (the foundation, if any, at its steady-sliding
    state), with one seed, so both machines are knocked alike (issue 13; ``stickslip basin``).
    """
    slider = Slider(lam, gamma=gamma, friction=friction or CoulombFriction())
    results = {}
    for name, structure in _structures(zeta, foundation).items():
        xi_eq = float(equilibrium_state(structure, slider)[0])
        box = {"xi": (xi_eq - BASIN_XI, xi_eq + BASIN_XI), "v": BASIN_V}
        states = sample_box(structure, slider, BASIN_SAMPLES, box, seed=1)
        results[name] = basin_stability(structure, slider, states)
    return results


@st.cache_data(show_spinner="Computing the occurrence maps...", max_entries=64)
def occurrence_maps(lam: float, zeta: float, gamma: float, foundation: FoundationKey | None,
                    friction: FrictionLaw | None = None) -> dict[str, OccurrenceMap]:
    """Verdicts on a ``lambda x zeta`` grid around the operating point (paper Figs. 8, 11).

    Two maps: the rigid base, and the foundation (the given one, fixed in SI units, or the
    one of Eqs. 28-30 tuned at every ``zeta`` of the grid); every cell with the friction law
    ``friction`` (dimensionless, as at the operating point).
    """
    n_lam, n_zeta = MAP_SHAPE
    lams = np.geomspace(lam / MAP_LAMBDA_SPAN, lam * MAP_LAMBDA_SPAN, n_lam)
    top = 2.0 * zeta if zeta > 0.0 else MAP_ZETA_FLOOR
    zetas = (np.arange(n_zeta) + 0.5) * (top / n_zeta)  # cell centres; edges 0 .. top
    dva = DvaSpec("optimal") if foundation is None else DvaSpec("explicit", Foundation(*foundation))
    return {name: occurrence_map(lams, zetas, spec, gamma, friction=friction,
                                 execution=ExecutionOptions(backend="serial"))
            for name, spec in (("rigid base", DvaSpec("none")), ("with foundation", dva))}


@st.cache_data(show_spinner="Searching the stick-slip-optimal foundation...", max_entries=32)
def stick_slip_optimum(zeta: float, gamma: float, lam_max: float) -> dict[str, Any]:
    """:func:`optimal_foundation_stick_slip` at ``(zeta, gamma)``, as its dictionary."""
    return optimal_foundation_stick_slip(zeta, gamma, lam_max=lam_max).to_dict()


LambdaAxis = Literal["speed", "load"]


def lambda_axis(system: PhysicalSystem) -> LambdaAxis | None:
    """The SI quantity that varying ``lambda`` at the operating point's friction law stands for.

    ``lambda = (mu_s - mu_k) W / (V sqrt(m k))`` (Eq. 22) moves with the belt speed ``V`` and the
    normal load ``W``, and nothing else does except the dimensionless friction law
    (:meth:`~stickslip.model.physical.PhysicalFriction.dimensionless`): ``u = v / V`` for a
    Stribeck or a table law, ``delta = sigma W / (2 sqrt(m k))`` for a linear one. A
    continuation in ``lambda`` holds that law fixed, so it is a change of belt speed exactly
    when the law does not depend on ``V`` (Coulomb, linear), else of the load when the law does
    not depend on ``W`` (Coulomb, table, Stribeck without viscous slope), else of neither
    (None: Stribeck with a viscous slope).
    """
    s = system
    law = s.friction.dimensionless(s.mass, s.stiffness, s.mu_s, s.mu_k, s.load, s.speed)
    if s.friction.dimensionless(s.mass, s.stiffness, s.mu_s, s.mu_k, s.load, 2.0 * s.speed) == law:
        return "speed"
    if s.friction.dimensionless(s.mass, s.stiffness, s.mu_s, s.mu_k, 2.0 * s.load, s.speed) == law:
        return "load"
    return None


def bifurcation_range(lam: float, onsets: list[float | None]) -> tuple[float, float]:
    """The range of ``lambda`` of the bifurcation diagram around the operating point.

    From :data:`BIFURCATION_MARGIN` below the smallest to :data:`BIFURCATION_MARGIN` above the
    largest of ``lam`` and the finite ``onsets`` (critical lambdas of the design report), so
    the operating point and the births of the stick-slip cycles are inside; clipped to a
    factor :data:`BIFURCATION_LIMIT` either side of ``lam``.
    """
    values = [lam] + [x for x in onsets if x is not None and math.isfinite(x) and x > 0.0]
    lo = max(min(values) / BIFURCATION_MARGIN, lam / BIFURCATION_LIMIT)
    hi = min(max(values) * BIFURCATION_MARGIN, lam * BIFURCATION_LIMIT)
    return lo, hi


@st.cache_data(show_spinner="Continuing the periodic motions...", max_entries=16)
def bifurcation_diagrams(lam_range: tuple[float, float], lam: float, zeta: float, gamma: float,
                         foundation: FoundationKey, friction: FrictionLaw | None = None
                         ) -> dict[str, ContinuationResult]:
    """:func:`continue_cycles` in ``lambda`` over ``lam_range``, without and with the foundation.

    Stick-slip cycles and slip oscillations, stable and unstable, steady sliding and the
    events (issue 20), for the machine at ``(zeta, gamma)`` with the dimensionless friction law
    ``friction`` (Coulomb by default) and the foundation ``(M, K, zeta_a)``; the bounds of
    each run are those of ``stickslip continue`` (:data:`BIFURCATION_SEEDS`,
    :data:`BIFURCATION_MAX_PERIOD`, :data:`BIFURCATION_MAX_STEPS`).
    """
    law = friction or CoulombFriction()
    return {name: continue_cycles(ContinuationSystem(lam, zeta, gamma, found, law), "lam", lam_range,
                                  max_period=BIFURCATION_MAX_PERIOD, seeds=BIFURCATION_SEEDS,
                                  max_steps=BIFURCATION_MAX_STEPS)
            for name, found in (("rigid base", None), ("with foundation", Foundation(*foundation)))}


def si_of_lambda(system: PhysicalSystem, axis: LambdaAxis, lam: float) -> float:
    """The belt speed (m/s, at the operating load) or the load (N, at the operating speed) at
    which the dimensionless ``lambda`` takes the value ``lam`` (Eq. 22)."""
    return system.speed_for_lambda(lam) if axis == "speed" else system.load_for_lambda(lam)


def length_scale_at(system: PhysicalSystem, axis: LambdaAxis, lam: float) -> float:
    """Metres per unit of the dimensionless amplitude at ``lam``: ``V / omega_n`` (Eqs. 15-16)
    with the belt speed ``V`` of that point (the operating one when the load varies)."""
    speed = system.speed_for_lambda(lam) if axis == "speed" else system.speed
    return speed / system.natural_frequency
