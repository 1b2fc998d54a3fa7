"""A stick-slip cycle proven, not observed: the minimal period and a ball that contracts onto it.

A run that sees its breakaway state repeat to ``cycle_tol`` after ``k`` stick phases has
*observed* a candidate. When the return map's multipliers are complex or near -1, states two
phases apart agree long before neighbours do, so ``k`` may be a multiple of the true period.
This module turns a candidate into a proof, or says it cannot.

The section and the map. For ``n >= 2`` degrees of freedom a breakaway state is fixed by the
foundation coordinates ``b`` (dimension ``d = 2 n - 2``): the slider moves with the belt and
its stick force is at the section's level (:class:`~stickslip.analysis.return_map.ReturnMap`).
``P(b)`` is the next breakaway state; a cycle of ``q`` stick phases is a fixed point of
``P^q``. For ``n = 1`` the breakaway state is unique, so every stick-slip motion repeats it
at the next breakaway: the period is one stick phase, with no bound to check.

Steps of :func:`prove_cycle`, for every divisor ``q`` of ``k`` in increasing order:

1. Newton's method on ``P^q(b) = b`` from the run's breakaway state, with the exact Jacobian
   (:meth:`~stickslip.analysis.return_map.ReturnMap.linearise`), gives ``b_hat`` and
   ``J = D P^q(b_hat)``.
2. A *tube* bound (:func:`stickslip.analysis._cycle_tube.tube_bound`) over the Euclidean
   ball ``B(b_hat, r)``: every trajectory
   started in the ball goes through the same sequence of phases as the nominal one (no event
   appears or vanishes, every event stays transversal), and
   ``sup_B ||D P^q(b) - J||_2 <= E(r)``. See
   :func:`stickslip.analysis._cycle_tube.tube_bound` for the derivation.
3. Contraction in the norm adapted to ``J`` (``||x||_W = ||C x||_2`` with ``C^T C = W``,
   ``(J/s)^T W (J/s) - W = -I`` with ``s = (1 + rho(J))/2``, so ``||J||_W = s sqrt(1 -
   1/lambda_max(W)) < s < 1`` when the spectral radius ``rho(J)`` of ``J`` is below 1):
   with ``kappa = ||C||_2 ||C^-1||_2``,
   ``theta = ||J||_W + kappa E(r) < 1`` bounds ``||D P^q||_W`` on the ball. If also the
   residual ``||P^q(b_hat) - b_hat||_W <= (1 - theta) rho`` for the W-ball of radius
   ``rho = r / ||C^-1||_2`` (inside the Euclidean one), ``P^q`` maps that closed ball into
   itself and contracts it: by Banach's fixed-point theorem there is exactly one fixed point
   ``b*`` in it and every state of the ball converges to it.
4. The run's state ``b_0`` lies in the ball: the run converges to that cycle.
5. Minimal period: the true period ``m`` of ``b*`` divides ``q``. For each proper divisor
   ``p`` of ``q``, the full breakaway state ``z_p`` after ``p`` breakaways satisfies
   ``||z_p(b*) - z_0(b*)|| >= ||z_p(b_hat) - z_0(b_hat)|| - Z_p(r) - ||L||_2 r > 0`` (``Z_p``
   the tube's bound on the state deviation there, ``L`` the lift), so ``b*`` is no fixed
   point of ``P^p``: the period is ``q`` stick phases.

:func:`prove_existence` proves an unstable cycle too (Newton-Kantorovich form, no
contraction needed): with ``A = (J - I)^-1``, ``T(b) = b - A (P^q(b) - b)`` has
``||D T|| <= ||A||_2 E(r)`` on the ball, and ``||A||_2 ||P^q(b_hat) - b_hat|| +
||A||_2 E(r) r <= r`` with ``||A||_2 E(r) < 1`` maps the ball into itself contracting:
exactly one fixed point of ``P^q`` in it.

Rounding: every bound adds a round-off allowance to the deviations it carries
(:mod:`stickslip.analysis._cycle_tube`), so a proof does not rest on the last bits.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.linalg
from numpy.typing import NDArray

from stickslip.analysis._cycle_tube import (
    Coordinates,
    Phase,
    ProductNorms,
    Tube,
    rounding_allowance,
    tube_bound,
)
from stickslip.analysis._cycle_tube import phases as sample_phases
from stickslip.analysis.engine_run import EngineOptions
from stickslip.analysis.return_map import ReturnMap, newton_fixed_point
from stickslip.kernel.system import SLIP_I
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure

FloatArray = NDArray[np.float64]

#: Radii tried, largest first: ``r = scale * RADIUS_START * RADIUS_FACTOR**-i``.
RADIUS_START = 1e-1
RADIUS_FACTOR = 4.0
RADIUS_TRIES = 24
#: Geometric bisections between the largest radius of the ladder that passes and the one above
#: it (the ball's radius to within a factor ``RADIUS_FACTOR ** 2**-RADIUS_BISECTIONS``).
RADIUS_BISECTIONS = 3
#: Breakaways computed per engine run when a run goes on to enter the proven ball.
EXTRA_CHUNK = 32


@dataclass(frozen=True)
class CycleProof:
    """A proven stick-slip cycle (dimensionless: ``V/omega_n`` and ``V``).

    Attributes
    ----------
    stick_phases : int
        The minimal period in stick phases (proven: no proper divisor is a period).
    fixed_point : ndarray, shape (2 n_dof,)
        The refined breakaway state ``state(b_hat)`` (contact-first order).
    multipliers : ndarray of complex
        Eigenvalues of ``D P^q`` at ``b_hat`` (the non-trivial Floquet multipliers).
    contraction : float
        ``theta``: a bound of ``||D P^q||_W`` over the ball (below 1); NaN for an
        existence proof of an unstable cycle.
    radius : float
        Euclidean radius of the proven ball in the foundation coordinates ``b``.
    distance : float
        ``||b_0 - b_hat||_2`` of the run's breakaway state (NaN for an existence proof).
    residual : float
        ``||P^q(b_hat) - b_hat||_2``.
    extra_stick_phases : int
        Stick phases the run went on past its candidate before it entered the ball.
    breakaway_onto : str
        ``slip-I`` or ``slip-II``: the section piece of the fixed point.
    """

    stick_phases: int
    fixed_point: FloatArray = field(repr=False)
    multipliers: NDArray[np.complex128] = field(repr=False)
    contraction: float
    radius: float
    distance: float
    residual: float
    extra_stick_phases: int = 0
    breakaway_onto: str = "slip-I"
    norm_matrix: FloatArray = field(default_factory=lambda: np.zeros((0, 0)), repr=False)
    """``C`` of the adapted norm ``||x||_W = ||C x||_2``; the proven ball is
    ``||C (b - b_hat)|| <= radius / ||C^-1||_2``."""
    margin: float = math.nan
    """How far (Euclidean, in ``b``) the true state may lie from the run's computed one and
    still be in the ball: ``(rho - ||C (b_0 - b_hat)||) / ||C||_2``."""
    run_error: float = math.nan
    """A bound of the run's own rounding carried to that state
    (:func:`stickslip.analysis.run_rounding.run_rounding`; NaN until checked)."""
    run_gain: float = math.nan
    """The largest growth of an error of one phase of the run by that state."""

    @property
    def moduli(self) -> FloatArray:
        """``|multipliers|``, largest first."""
        return np.sort(np.abs(self.multipliers))[::-1]

    def describe(self) -> str:
        """One line: what was checked."""
        moduli = ", ".join(f"{m:.3g}" for m in self.moduli[:4])
        more = "" if self.moduli.size <= 4 else f" (+{self.moduli.size - 4})"
        later = (f" {self.extra_stick_phases} stick phase(s) later" if self.extra_stick_phases
                 else "")
        rounding = (f", its rounding carried there at most {self.run_error:.1e}"
                    if math.isfinite(self.run_error) else "")
        return (f"proven: the {self.stick_phases}-stick-phase return map contracts (theta "
                f"{_fraction(self.contraction)}) a ball of radius {self.radius:.2e} about its "
                f"fixed point, which holds the run's state{later} (distance "
                f"{self.distance:.2e}{rounding}); no shorter period; |multipliers| "
                f"{moduli}{more}")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready numbers of the proof."""
        def num(x: float) -> float | None:
            return float(x) if math.isfinite(x) else None
        return {
            "stick_phases": self.stick_phases,
            "multiplier_moduli": [float(m) for m in self.moduli],
            "contraction": num(self.contraction),
            "ball_radius": num(self.radius),
            "distance": num(self.distance),
            "residual": num(self.residual),
            "extra_stick_phases": self.extra_stick_phases,
            "breakaway_onto": self.breakaway_onto,
            "margin": num(self.margin),
            "run_rounding_bound": num(self.run_error),
            "run_rounding_gain": num(self.run_gain),
        }


def _fraction(theta: float) -> str:
    """``theta`` to three digits, but never rounded up to 1 (a contraction reads below 1)."""
    text = f"{theta:.3g}"
    if theta < 1.0 and float(text) >= 1.0:
        return f"{math.floor(theta * 1e6) / 1e6:.6f}".rstrip("0")
    return text


def divisors(k: int) -> list[int]:
    """Divisors of ``k`` in increasing order (the candidate periods of a ``k``-phase repeat).

    Parameters
    ----------
    k : int
        A positive whole number (stick phases).

    Returns
    -------
    list of int
        ``[1, ..., k]``, each dividing ``k``.
    """
    return [d for d in range(1, k + 1) if k % d == 0]


def _adapted_norm(jac: FloatArray) -> tuple[FloatArray, float, float] | None:
    """``C`` with ``||x||_W = ||C x||``, ``||J||_W`` and ``kappa(C)``; None unless ``rho(J) < 1``.

    ``W`` solves ``(J/s)^T W (J/s) - W = -I`` with ``s = (1 + rho(J)) / 2``, so
    ``||J||_W = s sqrt(1 - 1/lambda_max(W)) < s``: a contraction factor between the spectral
    radius and 1 (with ``s = 1``, complex multipliers of modulus 0.77 gave ``||J||_W = 0.99``).
    """
    if jac.size == 0:
        return np.zeros((0, 0)), 0.0, 1.0
    radius = float(np.max(np.abs(np.linalg.eigvals(jac))))
    if radius >= 1.0:
        return None
    shrink = 0.5 * (1.0 + radius)
    try:
        w = scipy.linalg.solve_discrete_lyapunov(jac.T / shrink, np.eye(jac.shape[0]))
        w = 0.5 * (w + w.T)
        chol = np.linalg.cholesky(w).T  # W = C^T C
    except (np.linalg.LinAlgError, ValueError):
        return None
    c_inv = np.linalg.inv(chol)
    norm_w = float(np.linalg.norm(chol @ jac @ c_inv, 2))
    kappa = float(np.linalg.norm(chol, 2) * np.linalg.norm(c_inv, 2))
    if not (math.isfinite(norm_w) and norm_w < 1.0):
        return None
    return chol, norm_w, kappa


@dataclass
class _Candidate:
    """A Newton fixed point of ``P^q`` with its sampled phases (shared by both proofs)."""

    q: int
    b_hat: FloatArray
    jac: FloatArray
    residual: float
    phases: list[Phase]
    z_hit: FloatArray
    breakaway_states: list[FloatArray]
    value: FloatArray  # P^q(b_hat)
    coords: Coordinates  # the tube's coordinates (the structure's energy coordinates)


def _candidate(pmap: ReturnMap, b0: FloatArray, q: int) -> _Candidate | str:
    """The candidate of period ``q`` near ``b0``, or why there is none (a phrase)."""
    solution = newton_fixed_point(pmap, b0, q)
    if solution is None:
        return "Newton's method on the return map did not converge"
    b_hat, jac = solution
    value = pmap(b_hat, q)
    if value is None:
        return "the return map is not defined at Newton's fixed point"
    coords = Coordinates.energy(np.asarray(pmap.structure.mass), np.asarray(pmap.structure.stiffness))
    sampled = sample_phases(pmap, b_hat, q, coords)
    if sampled is None:
        return ("its phases are beyond the work a proof may take, or one ends on no surface "
                "the proof knows")
    phases, z_hit = sampled
    states = pmap.next_breakaways(pmap.state(b_hat), q)
    return _Candidate(q, b_hat, jac, float(np.linalg.norm(value - b_hat)), phases, z_hit, states,
                      value, coords)


def tubes(pmap: ReturnMap, cand: _Candidate) -> tuple[Callable[..., Tube], float]:
    """The tube bound about ``cand`` as a function of the ball's radius, and the state's scale.

    The nominal products' norms are formed once, in the candidate's coordinates (lift and
    reduction included); each call is :func:`~stickslip.analysis._cycle_tube.tube_bound`.

    Parameters
    ----------
    pmap : ReturnMap
        The return map of the candidate's system.
    cand : _Candidate
        The candidate (its sampled phases and coordinates).

    Returns
    -------
    (callable, float)
        ``radius -> Tube`` for Euclidean balls about ``b_hat`` in the foundation coordinates,
        and the state's scale ``max(1, max |z|)``.
    """
    n2 = 2 * pmap.n
    reduce_rows = np.delete(np.eye(n2), [0, pmap.n], axis=0)  # R: the foundation coordinates
    to_y, to_z = cand.coords.from_state, cand.coords.to_state
    norms = ProductNorms.of(cand.phases, to_y @ pmap.lift, reduce_rows @ to_z)
    scale = max(1.0, float(np.max(np.abs(pmap.state(cand.b_hat)))))
    lam, gamma = float(pmap.slider.lam), float(pmap.slider.gamma)

    def at(radius: float, equal_time: bool = False) -> Tube:
        return tube_bound(cand.phases, norms, pmap.stick_normal, lam, gamma, radius, scale,
                          cand.coords, equal_time)

    return at, scale


def _ball(pmap: ReturnMap, cand: _Candidate, accept: Any) -> tuple[float, Tube] | None:
    """The largest radius of the ladder whose tube passes ``accept(radius, tube)``, widened by
    :data:`RADIUS_BISECTIONS` bisections towards the next radius of the ladder (any radius
    that passes is a proof; the largest found is taken)."""
    tube_at, scale = tubes(pmap, cand)
    # both variants of the tube are proofs: band by band, and at equal times across the
    # edges of a continuous friction table (stickslip.analysis._band_variation)
    variants = (False, True) if any(ph.bands is not None for ph in cand.phases) else (False,)

    def passing(radius: float) -> Tube | None:
        for equal_time in variants:
            tube = tube_at(radius, equal_time)
            if tube.ok and accept(radius, tube):
                return tube
        return None

    for i in range(RADIUS_TRIES):
        radius = scale * RADIUS_START * RADIUS_FACTOR ** (-i)
        tube = passing(radius)
        if tube is None:
            continue
        # between this radius and the one above that failed: bisect (geometric means)
        failed = radius * RADIUS_FACTOR
        for _ in range(RADIUS_BISECTIONS if i > 0 else 0):
            middle = math.sqrt(radius * failed)
            wider = passing(middle)
            if wider is None:
                failed = middle
            else:
                radius, tube = middle, wider
        return radius, tube
    return None


def _shorter_period_excluded(pmap: ReturnMap, cand: _Candidate, radius: float,
                             tube: Tube) -> bool:
    """No proper divisor ``p`` of ``q`` is a period of the fixed point in the ball (step 5)."""
    start = pmap.state(cand.b_hat)
    lift_norm = float(np.linalg.norm(pmap.lift, 2))
    for p in divisors(cand.q)[:-1]:
        if p > len(cand.breakaway_states) or p > len(tube.breakaway_deviation):
            return False
        gap = float(np.linalg.norm(cand.breakaway_states[p - 1] - start))
        if gap <= tube.breakaway_deviation[p - 1] + lift_norm * radius:
            return False
    return True


def _contraction_ball(pmap: ReturnMap, cand: _Candidate) -> tuple[float, float, FloatArray] | str:
    """``(radius, theta, C)`` of a proven contraction ball about ``b_hat`` (step 3), or why
    there is none (a phrase)."""
    adapted = _adapted_norm(cand.jac)
    if adapted is None:
        largest = float(np.max(np.abs(np.linalg.eigvals(cand.jac)))) if cand.jac.size else 0.0
        return (f"its largest multiplier modulus is {largest:.3g}" if largest >= 1.0 else
                "no norm makes its return map a contraction")
    chol, norm_w, kappa = adapted
    c_inv_norm = float(np.linalg.norm(np.linalg.inv(chol), 2)) if chol.size else 1.0
    # the computed residual, plus the engine's rounding in evaluating the map
    scale = max(1.0, float(np.max(np.abs(pmap.state(cand.b_hat)))))
    rounding = rounding_allowance(cand.phases, scale)
    residual_w = (float(np.linalg.norm(chol @ (cand.value - cand.b_hat)))
                  + float(np.linalg.norm(chol, 2)) * rounding)
    thetas: dict[float, float] = {}

    def accept(radius: float, tube: Tube) -> bool:
        theta = norm_w + kappa * tube.jacobian_bound
        rho = radius / c_inv_norm
        thetas[radius] = theta
        return (theta < 1.0 and residual_w <= (1.0 - theta) * rho
                and _shorter_period_excluded(pmap, cand, radius, tube))

    found = _ball(pmap, cand, accept)
    if found is None:
        if not thetas:
            return ("the deviation bound of its phases (the tube) fails at every radius tried, "
                    f"down to {_min_radius(pmap, cand):.2g}: nearby motions are not shown to "
                    "follow it")
        best = min(thetas.values())
        if best < 1.0:
            return (f"the contraction bound falls to {best:.3g}, but at no radius does the ball "
                    "hold the map's residual with its rounding allowance (the engine's error in "
                    f"one evaluation, up to {rounding:.2g}): the balls that contract are too "
                    "small to prove anything in double precision")
        return (f"the contraction bound stays at {best:.3g} or above (it must be below 1) at "
                "every radius whose tube holds: the Jacobian's variation over the ball, or the "
                "rounding it carries, is too large")
    radius = found[0]
    return radius / c_inv_norm, thetas[radius], chol


def _min_radius(pmap: ReturnMap, cand: _Candidate) -> float:
    """The smallest radius of the proof's ladder for ``cand`` (the foundation coordinates)."""
    scale = max(1.0, float(np.max(np.abs(pmap.state(cand.b_hat)))))
    return scale * RADIUS_START * RADIUS_FACTOR ** (-(RADIUS_TRIES - 1))


def prove_cycle(structure: Structure, slider: Slider, breakaway_state: FloatArray,
                candidate_phases: int, options: EngineOptions, *,
                extra_breakaways: int = 512, min_margin: float = 0.0,
                why: list[str] | None = None) -> CycleProof | None:
    """Prove the stable cycle a run converges to, with its minimal period (see module notes).

    Parameters
    ----------
    structure, slider : Structure, Slider
        The system (contact on DOF 0, ``n_dof >= 2``), dimensionless.
    breakaway_state : ndarray, shape (2 n_dof,)
        The run's breakaway state at its candidate (``V/omega_n`` and ``V``).
    candidate_phases : int
        ``k``: the run saw the state repeat after ``k`` stick phases.
    options : EngineOptions
        Horizon of the map's runs.
    extra_breakaways : int
        When the run's state is not yet inside the proven ball, the run goes on for at
        most this many more breakaways (the map ``P`` iterated exactly) to enter it.
    min_margin : float
        The run goes on until its state is inside the ball by at least this much (Euclidean,
        in ``b``; the proof's ``margin``): room for the run's own rounding
        (:mod:`stickslip.analysis.run_rounding`).
    why : list of str, optional
        Filled with one phrase per period tried that gave no proof (``"period q: ..."``).

    Returns
    -------
    CycleProof or None
        None when no divisor of ``k`` gives a proof: the verdict stays undetermined.
    """
    pmap0 = ReturnMap(structure, slider, options)
    direction = pmap0.direction_of(np.asarray(breakaway_state, dtype=np.float64))
    pmap = pmap0 if direction == SLIP_I else ReturnMap(structure, slider, options, direction)
    b0 = pmap.reduce(np.asarray(breakaway_state, dtype=np.float64))
    reasons = [] if why is None else why
    for q in divisors(int(candidate_phases)):
        cand = _candidate(pmap, b0, q)
        if isinstance(cand, str):
            reasons.append(f"period {q}: {cand}")
            continue
        ball = _contraction_ball(pmap, cand)
        if isinstance(ball, str):
            reasons.append(f"period {q}: {ball}")
            continue
        rho, theta, chol = ball
        later: list[FloatArray] = []
        radius = rho * float(np.linalg.norm(np.linalg.inv(chol), 2)) if chol.size else rho
        onto = "slip-I" if direction == SLIP_I else "slip-II"
        multipliers = np.asarray(np.linalg.eigvals(cand.jac), dtype=np.complex128)
        # the run's state, or one of its next breakaways on this piece, inside the W-ball
        state = np.asarray(breakaway_state, dtype=np.float64)
        extra = 0
        while True:  # bounded: at most extra_breakaways more breakaways, in chunks
            if pmap.direction_of(state) == direction:
                b = pmap.reduce(state)
                inside = float(np.linalg.norm(chol @ (b - cand.b_hat)))
                norm_c = float(np.linalg.norm(chol, 2)) if chol.size else 1.0
                if inside <= rho and (rho - inside) / norm_c >= min_margin:
                    return CycleProof(q, pmap.state(cand.b_hat), multipliers, theta, radius,
                                      float(np.linalg.norm(b - cand.b_hat)), cand.residual,
                                      extra, onto, chol, (rho - inside) / norm_c)
            if extra >= extra_breakaways:
                break
            if not later:
                later = pmap.next_breakaways(state, min(EXTRA_CHUNK, extra_breakaways - extra))
                if not later:
                    break
            state = later.pop(0)
            extra += 1
        reasons.append(f"period {q}: a ball of radius {radius:.2g} is proven, but the run did "
                       f"not enter it within {extra} more breakaways")
    return None


def prove_existence(structure: Structure, slider: Slider, b_hat: FloatArray, q: int,
                    options: EngineOptions, direction: int = SLIP_I, *,
                    why: list[str] | None = None) -> float | None:
    """Radius of a ball about ``b_hat`` holding exactly one fixed point of ``P^q`` (stable or not).

    The Newton-Kantorovich form of the module notes; also checks that no proper divisor of
    ``q`` is a period (step 5).

    Parameters
    ----------
    structure, slider : Structure, Slider
        The system (contact on DOF 0), dimensionless.
    b_hat : ndarray, shape (2 n_dof - 2,)
        Foundation coordinates near the fixed point (``V/omega_n`` and ``V``); refined by
        Newton's method first.
    q : int
        Stick phases of the cycle.
    options : EngineOptions
        Horizon of the map's runs.
    direction : int
        The section piece: ``SLIP_I`` or ``SLIP_II`` breakaways.
    why : list of str, optional
        When given and no radius passes, gets one phrase saying why.

    Returns
    -------
    float or None
        The Euclidean radius in the foundation coordinates (0 for 1 DOF, where the breakaway
        state is unique); None when no radius of the ladder passes.
    """
    reasons = [] if why is None else why
    pmap = ReturnMap(structure, slider, options, direction)
    cand = _candidate(pmap, np.asarray(b_hat, dtype=np.float64), int(q))
    if isinstance(cand, str):
        reasons.append(cand)
        return None
    if cand.jac.size == 0:
        return 0.0
    try:
        a_inv = np.linalg.inv(cand.jac - np.eye(cand.jac.shape[0]))
    except np.linalg.LinAlgError:
        reasons.append("1 is a multiplier of its return map (J - I is singular)")
        return None
    a_norm = float(np.linalg.norm(a_inv, 2))
    bounds: list[float] = []
    # the computed residual, plus the engine's rounding in evaluating the map
    residual = cand.residual + rounding_allowance(
        cand.phases, max(1.0, float(np.max(np.abs(pmap.state(cand.b_hat))))))

    def accept(radius: float, tube: Tube) -> bool:
        contraction = a_norm * tube.jacobian_bound
        bounds.append(contraction)
        return (contraction < 1.0 and a_norm * residual + contraction * radius <= radius
                and _shorter_period_excluded(pmap, cand, radius, tube))

    found = _ball(pmap, cand, accept)
    if found is None:
        reasons.append(
            f"the tube fails at every radius tried, down to {_min_radius(pmap, cand):.2g}"
            if not bounds else
            f"the Newton-Kantorovich bound ||(J - I)^-1|| E(r) falls to {min(bounds):.3g}, but "
            "at no radius does the ball hold the map's residual with its rounding allowance"
            if min(bounds) < 1.0 else
            f"the Newton-Kantorovich bound ||(J - I)^-1|| E(r) stays at {min(bounds):.3g} or "
            "above (it must be below 1) at every radius whose tube holds")
        return None
    return found[0]
