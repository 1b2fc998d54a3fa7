"""A stick-slip cycle proven, not observed: the minimal period and a ball that contracts onto it.

A run that sees its breakaway state repeat to ``cycle_tol`` after ``k`` stick phases has
*observed* a candidate. When the return map's multipliers are complex or near -1, states two
phases apart agree long before neighbours do, so ``k`` may be a multiple of the true period.
This module turns a candidate into a proof, or says it cannot.

The section and the map. For ``n >= 2`` degrees of freedom a breakaway state is fixed by the
foundation coordinates ``b`` (dimension ``d = 2 n - 2``): the slider moves with the belt and
its stick force is at the section's level (:class:`~stickslip.analysis.cycles._ReturnMap`).
``P(b)`` is the next breakaway state; a cycle of ``q`` stick phases is a fixed point of
``P^q``. For ``n = 1`` the breakaway state is unique, so every stick-slip motion repeats it
at the next breakaway: the period is one stick phase, with no bound to check.

Steps of :func:`prove_cycle`, for every divisor ``q`` of ``k`` in increasing order:

1. Newton's method on ``P^q(b) = b`` from the run's breakaway state, with the exact Jacobian
   (:meth:`~stickslip.analysis.cycles._ReturnMap.linearise`), gives ``b_hat`` and
   ``J = D P^q(b_hat)``.
2. A *tube* bound (:func:`_tube`) over the Euclidean ball ``B(b_hat, r)``: every trajectory
   started in the ball goes through the same sequence of phases as the nominal one (no event
   appears or vanishes, every event stays transversal), and
   ``sup_B ||D P^q(b) - J||_2 <= E(r)``. See :func:`_tube` for the derivation.
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

Rounding: the nominal quantities are computed in double precision; every bound adds
``ROUNDING`` (relative to the state's scale) to the deviations it carries, so a proof does
not rest on the last bits.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.linalg
from numpy.typing import NDArray

from stickslip.analysis.cycles import _newton, _ReturnMap
from stickslip.analysis.simulation import EngineOptions
from stickslip.kernel.system import SLIP_I, STICK, mode_kind_band
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure

FloatArray = NDArray[np.float64]

#: Relative round-off allowance added to every state deviation the tube carries.
ROUNDING = 1e-13
#: Largest number of samples of one phase's nominal trajectory (bounds the work).
MAX_SAMPLES = 20_000
#: ``||A||_F h`` of the sampling step: small, so the bounds between samples are tight.
SAMPLE_STEP = 0.02
#: Radii tried, largest first: ``r = scale * RADIUS_START * RADIUS_FACTOR**-i``.
RADIUS_START = 1e-1
RADIUS_FACTOR = 4.0
RADIUS_TRIES = 24
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
        return (f"proven: the {self.stick_phases}-stick-phase return map contracts (theta "
                f"{self.contraction:.3g}) a ball of radius {self.radius:.2e} about its fixed "
                f"point, which holds the run's state{later} (distance {self.distance:.2e}); no "
                f"shorter period; |multipliers| {moduli}{more}")

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
        }


def divisors(k: int) -> list[int]:
    """Divisors of ``k`` in increasing order."""
    return [d for d in range(1, k + 1) if k % d == 0]


@dataclass
class _Phase:
    """Nominal data of one phase of the run behind ``P^q`` (see :func:`_phases`)."""

    mode: int
    duration: float
    a: FloatArray  # A of z' = A z + c
    c: FloatArray
    norm_a: float
    functions: list[tuple[FloatArray, float]]  # (normal n, level g0): g = n.z - g0
    ending: int  # index into functions of the event that ends the phase
    start_zero: list[bool]  # functions that vanish at the start (left from their surface)
    g: FloatArray  # (samples, functions) nominal g at the samples
    rate: FloatArray  # (samples, functions) nominal n.f
    flow_norm: FloatArray  # ||f(z*(s_j))||_2 at the samples
    m_norm: FloatArray  # ||expm(A s_j)||_F at the samples
    h: float  # sample spacing
    z_end: FloatArray
    f_minus: FloatArray  # field of this mode at z_end
    f_plus: FloatArray  # field of the next mode at z_end (0 at the map's final section)
    a_plus: FloatArray
    belt_decision: bool  # ends at the belt speed: the next mode is chosen by the stick force
    e_nominal: FloatArray  # expm(A t)
    breakaway: bool  # ends with a breakaway (counted for the minimal-period check)
    salt: FloatArray = field(init=False)  # the nominal saltation matrix at the end
    salt_norm: float = field(init=False)
    e_norm: float = field(init=False)

    def __post_init__(self) -> None:
        nv = self.functions[self.ending][0]
        self.salt = (np.eye(self.f_minus.size)
                     + np.outer(self.f_plus - self.f_minus, nv) / float(nv @ self.f_minus))
        self.salt_norm = float(np.linalg.norm(self.salt, 2))
        self.e_norm = float(np.linalg.norm(self.e_nominal, 2))


def _functions(pmap: _ReturnMap, mode: int) -> list[tuple[FloatArray, float]]:
    """Every event surface of ``mode``: ``n . z = g0`` (the engine's events, Eq. 20 and bands)."""
    lam, gamma = float(pmap.slider.lam), float(pmap.slider.gamma)
    kind, band = mode_kind_band(mode)
    if kind == STICK:
        return [(pmap.stick_normal, lam), (pmap.stick_normal, -lam * (1.0 + 2.0 * gamma))]
    edges = pmap.edges
    sign = -1.0 if kind == SLIP_I else 1.0
    out = [(pmap.slip_normal, 1.0 + sign * float(edges[band]))]
    if band + 1 < edges.size and math.isfinite(float(edges[band + 1])):
        out.append((pmap.slip_normal, 1.0 + sign * float(edges[band + 1])))
    return out


def _phases(pmap: _ReturnMap, b: FloatArray, q: int) -> tuple[list[_Phase], FloatArray] | None:
    """The nominal phases from ``state(b)`` to its ``q``-th breakaway, sampled for the tube."""
    run = pmap._run(pmap.state(b), q)
    if run is None:
        return None
    result, times = run
    t_hit = float(times[-1])
    q_end, v_end, _ = result.state_at(np.array([t_hit]))
    z_hit = np.concatenate([q_end[0], v_end[0]])
    seg_t, seg_mode, seg_z = result.segment_times, result.segment_modes, result.segment_states
    last = int(np.searchsorted(seg_t, t_hit, side="left")) - 1
    if last < 0 or int(seg_mode[last]) != STICK:
        return None
    first = 0
    if int(seg_mode[0]) == STICK and last > 0 and float(seg_t[1]) <= 1e-9:
        first = 1  # the start's own breakaway, registered within rounding of tau = 0
    phases: list[_Phase] = []
    n2 = 2 * pmap.n
    for i in range(first, last + 1):
        mode = int(seg_mode[i])
        t0 = float(seg_t[i])
        t1 = t_hit if i == last else float(seg_t[i + 1])
        z0 = np.asarray(seg_z[i], dtype=np.float64)
        z_end = z_hit if i == last else np.asarray(seg_z[i + 1], dtype=np.float64)
        a, c = pmap.flow_matrix[mode], pmap.flow_constant[mode]
        functions = _functions(pmap, mode)
        scale = max(1.0, float(np.max(np.abs(z_end))))
        values_end = [abs(float(nv @ z_end) - g0) for nv, g0 in functions]
        ending = int(np.argmin(values_end))
        if values_end[ending] > 1e-7 * scale:
            return None  # the recorded phase end is on no surface: not a phase this proof knows
        start_zero = [abs(float(nv @ z0) - g0) <= 1e-9 * scale for nv, g0 in functions]
        duration = t1 - t0
        norm_a = float(np.linalg.norm(a))
        samples = int(min(MAX_SAMPLES, max(8, math.ceil(duration * norm_a / SAMPLE_STEP))))
        h = duration / samples
        aug = np.zeros((n2 + 1, n2 + 1))
        aug[:n2, :n2], aug[:n2, n2] = a, c
        step = scipy.linalg.expm(aug * h)
        w = np.concatenate([z0, [1.0]])
        e_power = np.eye(n2)
        zs = np.empty((samples + 1, n2))
        m_norm = np.empty(samples + 1)
        for j in range(samples + 1):
            zs[j] = w[:n2]
            m_norm[j] = float(np.linalg.norm(e_power))
            w = step @ w
            e_power = step[:n2, :n2] @ e_power
        fields = zs @ a.T + c
        normals = np.array([nv for nv, _ in functions])
        levels = np.array([g0 for _, g0 in functions])
        g = zs @ normals.T - levels
        g[-1] = normals @ z_end - levels  # the recorded end (the event's exact state)
        rate = fields @ normals.T
        if i == last:
            f_plus, a_plus, belt, bk = np.zeros(n2), np.zeros((n2, n2)), False, True
        else:
            nxt = int(seg_mode[i + 1])
            f_plus = pmap.flow_matrix[nxt] @ z_end + pmap.flow_constant[nxt]
            a_plus = pmap.flow_matrix[nxt]
            belt = mode != STICK and abs(float(z_end[pmap.n]) - 1.0) <= 1e-12
            bk = mode == STICK
        phases.append(_Phase(mode, duration, a, c, norm_a, functions, ending, start_zero, g, rate,
                             np.linalg.norm(fields, axis=1), m_norm, h, z_end,
                             a @ z_end + c, f_plus, a_plus, belt, scipy.linalg.expm(a * duration),
                             bk))
    return phases, z_hit


@dataclass
class _Tube:
    """Outcome of :func:`_tube` at one radius."""

    ok: bool
    jacobian_bound: float = math.inf  # E(r)
    breakaway_deviation: list[float] = field(default_factory=list)  # Z at each breakaway


def _clear(g: FloatArray, lip: FloatArray, eps: FloatArray) -> NDArray[np.bool_]:
    """Per sample interval: ``|g*| > eps`` on all of it (``g*`` Lipschitz ``lip`` there).

    On ``[s_j, s_j + h]`` a function with end values of one sign and Lipschitz constant ``L``
    stays at least ``(|g_j| + |g_{j+1}| - L h) / 2`` from zero (``lip`` is ``L h``).
    """
    same = np.sign(g[:-1]) * np.sign(g[1:]) > 0
    low = 0.5 * (np.abs(g[:-1]) + np.abs(g[1:]) - lip)
    return same & (low > eps)


def _tube(phases: list[_Phase], norms: _ProductNorms, stick_normal: FloatArray,
          lam: float, gamma: float, radius: float, scale: float) -> _Tube:
    """Bounds over every trajectory started in the ball ``||b - b_hat||_2 <= radius``.

    Derivation. In a phase of mode ``(A, c)`` two motions started at ``z*`` and ``z* + delta``
    differ by ``expm(A s) delta`` at equal phase time ``s``, so by at most
    ``eps(s) = ||n|| M(s) Z`` along any event function ``g = n . z - g0`` (``Z >= ||delta||``,
    ``M(s) >= ||expm(A s)||``, sampled, and ``M(s_j + u) <= M(s_j) exp(||A|| u)``). Along the
    nominal motion ``g*' = n . f`` with ``f = A z + c``, and ``f(z*(s_j + u)) =
    expm(A u) f(z*(s_j))``, so ``g*`` is Lipschitz with ``||n|| F`` and ``n . f`` with
    ``||n^T A|| F`` (``F`` the sampled ``||f||`` times ``exp(||A|| h)``). Hence:

    * an interval where ``|g*| > eps`` (:func:`_clear`) holds no event of ``g``;
    * the other intervals must form, for the function that ends the phase, a final window
      and, for a function whose surface the phase starts on (after a breakaway or a band
      edge, where both motions start exactly on it), a first window; on each window the
      perturbed rate ``n . f`` keeps the nominal sign with modulus at least
      ``rho = min |n . f*| - ||n^T A|| (F h / 2 + M Z) > 0``. The start window is then left
      without a zero; at the end, ``|g(t*)| <= eps(t*)`` and monotonicity put the one zero
      within ``T = eps(t*) / rho`` of ``t*`` (checked again past ``t*`` with ``exp(||A|| T)``).
    * the event state moves by at most ``Z_e = M(t*) e^{||A|| T} Z + F_end e^{||A|| T} T``;
      at the belt speed the next mode (stick or slip through) is chosen by the stick force
      ``S = s . z``, kept by ``min |S* - level| > ||s|| Z_e``; ``Z_e`` starts the next phase.

    Jacobian. ``D P^q = R X_N ... X_1 L`` with ``X_i = S_i expm(A_i t_i)`` (saltation
    ``S = I + (f^+ - f^-) n^T / (n . f^-)`` at the event state, the final one with
    ``f^+ = 0``): ``X_i`` is the derivative of the map ``F_i`` from the start of phase ``i``
    to the start of the next. Over the tube ``||expm(A t) - expm(A t*)|| <= ||A|| T M(t*)
    e^{||A|| T}``; ``f^+ - f^-`` moves by ``||A^+ - A^-|| Z_e`` and ``n . f^-`` by
    ``||n^T A^-|| Z_e``, which bounds ``||S - S*||``: ``Delta_i >= ||X_i - X_i*||``.

    Tight deviations. The phase starts lie on hyperplanes (the event surfaces), so the
    segment between two of them does too, and the mean value inequality gives
    ``F_i(z) - F_i(z*) = X_i* (z - z*) + rho_i`` with ``||rho_i|| <= Delta_i Z_i``. Hence
    ``z_i - z_i* = G(0, i) L delta_b + sum_{j<i} G(j+1, i) rho_j`` with the nominal products
    ``G(j, i) = X*_{i-1} ... X*_j``, and ``Z_i <= ||G(0, i) L|| r + sum_{j<i} ||G(j+1, i)||
    Delta_j Z_j``: norms of products, not products of norms (the per-phase bound above is
    kept when smaller). Likewise ``prod X - prod X* = sum_i Q_i (X_i - X_i*) G(0, i)`` with
    the perturbed suffix ``Q_i = R X_N ... X_{i+1}``, ``||Q_i - Q_i*|| <= D_i = sum_{j>i}
    (||Q_j*|| + D_j) Delta_j ||G(i+1, j)||``, so ``E(r) = sum_i (||Q_i*|| + D_i) Delta_i
    ||G(0, i) L||`` bounds ``||D P^q - J||``.
    """
    z_dev = norms.prefix[0] * radius + ROUNDING * scale
    z_devs: list[float] = []
    stick_norm = float(np.linalg.norm(stick_normal))
    deltas: list[float] = []
    breakaway_dev: list[float] = []
    low_level = -lam * (1.0 + 2.0 * gamma)
    for i, ph in enumerate(phases):
        z_devs.append(z_dev)
        grow = math.exp(ph.norm_a * ph.h)
        m_int = np.maximum(ph.m_norm[:-1], ph.m_norm[1:]) * grow
        f_int = np.maximum(ph.flow_norm[:-1], ph.flow_norm[1:]) * grow
        f_max = float(np.max(f_int))
        t_dev = 0.0
        for e, (nv, _g0) in enumerate(ph.functions):
            n_norm = float(np.linalg.norm(nv))
            na_norm = float(np.linalg.norm(nv @ ph.a))
            eps = n_norm * m_int * z_dev
            clear = _clear(ph.g[:, e], n_norm * f_int * ph.h, eps)
            n_int = clear.size
            lo = 0
            if ph.start_zero[e]:
                while lo < n_int and not clear[lo]:
                    lo += 1
            hi = n_int
            if e == ph.ending:
                while hi > lo and not clear[hi - 1]:
                    hi -= 1
            if not np.all(clear[lo:hi]):
                return _Tube(False)
            for window in ((0, lo), (hi, n_int)):
                a_idx, b_idx = window
                if b_idx <= a_idx:
                    continue
                rates = ph.rate[a_idx:b_idx + 1, e]
                if not (np.all(rates > 0) or np.all(rates < 0)):
                    return _Tube(False)
                rho = float(np.min(np.abs(rates))) - na_norm * (
                    0.5 * f_max * ph.h + float(np.max(m_int[a_idx:b_idx])) * z_dev)
                if rho <= 0.0:
                    return _Tube(False)
                if window[0] == hi and e == ph.ending:
                    eps_end = n_norm * float(ph.m_norm[-1]) * z_dev
                    t_dev = eps_end / rho
                    if not t_dev * ph.norm_a < 1.0:
                        return _Tube(False)  # the end moves by a phase's worth: no bound
                    ext = math.exp(ph.norm_a * t_dev)
                    rate_end = abs(float(ph.rate[-1, e]))
                    if rate_end - na_norm * (float(ph.flow_norm[-1]) * ext * t_dev
                                             + float(ph.m_norm[-1]) * ext * z_dev) <= 0.0:
                        return _Tube(False)
            if e == ph.ending and hi == n_int:
                # the end itself clear: impossible (g* vanishes there); treat as failure
                return _Tube(False)
        ext = math.exp(ph.norm_a * t_dev)
        for e, (nv, _g0) in enumerate(ph.functions):
            if e == ph.ending:
                continue  # the other surfaces past t*, up to t* + T
            drift = float(np.linalg.norm(nv)) * (float(ph.flow_norm[-1]) * ext * t_dev
                                                 + float(ph.m_norm[-1]) * ext * z_dev)
            if abs(float(ph.g[-1, e])) <= drift:
                return _Tube(False)
        z_event = float(ph.m_norm[-1]) * ext * z_dev + float(ph.flow_norm[-1]) * ext * t_dev
        z_event += ROUNDING * scale
        if ph.belt_decision:
            force = float(stick_normal @ ph.z_end)
            if min(abs(force - lam), abs(force - low_level)) <= stick_norm * z_event:
                return _Tube(False)
        # the factor X = S expm(A t) and its variation over the tube
        nv = ph.functions[ph.ending][0]
        n_norm = float(np.linalg.norm(nv))
        u_star = ph.f_plus - ph.f_minus
        p_star = float(nv @ ph.f_minus)
        dp = float(np.linalg.norm(nv @ ph.a)) * z_event
        if abs(p_star) - dp <= 0.0:
            return _Tube(False)
        du = float(np.linalg.norm(ph.a_plus - ph.a)) * z_event
        d_salt = n_norm * (du / (abs(p_star) - dp)
                           + float(np.linalg.norm(u_star)) * dp / ((abs(p_star) - dp) * abs(p_star)))
        d_exp = ph.norm_a * t_dev * float(ph.m_norm[-1]) * ext
        deltas.append((ph.salt_norm + d_salt) * d_exp + d_salt * ph.e_norm)
        tight = norms.prefix[i + 1] * radius + sum(
            norms.between[j + 1][i + 1] * deltas[j] * z_devs[j] for j in range(i + 1))
        z_dev = min(z_event, tight + ROUNDING * scale)
        if ph.breakaway:
            breakaway_dev.append(z_dev)
    n_ph = len(phases)
    d_suffix = [0.0] * (n_ph + 1)
    for i in range(n_ph - 1, -1, -1):
        d_suffix[i] = sum((norms.suffix[j] + d_suffix[j]) * deltas[j] * norms.between[i + 1][j]
                          for j in range(i + 1, n_ph))
    bound = sum((norms.suffix[i] + d_suffix[i]) * deltas[i] * norms.prefix[i] for i in range(n_ph))
    return _Tube(True, bound, breakaway_dev)


@dataclass
class _ProductNorms:
    """Norms of the nominal products of :func:`_tube` (independent of the radius).

    ``prefix[i] = ||G(0, i) L||`` (``i = 0..N``), ``suffix[i] = ||R G(i + 1, N)||`` and
    ``between[j][i] = ||G(j, i)||`` (``G(j, i) = X*_{i-1} ... X*_j``, the identity for
    ``j >= i``), 2-norms.
    """

    prefix: list[float]
    suffix: list[float]
    between: list[list[float]]

    @classmethod
    def of(cls, phases: list[_Phase], lift: FloatArray, reduce_rows: FloatArray) -> _ProductNorms:
        n_ph = len(phases)
        factors = [ph.salt @ ph.e_nominal for ph in phases]
        dim = lift.shape[0]
        between = [[1.0] * (n_ph + 1) for _ in range(n_ph + 1)]
        for j in range(n_ph):
            product = np.eye(dim)
            for i in range(j + 1, n_ph + 1):
                product = factors[i - 1] @ product
                between[j][i] = float(np.linalg.norm(product, 2))
        prefix, product = [], lift.copy()
        for i in range(n_ph + 1):
            prefix.append(float(np.linalg.norm(product, 2)))
            if i < n_ph:
                product = factors[i] @ product
        suffix, product = [0.0] * n_ph, reduce_rows.copy()
        for i in range(n_ph - 1, -1, -1):
            suffix[i] = float(np.linalg.norm(product, 2))
            product = product @ factors[i]
        return cls(prefix, suffix, between)


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
    phases: list[_Phase]
    z_hit: FloatArray
    breakaway_states: list[FloatArray]
    value: FloatArray  # P^q(b_hat)


def _candidate(pmap: _ReturnMap, b0: FloatArray, q: int) -> _Candidate | None:
    solution = _newton(pmap, b0, q)
    if solution is None:
        return None
    b_hat, jac = solution
    value = pmap(b_hat, q)
    if value is None:
        return None
    sampled = _phases(pmap, b_hat, q)
    if sampled is None:
        return None
    phases, z_hit = sampled
    states = pmap.next_breakaways(pmap.state(b_hat), q)
    return _Candidate(q, b_hat, jac, float(np.linalg.norm(value - b_hat)), phases, z_hit, states,
                      value)


def _ball(pmap: _ReturnMap, cand: _Candidate, accept: Any) -> tuple[float, _Tube] | None:
    """The largest radius of the ladder whose tube passes ``accept(radius, tube)``."""
    n2 = 2 * pmap.n
    reduce_rows = np.delete(np.eye(n2), [0, pmap.n], axis=0)  # R: the foundation coordinates
    norms = _ProductNorms.of(cand.phases, pmap.lift, reduce_rows)
    scale = max(1.0, float(np.max(np.abs(pmap.state(cand.b_hat)))))
    lam, gamma = float(pmap.slider.lam), float(pmap.slider.gamma)
    for i in range(RADIUS_TRIES):
        radius = scale * RADIUS_START * RADIUS_FACTOR ** (-i)
        tube = _tube(cand.phases, norms, pmap.stick_normal, lam, gamma, radius, scale)
        if tube.ok and accept(radius, tube):
            return radius, tube
    return None


def _shorter_period_excluded(pmap: _ReturnMap, cand: _Candidate, radius: float,
                             tube: _Tube) -> bool:
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


def _contraction_ball(pmap: _ReturnMap, cand: _Candidate) -> tuple[float, float, FloatArray] | None:
    """``(radius, theta, C)`` of a proven contraction ball about ``b_hat`` (step 3)."""
    adapted = _adapted_norm(cand.jac)
    if adapted is None:
        return None
    chol, norm_w, kappa = adapted
    c_inv_norm = float(np.linalg.norm(np.linalg.inv(chol), 2)) if chol.size else 1.0
    residual_w = float(np.linalg.norm(chol @ (cand.value - cand.b_hat)))
    thetas: dict[float, float] = {}

    def accept(radius: float, tube: _Tube) -> bool:
        theta = norm_w + kappa * tube.jacobian_bound
        rho = radius / c_inv_norm
        thetas[radius] = theta
        return (theta < 1.0 and residual_w <= (1.0 - theta) * rho
                and _shorter_period_excluded(pmap, cand, radius, tube))

    found = _ball(pmap, cand, accept)
    if found is None:
        return None
    radius = found[0]
    return radius / c_inv_norm, thetas[radius], chol


def prove_cycle(structure: Structure, slider: Slider, breakaway_state: FloatArray,
                candidate_phases: int, options: EngineOptions, *,
                extra_breakaways: int = 512) -> CycleProof | None:
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

    Returns
    -------
    CycleProof or None
        None when no divisor of ``k`` gives a proof: the verdict stays undetermined.
    """
    pmap0 = _ReturnMap(structure, slider, options)
    direction = pmap0.direction_of(np.asarray(breakaway_state, dtype=np.float64))
    pmap = pmap0 if direction == SLIP_I else _ReturnMap(structure, slider, options, direction)
    b0 = pmap.reduce(np.asarray(breakaway_state, dtype=np.float64))
    for q in divisors(int(candidate_phases)):
        cand = _candidate(pmap, b0, q)
        if cand is None:
            continue
        ball = _contraction_ball(pmap, cand)
        if ball is None:
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
                if float(np.linalg.norm(chol @ (b - cand.b_hat))) <= rho:
                    return CycleProof(q, pmap.state(cand.b_hat), multipliers, theta, radius,
                                      float(np.linalg.norm(b - cand.b_hat)), cand.residual,
                                      extra, onto, chol)
            if extra >= extra_breakaways:
                break
            if not later:
                later = pmap.next_breakaways(state, min(EXTRA_CHUNK, extra_breakaways - extra))
                if not later:
                    break
            state = later.pop(0)
            extra += 1
    return None


def prove_existence(structure: Structure, slider: Slider, b_hat: FloatArray, q: int,
                    options: EngineOptions, direction: int = SLIP_I) -> float | None:
    """Radius of a ball about ``b_hat`` holding exactly one fixed point of ``P^q`` (stable or not).

    The Newton-Kantorovich form of the module notes; also checks that no proper divisor of
    ``q`` is a period (step 5). None when no radius of the ladder passes.
    """
    pmap = _ReturnMap(structure, slider, options, direction)
    cand = _candidate(pmap, np.asarray(b_hat, dtype=np.float64), int(q))
    if cand is None:
        return None
    if cand.jac.size == 0:
        return 0.0
    try:
        a_inv = np.linalg.inv(cand.jac - np.eye(cand.jac.shape[0]))
    except np.linalg.LinAlgError:
        return None
    a_norm = float(np.linalg.norm(a_inv, 2))

    def accept(radius: float, tube: _Tube) -> bool:
        contraction = a_norm * tube.jacobian_bound
        return (contraction < 1.0 and a_norm * cand.residual + contraction * radius <= radius
                and _shorter_period_excluded(pmap, cand, radius, tube))

    found = _ball(pmap, cand, accept)
    return None if found is None else found[0]
