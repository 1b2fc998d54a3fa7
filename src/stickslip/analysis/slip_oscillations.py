"""Slip oscillations at one parameter point, stable and unstable, with or without a Hopf point.

A slip oscillation is a periodic motion that never sticks (velocity-dependent friction only:
with the Coulomb law, or a linear law that does not reach its floor at zero friction, slip-I
is a linear system and has none). It is a fixed point of the map ``P`` between two velocity maxima of the
slider on the section ``xi'' = 0``, ``xi''' < 0``
(:class:`~stickslip.analysis._periodic_sections.SlipSection`:
unknowns the peak velocity ``xi'`` and the other DOFs' coordinates, the map evaluated by the
exact engine), refined by Newton's method; its Floquet multipliers are the eigenvalues of
``D P`` (central differences) and it is stable when all lie inside the unit circle.

Where the seeds come from (all of them refined by the same Newton iteration, so a seed only
decides *which* cycles are looked at, never what is reported):

* **forward runs** from random states around steady sliding: a run the engine certifies as a
  slip oscillation ends on a stable one (an attractor);
* **the section scan** (one degree of freedom, where the phase space is the plane): ``P`` is
  increasing on the one-dimensional section, so every cycle is a sign change of
  ``P(y) - y`` along the peak velocity ``y`` in ``(0, 1)``; a run that reaches the belt
  speed counts as ``P(y) > y`` (it grew out of every slip oscillation). The sign changes are
  bracketed on a grid (even and geometric, with the deepest dips of ``|P(y) - y| / y``
  searched for a pair of cycles in one cell: :func:`_section_scan`) and each is followed by
  **backward-time iteration** of the map,
  ``y <- P^-1(y)`` (``P`` inverted by bisection: the backward-time run on the section,
  evaluated with the forward engine), which converges to an unstable cycle as a forward run
  converges to a stable one;
* **the trap-certificate cycle** of the basin code (one DOF): the slip trap region
  (:mod:`stickslip.kernel.certificate`) starts inside the unstable cycle and the slip escape
  region (:mod:`stickslip.kernel.outer_certificate`) just outside it, both on the ray
  ``xi' = 0, xi > xi_eq``; the midpoint, carried to its next velocity maximum, is a seed;
* **modal starts** (more than one DOF): the least-damped mode of the slip-I linearisation,
  scaled to peak velocities spread over ``(0, 1)``; where the map's peak velocity changes
  sign along that family a start of Newton's method (an unstable cycle of several DOFs is a
  saddle: backward runs do not reach it).

All quantities are dimensionless (``tau``, ``V/omega_n``, belt speed 1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis._periodic_sections import SlipSection
from stickslip.analysis.simulation import EngineOptions, simulate
from stickslip.analysis.stability import one_sided_slopes, slip_matrix
from stickslip.analysis.verdict import Verdict
from stickslip.model._validate import random_seed
from stickslip.model.friction import CoulombFriction, LinearFriction
from stickslip.model.initial import InitialState
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure, to_user_order

FloatArray = NDArray[np.float64]

#: Peak velocities of the section scan (one DOF): the grid on which ``P(y) - y`` is bracketed,
#: evenly spaced in ``(0, 0.99]`` and, for the small cycles near a Hopf point, geometrically
#: from ``SCAN_SMALLEST`` up to the even grid's second point (:data:`SCAN_GEOMETRIC` points,
#: ratio about 1.3; above it the even grid is the finer).
SCAN_POINTS = 40
SCAN_GEOMETRIC = 24
SCAN_SMALLEST = 1e-4
#: Local minima of ``|P(y) - y| / y`` searched for a dip through zero (two cycles in one
#: cell of the grid give no sign change there), the deepest first, and the map's evaluations
#: per search.
SCAN_DIPS = 2
SCAN_DIP_EVALUATIONS = 12
#: Backward iterations of the map per bracket (each one a bisection of ``P``).
BACKWARD_STEPS = 4
#: Peak velocities along the least-damped mode screened for a sign change (more than one DOF).
MODAL_STARTS = 19
#: Newton iterations of the refinement.
NEWTON_STEPS = 20
#: Peak velocities below this are steady sliding (the section's trivial fixed point).
STEADY = 1e-7
#: Two cycles are the same when their section states agree to this (relative).
SAME_CYCLE = 1e-6


@dataclass(frozen=True)
class SlipOscillation:
    """One slip oscillation (dimensionless: ``tau``, ``V/omega_n``, belt speed 1).

    Attributes
    ----------
    state : ndarray, shape (2 n_dof,)
        The full state at the slider's velocity maximum (shifted coordinates, the user's DOF
        order).
    peak_velocity : float
        The slider's largest velocity ``xi'`` over the cycle (below the belt speed, 1).
    period : float
        Period in ``tau``.
    amplitude : float
        Half the peak-to-peak of the slider's ``xi`` over the cycle.
    multipliers : ndarray of complex
        Floquet multipliers of the velocity-maximum map (``2 n_dof - 1`` of them).
    stable : bool
        Every multiplier inside the unit circle.
    found_by : tuple of str
        The seeds that led to it: ``forward run``, ``section scan``, ``trap certificate``,
        ``modal start`` (independent searches agreeing on one cycle).
    """

    state: FloatArray
    peak_velocity: float
    period: float
    amplitude: float
    multipliers: NDArray[np.complex128] = field(repr=False)
    stable: bool
    found_by: tuple[str, ...]

    @property
    def multiplier(self) -> float:
        """Largest Floquet multiplier modulus."""
        return float(np.max(np.abs(self.multipliers))) if self.multipliers.size else 0.0

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready, with the keys of ``stickslip cycles --json`` (``slip_oscillations``)."""
        return {
            "kind": "slip-oscillation",
            "period": self.period,
            "amplitude": self.amplitude,
            "peak_velocity": self.peak_velocity,
            "stick_ratio": 0.0,
            "stable": self.stable,
            "multipliers": [{"re": float(m.real), "im": float(m.imag), "abs": float(abs(m))}
                            for m in self.multipliers],
            "state": [float(x) for x in self.state],
            "found_by": list(self.found_by),
        }


class _Parts:
    """A fixed (structure, slider) in the shape :class:`SlipSection` builds from."""

    def __init__(self, structure: Structure, slider: Slider) -> None:
        self.structure, self.slider = structure, slider

    def build(self) -> tuple[Structure, Slider]:
        return self.structure, self.slider


def may_oscillate(slider: Slider) -> bool:
    """Whether the law can have isolated slip oscillations.

    Parameters
    ----------
    slider : Slider
        The slider and its friction law.

    Returns
    -------
    bool
        False for Coulomb's law and a linear law that stays linear (one band: its slip
        motions are linear, no isolated oscillation); True otherwise, a weakening linear law
        included, whose floor at zero friction (a second band) bounds a growing oscillation
        (the fitted foundation at ``lambda = 0.5``, ``delta = 0.4``: period 6.72177).
    """
    if isinstance(slider.friction, CoulombFriction):
        return False
    if isinstance(slider.friction, LinearFriction):
        edges = slider.friction.bands(float(slider.lam), float(slider.gamma))[0]
        return bool(edges.size > 2)
    return True


def slip_section(structure: Structure, slider: Slider, options: EngineOptions | None = None
                 ) -> SlipSection:
    """The velocity-maximum section of a contact-first structure.

    Parameters
    ----------
    structure, slider : Structure, Slider
        The system, dimensionless (contact on DOF 0).
    options : EngineOptions, optional
        Horizon and budgets of the section's runs (the defaults when None).

    Returns
    -------
    SlipSection
        The Poincare section ``xi'' = 0`` (velocity maximum) in slip and its return map.
    """
    return SlipSection(_Parts(structure, slider), options or EngineOptions())  # type: ignore[arg-type]


def refine(section: SlipSection, y0: FloatArray, max_iter: int = NEWTON_STEPS
           ) -> tuple[FloatArray, FloatArray] | None:
    """Newton's method on ``P(y) = y`` from ``y0``: the fixed point and ``D P`` there, or None.

    Parameters
    ----------
    section : SlipSection
        The section and its return map ``P``.
    y0 : ndarray
        Start on the section.
    max_iter : int
        Bound on the iterations.

    Returns
    -------
    (ndarray, ndarray) or None
        The fixed point and ``D P`` there; None without convergence.
    """
    y = np.asarray(y0, dtype=np.float64).copy()
    for _ in range(max_iter):
        out = section.residual(y)
        if out is None:
            return None
        g, jac = out
        if float(np.max(np.abs(g))) <= 1e-11 * max(1.0, float(np.max(np.abs(y)))):
            return y, jac
        try:
            step = np.linalg.solve(jac - np.eye(y.size), -g)
        except np.linalg.LinAlgError:
            return None
        # damped: a step may not leave the section's velocity range (0, 1)
        scale = 1.0
        while scale > 1e-3 and not 0.0 < y[0] + scale * step[0] < 1.0:
            scale *= 0.5
        y = y + scale * step
        if not np.all(np.isfinite(y)):
            return None
    return None


def _gap_sign(section: SlipSection, y: FloatArray) -> float:
    """Sign of ``P(y)_0 - y_0``; a run that reaches the belt speed grew: ``+1``."""
    py = section.step(y)
    return 1.0 if py is None else float(np.sign(py[0] - y[0]))


def _gap(section: SlipSection, y: float) -> float:
    """``P(y)_0 - y_0`` (one DOF); a run that reaches the belt speed grew: ``+inf``."""
    py = section.step(np.array([y]))
    return math.inf if py is None else float(py[0] - y)


def _inverse(section: SlipSection, target: float, lo: float, hi: float) -> float | None:
    """``P^-1(target)`` on ``[lo, hi]`` (one DOF, ``P`` increasing): Brent's method once the
    upper end is a run that does not reach the belt speed; None when ``target`` is not in
    ``P``'s range there."""
    from scipy.optimize import brentq

    def value(y: float) -> float | None:
        py = section.step(np.array([y]))
        return None if py is None else float(py[0])

    a, b = lo, hi
    fa, fb = value(a), value(b)
    if fa is None or fa > target:
        return None
    for _ in range(40):  # pull the upper end in until its run stays in slip
        if fb is not None:
            break
        b = 0.5 * (a + b)
        fb = value(b)
        if fb is not None and fb < target:
            a, fa, b, fb = b, fb, hi, None
    if fb is None or fb < target:
        return None
    return float(brentq(lambda y: (value(y) or np.inf) - target, a, b, xtol=1e-13, maxiter=100))


def _section_scan(section: SlipSection) -> list[FloatArray]:
    """One DOF: seeds at every sign change of ``P(y) - y`` on the scan's grid, each pulled in
    by backward iteration of the map where the cycle repels (the unstable ones).

    The grid has :data:`SCAN_POINTS` even and :data:`SCAN_GEOMETRIC` geometric points. Two
    cycles in one cell give no sign change: at the deepest local minima of ``|P(y) - y| / y``
    on the grid (:data:`SCAN_DIPS`; the map nearest the identity, as between two cycles born
    in a fold) the relative gap is minimised over the two cells beside it, and a minimum of
    the other sign adds the point between the pair. A sign change is a cycle; the scan finds those it
    brackets, which is no proof that there are no others.
    """
    from scipy.optimize import minimize_scalar

    even = np.linspace(0.0, 0.99, SCAN_POINTS + 1)[1:]
    grid = np.union1d(even, np.geomspace(SCAN_SMALLEST, even[1], SCAN_GEOMETRIC))
    gaps = {float(y): _gap(section, float(y)) for y in grid}
    ys = sorted(gaps)
    dips = []
    for i in range(1, len(ys) - 1):
        lo, mid, hi = ys[i - 1], ys[i], ys[i + 1]
        side = np.sign(gaps[mid])
        if not (side == np.sign(gaps[lo]) == np.sign(gaps[hi]) != 0.0 and math.isfinite(gaps[mid])):
            continue
        if abs(gaps[mid]) / mid < min(abs(gaps[lo]) / lo, abs(gaps[hi]) / hi):
            dips.append((abs(gaps[mid]) / mid, lo, mid, hi, float(side)))
    for _depth, lo, mid, hi, side in sorted(dips)[:SCAN_DIPS]:

        def relative(y: float, side: float = side) -> float:
            gap = _gap(section, y)
            gaps[y] = gap
            return side * gap / y if math.isfinite(gap) else math.inf

        minimize_scalar(relative, bounds=(lo, hi), method="bounded",
                        options={"maxiter": SCAN_DIP_EVALUATIONS, "xatol": 1e-6 * mid})
    ys = sorted(gaps)
    signs = [float(np.sign(gaps[y])) for y in ys]
    seeds: list[FloatArray] = []
    for i in range(len(ys) - 1):
        if signs[i] == signs[i + 1] or signs[i] == 0.0:
            continue
        lo, hi = ys[i], ys[i + 1]
        y = 0.5 * (lo + hi)
        if signs[i] < 0.0 < signs[i + 1]:  # repelling: backward-time iteration converges to it
            for _ in range(BACKWARD_STEPS):
                back = _inverse(section, y, lo, hi)
                if back is None:
                    break
                y = back
        seeds.append(np.array([y]))
    return seeds


def _trap_certificate_seed(structure: Structure, slider: Slider, section: SlipSection
                           ) -> FloatArray | None:
    """One DOF: the unstable cycle bracketed by the basin code's slip trap and escape regions."""
    from stickslip.kernel.batch import prepare_states
    from stickslip.kernel.outer_certificate import ESCAPE_RHO0
    from stickslip.kernel.system import TRAP_RHO0, TRAP_SQRT_K

    edges, intercepts, slopes = slider.friction.bands(float(slider.lam), float(slider.gamma))
    prepared, r_in, _r_hi, escape = prepare_states(
        structure.mass, structure.damping, structure.stiffness, float(slider.lam),
        float(slider.gamma), edges, intercepts, slopes, True, True)
    trap = prepared[22]
    if r_in.size == 0 or not trap[TRAP_RHO0] > 0.0:
        return None  # no region: no unstable cycle bracketed
    rho = 0.5 * (float(trap[TRAP_RHO0]) + float(escape[ESCAPE_RHO0]))
    z_eq = np.asarray(prepared[15], dtype=np.float64)
    start = np.array([float(z_eq[0]) + rho / float(trap[TRAP_SQRT_K]), 0.0])
    return section.first_maximum(start)


def _forward_seeds(structure: Structure, slider: Slider, section: SlipSection, rng: np.random.Generator,
                   seeds: int, options: EngineOptions) -> list[FloatArray]:
    """Ends of forward runs from random states around steady sliding that the engine
    certifies as slip oscillations (stable cycles)."""
    n = structure.n_dof
    centre = section.full_state(np.zeros(2 * n - 1))  # the velocity-zero state nearest steady sliding
    scale = max(1.0, float(np.max(np.abs(centre))))
    out: list[FloatArray] = []
    for _ in range(int(seeds)):
        z = np.concatenate([centre[:n] + rng.uniform(-scale, scale, n), rng.uniform(-0.9, 0.9, n)])
        run = simulate(structure, slider, initial=InitialState(z[:n], z[n:]), options=options,
                       record=False)
        if run.verdict is Verdict.SLIP_OSCILLATION:
            seed = section.first_maximum(np.asarray(run.final_state, dtype=np.float64))
            if seed is not None:
                out.append(seed)
    return out


def _modal_seeds(structure: Structure, section: SlipSection, count: int) -> list[FloatArray]:
    """Seeds along the least-damped slip-I mode: the mode scaled to ``count`` peak velocities
    across ``(0, 1)``, and the midpoints where the map's peak velocity ``P(y)_0 - y_0`` changes
    sign along that family (as the section scan of one DOF does on the whole section)."""
    n = structure.n_dof
    values, vectors = np.linalg.eig(slip_matrix(structure, min(one_sided_slopes(section.slider))))
    oscillating = np.flatnonzero(values.imag > 1e-9)
    if oscillating.size == 0:
        return []
    w = vectors[:, oscillating[np.argmax(values.real[oscillating])]]
    if abs(w[n]) == 0.0:
        return []
    peaks = np.linspace(0.05, 0.95, max(2, count))
    # the slider velocity real and largest: a velocity maximum of the linear mode
    family = [section.reduce(np.real(peak / w[n] * w)) for peak in peaks]
    signs = [_gap_sign(section, y) for y in family]
    return [0.5 * (family[i] + family[i + 1]) for i in range(len(family) - 1)
            if signs[i] != signs[i + 1]]


def find_slip_oscillations(
    structure: Structure,
    slider: Slider,
    *,
    seeds: int = 12,
    seed: int = 0,
    options: EngineOptions | None = None,
) -> tuple[SlipOscillation, ...]:
    """Every slip oscillation found at this parameter point, stable and unstable.

    Parameters
    ----------
    structure, slider : Structure, Slider
        The system (dimensionless); a law without isolated slip oscillations (Coulomb, a
        linear law without its floor, :func:`may_oscillate`) returns none without a search.
    seeds : int
        Random forward runs, and modal starts of Newton's method.
    seed : int
        Random seed of the forward runs.
    options : EngineOptions, optional
        Horizon of the forward runs and of the section's runs.

    Returns
    -------
    tuple of SlipOscillation
        The distinct cycles, by increasing amplitude.
    """
    if not may_oscillate(slider):
        return ()
    if structure.contact_dof != 0:  # the contact-first twin; states back in the user's order
        inner, perm = structure.contact_first()
        inner_found = find_slip_oscillations(inner, slider, seeds=seeds, seed=seed, options=options)
        return tuple(replace(c, state=to_user_order(c.state, perm)) for c in inner_found)
    opts = options or EngineOptions()
    section = slip_section(structure, slider, opts)
    rng = np.random.default_rng(random_seed(seed))
    candidates: list[tuple[str, FloatArray]] = []
    candidates += [("forward run", y) for y in _forward_seeds(structure, slider, section, rng, seeds, opts)]
    if structure.n_dof == 1:
        candidates += [("section scan", y) for y in _section_scan(section)]
        trap = _trap_certificate_seed(structure, slider, section)
        if trap is not None:
            candidates.append(("trap certificate", trap))
    else:  # with more DOFs, start Newton from the least-damped mode
        candidates += [("modal start", y) for y in _modal_seeds(structure, section, MODAL_STARTS)]
    found: list[SlipOscillation] = []
    for origin, y0 in candidates:
        solved = refine(section, y0)
        if solved is None or not STEADY < solved[0][0] < 1.0:
            continue  # no convergence, or steady sliding itself (no oscillation)
        y, jac = solved
        z = section.full_state(y)
        same = [i for i, c in enumerate(found)
                if np.max(np.abs(z - c.state)) <= SAME_CYCLE * max(1.0, float(np.max(np.abs(z))))]
        if same:
            if origin not in found[same[0]].found_by:
                found[same[0]] = replace(found[same[0]], found_by=(*found[same[0]].found_by, origin))
            continue
        measured = section.measure(y)
        if measured is None:
            continue
        period, amplitude, _ = measured
        mult = (np.asarray(np.linalg.eigvals(jac), dtype=np.complex128) if jac.size
                else np.zeros(0, dtype=np.complex128))
        found.append(SlipOscillation(z, float(y[0]), period, amplitude, mult,
                                     bool(np.all(np.abs(mult) < 1.0)), (origin,)))
    found.sort(key=lambda c: c.amplitude)
    return tuple(found)
