"""The tube bound behind a cycle proof: every trajectory from a ball follows the nominal one.

:func:`phases` samples the nominal run of ``P^q`` phase by phase (event surfaces, rates,
``||expm(A s)||``, by :mod:`stickslip.analysis._phase_flow`), :class:`ProductNorms` holds
the norms of the nominal Jacobian's partial products, and :func:`tube_bound` bounds, for a
radius ``r``, the deviation of every trajectory started in the ball ``B(b_hat, r)`` and
``sup ||D P^q - J||`` over it (derivation in its docstring).
:mod:`stickslip.analysis.cycle_proof` turns the bound into proofs.

Rounding: the nominal quantities are computed in double precision; every bound adds
:func:`rounding_allowance` (the engine's rounding along the run) to the deviations it
carries, and a proof to its residual, so a proof does not rest on the last bits.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis import _phase_flow as flow
from stickslip.analysis.return_map import ReturnMap
from stickslip.kernel.linalg import expm
from stickslip.kernel.system import SLIP_I, STICK, mode_kind_band

FloatArray = NDArray[np.float64]

#: Relative round-off allowance, the floor of :func:`rounding_allowance`.
ROUNDING = 1e-13


@dataclass(frozen=True)
class Coordinates:
    """The coordinates ``y = T^-1 z`` a tube is bounded in (the engine's state is ``z``).

    The tube's bounds are 2-norm bounds, true in any coordinates; their size is not. In the
    *energy coordinates* (:meth:`energy`) ``|y|^2 / 2`` is the structure's mechanical energy,
    so a passive mode's flow does not grow (``||expm(A t)||_2 <= 1``), where in the engine's
    coordinates it can grow by ``sqrt(cond)`` of the mass and stiffness matrices.
    """

    to_state: FloatArray  # T
    from_state: FloatArray  # T^-1

    @property
    def to_state_norm(self) -> float:
        """``||T||_2``: a deviation in ``y`` is at most this times larger in ``z``."""
        return float(np.linalg.norm(self.to_state, 2))

    @property
    def from_state_norm(self) -> float:
        """``||T^-1||_2``: a deviation in ``z`` is at most this times larger in ``y``."""
        return float(np.linalg.norm(self.from_state, 2))

    @classmethod
    def identity(cls, n2: int) -> Coordinates:
        """The engine's own coordinates."""
        return cls(np.eye(n2), np.eye(n2))

    @classmethod
    def energy(cls, mass: FloatArray, stiffness: FloatArray) -> Coordinates:
        """``y = (K^(1/2) q, M^(1/2) v)``; the identity unless both matrices are positive
        definite (a structure with a rigid-body mode has no energy norm)."""
        n = mass.shape[0]
        roots = []
        for matrix in (stiffness, mass):
            sym = 0.5 * (np.asarray(matrix, dtype=np.float64) + np.asarray(matrix).T)
            w, v = np.linalg.eigh(sym)
            if not (w.size and np.all(np.isfinite(w)) and w[0] > 1e-12 * w[-1] > 0.0):
                return cls.identity(2 * n)
            roots.append((v * np.sqrt(w), v / np.sqrt(w)))  # columns scaled: V W^(1/2)
        (k_half, k_inv_half), (m_half, m_inv_half) = roots
        from_state = np.zeros((2 * n, 2 * n))
        to_state = np.zeros((2 * n, 2 * n))
        from_state[:n, :n] = k_half.T  # W^(1/2) V^T: a square root of K with |y|^2 = q' K q
        from_state[n:, n:] = m_half.T
        to_state[:n, :n] = k_inv_half  # its inverse V W^(-1/2)
        to_state[n:, n:] = m_inv_half
        return cls(to_state, from_state)


@dataclass
class Phase:
    """Nominal data of one phase of the run behind ``P^q`` (see :func:`phases`)."""

    mode: int
    duration: float
    a: FloatArray  # A of z' = A z + c
    c: FloatArray
    norm_a: float
    functions: list[tuple[FloatArray, float]]  # (normal n, level g0): g = n.z - g0
    ending: int  # index into functions of the event that ends the phase
    start_zero: list[bool]  # functions that vanish at the start (left from their surface)
    tangential: list[bool]  # ... and leave it tangentially: rate 0 on the whole start section
    g: FloatArray  # (samples, functions) nominal g at the samples
    rate: FloatArray  # (samples, functions) nominal n.f
    curv: FloatArray  # (samples, functions) nominal n.A f, the second derivative of g
    flow_norm: FloatArray  # ||f(z*(s_j))||_2 at the samples
    m_norm: FloatArray  # bounds of ||expm(A s_j)||_2 at the samples (sampled_flow)
    hs: FloatArray  # the sample intervals' lengths
    z_end: FloatArray
    f_minus: FloatArray  # field of this mode at z_end
    f_plus: FloatArray  # field of the next mode at z_end (0 at the map's final section)
    a_plus: FloatArray
    belt_decision: bool  # ends at the belt speed: the next mode is chosen by the stick force
    e_nominal: FloatArray  # expm(A t)
    breakaway: bool  # ends with a breakaway (counted for the minimal-period check)
    engine_norm_a: float  # ||A||_F in the engine's coordinates (its step size: the rounding)
    salt: FloatArray = field(init=False)  # the nominal saltation matrix at the end
    salt_norm: float = field(init=False)
    e_norm: float = field(init=False)

    def __post_init__(self) -> None:
        nv = self.functions[self.ending][0]
        self.salt = (np.eye(self.f_minus.size)
                     + np.outer(self.f_plus - self.f_minus, nv) / float(nv @ self.f_minus))
        self.salt_norm = float(np.linalg.norm(self.salt, 2))
        self.e_norm = float(np.linalg.norm(self.e_nominal, 2))


def _functions(pmap: ReturnMap, mode: int) -> list[tuple[FloatArray, float]]:
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


def phases(pmap: ReturnMap, b: FloatArray, q: int, coords: Coordinates | None = None
           ) -> tuple[list[Phase], FloatArray] | None:
    """The nominal phases from ``state(b)`` to its ``q``-th breakaway, sampled for the tube.

    ``coords``: the coordinates ``y = T^-1 z`` every phase is expressed in (its matrix
    ``T^-1 A T``, its states, the normals ``n T`` of its surfaces): the identity when None.
    The returned breakaway state ``z_hit`` is in the engine's coordinates.
    """
    if coords is None:
        coords = Coordinates.identity(2 * pmap.n)
    to_y, to_z = coords.from_state, coords.to_state
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
    phases: list[Phase] = []
    n2 = 2 * pmap.n
    lift = to_y @ pmap.lift
    ends = np.append(seg_t[first + 1:last + 1], t_hit)
    for mode, t0, t1 in zip(seg_mode[first:last + 1], seg_t[first:last + 1], ends, strict=True):
        norm_a = float(np.linalg.norm(to_y @ pmap.flow_matrix[int(mode)] @ to_z))
        samples = flow.sample_times(float(t1 - t0), norm_a)[0].size
        if flow.flow_work(samples, n2 + 1) > flow.MAX_PHASE_WORK:
            return None  # beyond the work a proof may take (MAX_PHASE_WORK): not proven
    for i in range(first, last + 1):
        mode = int(seg_mode[i])
        t0 = float(seg_t[i])
        t1 = t_hit if i == last else float(seg_t[i + 1])
        z0 = np.asarray(seg_z[i], dtype=np.float64)
        z_end = z_hit if i == last else np.asarray(seg_z[i + 1], dtype=np.float64)
        belt = mode != STICK and abs(float(z_end[pmap.n]) - 1.0) <= 1e-12
        # the tolerances on the surfaces' values (invariant: n T . T^-1 z = n . z) scale with
        # the engine's state, which the events were located in
        scale = max(1.0, float(np.max(np.abs(z_end))))
        z0, z_end = to_y @ z0, to_y @ z_end
        a, c = to_y @ pmap.flow_matrix[mode] @ to_z, to_y @ pmap.flow_constant[mode]
        functions = [(nv @ to_z, g0) for nv, g0 in _functions(pmap, mode)]
        values_end = [abs(float(nv @ z_end) - g0) for nv, g0 in functions]
        ending = int(np.argmin(values_end))
        if values_end[ending] > 1e-7 * scale:
            return None  # the recorded phase end is on no surface: not a phase this proof knows
        start_zero = [abs(float(nv @ z0) - g0) <= 1e-9 * scale for nv, g0 in functions]
        duration = t1 - t0
        norm_a = float(np.linalg.norm(a))
        times, zs, m_norm = flow.sampled_flow(a, c, z0, duration, norm_a)
        hs = np.diff(times)
        fields = zs @ a.T + c
        normals = np.array([nv for nv, _ in functions])
        levels = np.array([g0 for _, g0 in functions])
        g = zs @ normals.T - levels
        g[-1] = normals @ z_end - levels  # the recorded end (the event's exact state)
        rate = fields @ normals.T
        curv = fields @ (normals @ a).T
        # a tangential departure (a law continuous at the static limit: F(0+) = the stick
        # bound): the rate vanishes at the start, and on the whole breakaway section (the
        # lifted states of every b), so every perturbed motion leaves at second order
        at_breakaway = i == first or int(seg_mode[i - 1]) == STICK
        rate_scale = float(np.max(np.abs(rate))) + 1e-300
        tangential = [
            zero and at_breakaway and abs(float(rate[0, e])) <= 1e-12 * rate_scale
            and float(np.linalg.norm((normals[e] @ a) @ lift))
            <= 1e-12 * float(np.linalg.norm(normals[e] @ a)) * float(np.linalg.norm(lift))
            for e, zero in enumerate(start_zero)]
        if i == last:
            f_plus, a_plus, belt, bk = np.zeros(n2), np.zeros((n2, n2)), False, True
        else:
            nxt = int(seg_mode[i + 1])
            a_plus = to_y @ pmap.flow_matrix[nxt] @ to_z
            f_plus = a_plus @ z_end + to_y @ pmap.flow_constant[nxt]
            bk = mode == STICK
        phases.append(Phase(mode, duration, a, c, norm_a, functions, ending, start_zero,
                            tangential, g, rate, curv,
                             np.linalg.norm(fields, axis=1), m_norm, hs, z_end,
                             a @ z_end + c, f_plus, a_plus, belt, expm(a * duration),
                             bk, float(np.linalg.norm(pmap.flow_matrix[mode]))))
    return phases, z_hit


@dataclass
class Tube:
    """Outcome of :func:`tube_bound` at one radius."""

    ok: bool
    jacobian_bound: float = math.inf  # E(r)
    breakaway_deviation: list[float] = field(default_factory=list)  # Z at each breakaway
    failed_phase: int = -1  # the phase whose check failed (not ok); -1 when ok
    failed_deviation: float = math.nan  # the deviation Z the tube carried into that phase


def interval_floor(values: FloatArray, curvature: FloatArray) -> FloatArray:
    """Per sample interval: a lower bound of ``|v|`` over it; negative where ``v`` may vanish.

    ``v`` is sampled at the interval's ends; ``curvature`` bounds ``|v''| h^2 / 8`` on each
    interval, the error of the linear interpolant. With end values of one sign, ``|v| >=
    min(|v_j|, |v_{j+1}|) - curvature`` there; an interval whose ends differ in sign gets -1.
    """
    same = np.sign(values[:-1]) * np.sign(values[1:]) > 0
    low = np.minimum(np.abs(values[:-1]), np.abs(values[1:])) - curvature
    return np.where(same, low, -1.0)


def clear_of_zero(g: FloatArray, curvature: FloatArray, eps: FloatArray) -> NDArray[np.bool_]:
    """Per sample interval: ``|g*| > eps`` on all of it (see :func:`interval_floor`)."""
    return interval_floor(g, curvature) > eps


def _end_time_deviation(ph: Phase, z_dev: float) -> float | None:
    """``T``: how far the phase's end moves for starts within ``z_dev``; None without a bound.

    The event checks of :func:`tube_bound` for one phase: every event surface clear of the
    perturbed motions except in the windows next to the surfaces the phase starts on and ends
    on, where the rate keeps its sign (see its docstring).
    """
    grow = np.exp(ph.norm_a * ph.hs)
    m_int = np.maximum(ph.m_norm[:-1], ph.m_norm[1:]) * grow
    f_int = np.maximum(ph.flow_norm[:-1], ph.flow_norm[1:]) * grow
    # |d^k/ds^k (n . z*)| <= ||n A^k|| F: the linear interpolant's error is that times h^2 / 8
    h2 = f_int * ph.hs ** 2 / 8.0
    t_dev = 0.0
    for e, (nv, _g0) in enumerate(ph.functions):
        n_norm = float(np.linalg.norm(nv))
        na_norm = float(np.linalg.norm(nv @ ph.a))
        eps = n_norm * m_int * z_dev
        clear = clear_of_zero(ph.g[:, e], na_norm * h2, eps)
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
            return None
        for window in ((0, lo), (hi, n_int)):
            a_idx, b_idx = window
            if b_idx <= a_idx:
                continue
            if a_idx == 0 and ph.tangential[e]:
                # g = g' = 0 at the start for every perturbed motion: g'' keeps its sign
                curvs = ph.curv[0:b_idx + 1, e]
                na2 = float(np.linalg.norm(nv @ ph.a @ ph.a))
                na3 = float(np.linalg.norm(nv @ ph.a @ ph.a @ ph.a))
                floor = interval_floor(curvs, na3 * h2[a_idx:b_idx])
                rho2 = float(np.min(floor)) - na2 * float(np.max(m_int[a_idx:b_idx])) * z_dev
                if not (np.all(curvs > 0) or np.all(curvs < 0)) or rho2 <= 0.0:
                    return None
                continue
            rates = ph.rate[a_idx:b_idx + 1, e]
            if not (np.all(rates > 0) or np.all(rates < 0)):
                return None
            na2 = float(np.linalg.norm(nv @ ph.a @ ph.a))
            floor = interval_floor(rates, na2 * h2[a_idx:b_idx])
            rho = float(np.min(floor)) - na_norm * float(np.max(m_int[a_idx:b_idx])) * z_dev
            if rho <= 0.0:
                return None
            if window[0] == hi and e == ph.ending:
                eps_end = n_norm * float(ph.m_norm[-1]) * z_dev
                t_dev = eps_end / rho
                if not t_dev * ph.norm_a < 1.0:
                    return None  # the end moves by a phase's worth: no bound
                ext = math.exp(ph.norm_a * t_dev)
                rate_end = abs(float(ph.rate[-1, e]))
                if rate_end - na_norm * (float(ph.flow_norm[-1]) * ext * t_dev
                                         + float(ph.m_norm[-1]) * ext * z_dev) <= 0.0:
                    return None
        if e == ph.ending and hi == n_int:
            # the end itself clear: impossible (g* vanishes there); treat as failure
            return None
    ext = math.exp(ph.norm_a * t_dev)
    f_end = float(np.linalg.norm(ph.f_minus))
    for e, (nv, _g0) in enumerate(ph.functions):
        if e == ph.ending:
            continue  # the other surfaces past t*, up to t* + T
        n_norm = float(np.linalg.norm(nv))
        spread = n_norm * float(ph.m_norm[-1]) * ext * z_dev
        # the nominal continuation moves g by at most T |n . f(z*)| + ||n^T A|| ||f|| T^2 e/2
        # (f(z*(t* + s)) = expm(A s) f(z*(t*)); see end_drift), or by ||n|| ||f|| e T
        along = min(n_norm * float(ph.flow_norm[-1]) * ext * t_dev,
                    end_drift(nv, ph.a, ph.f_minus, f_end, ph.norm_a, t_dev))
        if abs(float(ph.g[-1, e])) <= spread + along:
            return None
    return t_dev


def end_drift(nv: FloatArray, a: FloatArray, f_star: FloatArray, f_norm: float, norm_a: float,
              t_dev: float) -> float:
    """Bound of ``|g*(t* + u) - g*(t*)|`` for ``0 <= u <= t_dev`` along the nominal flow.

    With ``g = n . z - g0`` and ``z' = A z + c``, ``g*' = n . f`` and ``f(z*(t* + s)) =
    expm(A s) f*`` (``f*`` the field at the phase's end). ``expm(A s) - I = int_0^s A
    expm(A r) dr`` gives ``|n . (expm(A s) - I) f*| <= ||n^T A|| s exp(||A|| s) ||f*||``, so

    ``|g*(t* + u) - g*(t*)| <= u |n . f*| + ||n^T A|| ||f*|| u^2 exp(||A|| u) / 2``,

    increasing in ``u``: its value at ``t_dev`` bounds the window. Tighter than ``||n|| ||f*||
    exp(||A|| T) T`` when the surface's rate ``n . f*`` is small (a band edge of the same
    velocity near the one the phase ends on).

    Parameters
    ----------
    nv : ndarray
        The surface's normal ``n``.
    a : ndarray
        The mode's matrix ``A``.
    f_star : ndarray
        ``f*``: the nominal field at the phase's end.
    f_norm : float
        ``||f*||_2``.
    norm_a : float
        A bound of ``||A||_2`` (the Frobenius norm).
    t_dev : float
        ``T``: the window past ``t*``.

    Returns
    -------
    float
        The bound.
    """
    return (t_dev * abs(float(nv @ f_star))
            + float(np.linalg.norm(nv @ a)) * f_norm * t_dev ** 2 * math.exp(norm_a * t_dev) / 2.0)


#: Allowance for the engine's rounding per step, in units of the machine epsilon (see
#: :func:`rounding_allowance`).
STEP_ROUNDING = 2.0


def rounding_allowance(phases: list[Phase], scale: float) -> float:
    """The engine's rounding along the nominal run of ``P^q``: an absolute allowance.

    The engine steps with ``h ||A|| <= 1/2`` (its own matrix, in its coordinates ``z``, not
    the tube's), so a phase of duration ``t`` takes at most ``2 t ||A||_F + 1`` steps; the
    allowance is :data:`STEP_ROUNDING` machine epsilons of the state's scale per step, over the
    whole run (at least :data:`ROUNDING` of the scale). It is calibrated, not a worst-case
    bound (which would multiply by the propagator's size): an independent extended-precision
    integration of a 44-DOF machine measured the error of one map evaluation at 5.2e-12, 1.1
    epsilon per step of its 2,222; the allowance, about twice that per step, is 9.4e-12 there
    (the 1e-13 of the scale allowed before let a ball of radius 1.4e-11 be claimed that the
    exact map leaves). The tube adds it to the deviations it carries (in its coordinates,
    times ``||T^-1||``), and a proof to the computed residual ``P^q(b_hat) - b_hat``: a ball
    must be wide enough to hold it.

    Parameters
    ----------
    phases : list of Phase
        The nominal run's phases (:func:`phases`).
    scale : float
        The state's scale (``max(1, max |z|)``).

    Returns
    -------
    float
        The allowance, in the state's units.
    """
    steps = sum(2.0 * ph.duration * ph.engine_norm_a + 1.0 for ph in phases)
    return max(ROUNDING, STEP_ROUNDING * float(np.finfo(np.float64).eps) * steps) * scale


def tube_bound(phases: list[Phase], norms: ProductNorms, stick_normal: FloatArray,
               lam: float, gamma: float, radius: float, scale: float,
               coords: Coordinates | None = None) -> Tube:
    """Bounds over every trajectory started in the ball ``||b - b_hat||_2 <= radius``.

    Derivation. In a phase of mode ``(A, c)`` two motions started at ``z*`` and ``z* + delta``
    differ by ``expm(A s) delta`` at equal phase time ``s``, so by at most
    ``eps(s) = ||n|| M(s) Z`` along any event function ``g = n . z - g0`` (``Z >= ||delta||``,
    ``M(s) >= ||expm(A s)||``, sampled, and ``M(s_j + u) <= M(s_j) exp(||A|| u)``). Along the
    nominal motion ``g*' = n . f`` with ``f = A z + c``, and ``f(z*(s_j + u)) =
    expm(A u) f(z*(s_j))``, so the ``k``-th derivative of ``g*`` is ``n . A^(k-1) f``, bounded
    by ``||n^T A^(k-1)|| F`` (``F`` the sampled ``||f||`` times ``exp(||A|| h)``): on a sample
    interval of length ``h`` the linear interpolant of ``g*`` (of its rate, of its curvature)
    is within ``||n^T A|| F h^2 / 8`` (``||n^T A^2|| ...``, ``||n^T A^3|| ...``) of it
    (:func:`interval_floor`). Hence:

    * an interval where ``|g*| > eps`` (:func:`clear_of_zero`) holds no event of ``g``;
    * the other intervals must form, for the function that ends the phase, a final window
      and, for a function whose surface the phase starts on (after a breakaway or a band
      edge, where both motions start exactly on it), a first window; on each window the
      perturbed rate ``n . f`` keeps the nominal sign with modulus at least
      ``rho = min |n . f*| - ||n^T A|| M Z > 0`` (the minimum over the interpolant, less
      its error). The start window is then left
      without a zero; at the end, ``|g(t*)| <= eps(t*)`` and monotonicity put the one zero
      within ``T = eps(t*) / rho`` of ``t*`` (checked again past ``t*`` with ``exp(||A|| T)``).
    * a tangential departure at a breakaway (a law continuous at the static limit, so the
      slider's acceleration is zero there: ``g = g' = 0`` at the start of every perturbed
      motion, the rate vanishing on the whole breakaway section, ``||(n^T A) L|| = 0`` to
      rounding): on the first window ``g'' = n . A f`` keeps its sign with modulus at least
      ``min |n . A f*| - ||n^T A^2|| M Z > 0``, so the motion leaves the surface.
    * the event state moves by at most ``Z_e = M(t*) e^{||A|| T} Z + F_end e^{||A|| T} T``;
      at the belt speed the next mode (stick or slip through) is chosen by the stick force
      ``S = s . z``, kept by ``min |S* - level| > ||s|| Z_e``; ``Z_e`` starts the next phase.

    Jacobian. ``D P^q = R X_N ... X_1 L`` with ``X_i = S_i expm(A_i t_i)`` (saltation
    ``S = I + (f^+ - f^-) n^T / (n . f^-)`` at the event state, the final one with
    ``f^+ = 0``): ``X_i`` is the derivative of the map ``F_i`` from the start of phase ``i``
    to the start of the next. Over the tube ``||expm(A t) - expm(A t*)|| <= ||A|| T M(t*)
    e^{||A|| T}``; ``f^+ - f^-`` moves by ``||A^+ - A^-|| Z_e`` (at a friction-band edge by
    ``||(A^+ - A^-) P|| Z_e``, ``P`` the projector onto the surface, which holds both event
    points: zero to rounding for a continuous law) and ``n . f^-`` by ``||n^T A^-|| Z_e``,
    which bounds ``||S - S*||``: ``Delta_i >= ||X_i - X_i*||``.

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
    if coords is None:
        coords = Coordinates.identity(stick_normal.size)
    # the phases, their products and the deviations are in the coordinates y = T^-1 z
    stick_normal = stick_normal @ coords.to_state
    rounding = rounding_allowance(phases, scale) * coords.from_state_norm
    z_dev = norms.prefix[0] * radius + rounding
    z_devs: list[float] = []
    stick_norm = float(np.linalg.norm(stick_normal))
    deltas: list[float] = []
    carried: list[float] = []  # Delta_j Z_j
    breakaway_dev: list[float] = []
    low_level = -lam * (1.0 + 2.0 * gamma)
    for i, ph in enumerate(phases):
        z_devs.append(z_dev)
        t_dev = _end_time_deviation(ph, z_dev)
        if t_dev is None:
            return Tube(False, failed_phase=i, failed_deviation=z_dev)
        ext = math.exp(ph.norm_a * t_dev)
        z_event = float(ph.m_norm[-1]) * ext * z_dev + float(ph.flow_norm[-1]) * ext * t_dev
        z_event += rounding
        if ph.belt_decision:
            force = float(stick_normal @ ph.z_end)
            if min(abs(force - lam), abs(force - low_level)) <= stick_norm * z_event:
                return Tube(False, failed_phase=i, failed_deviation=z_dev)
        # the factor X = S expm(A t) and its variation over the tube
        nv = ph.functions[ph.ending][0]
        n_norm = float(np.linalg.norm(nv))
        u_star = ph.f_plus - ph.f_minus
        p_star = float(nv @ ph.f_minus)
        dp = float(np.linalg.norm(nv @ ph.a)) * z_event
        if abs(p_star) - dp <= 0.0:
            return Tube(False, failed_phase=i, failed_deviation=z_dev)
        jump = ph.a_plus - ph.a
        if not (ph.belt_decision or ph.breakaway):
            # a friction-band edge: both event points lie on the surface n . z = g0, so
            # (f+ - f-)(z) - (f+ - f-)(z*) = (A+ - A-) P (z - z*) with P the projector onto
            # the surface (the law is continuous there: A+ - A- is in n's column alone, and
            # (A+ - A-) P vanishes up to rounding)
            jump = jump - np.outer(jump @ nv, nv) / float(nv @ nv)
        du = float(np.linalg.norm(jump)) * z_event
        d_salt = n_norm * (du / (abs(p_star) - dp)
                           + float(np.linalg.norm(u_star)) * dp / ((abs(p_star) - dp) * abs(p_star)))
        d_exp = ph.norm_a * t_dev * float(ph.m_norm[-1]) * ext
        deltas.append((ph.salt_norm + d_salt) * d_exp + d_salt * ph.e_norm)
        carried.append(deltas[-1] * z_devs[-1])
        tight = norms.prefix[i + 1] * radius + float(norms.between[1:i + 2, i + 1] @ np.array(carried))
        z_dev = min(z_event, tight + rounding)
        if ph.breakaway:
            breakaway_dev.append(z_dev * coords.to_state_norm)  # in the engine's coordinates
    n_ph = len(phases)
    suffix, delta = np.array(norms.suffix), np.array(deltas)
    d_suffix = np.zeros(n_ph + 1)
    for i in range(n_ph - 1, -1, -1):
        j = slice(i + 1, n_ph)
        d_suffix[i] = float(((suffix[j] + d_suffix[j]) * delta[j]) @ norms.between[i + 1, j])
    bound = float(((suffix + d_suffix[:n_ph]) * delta) @ np.array(norms.prefix[:n_ph]))
    return Tube(True, bound, breakaway_dev)


@dataclass
class ProductNorms:
    """Norms of the nominal products of :func:`tube_bound` (independent of the radius).

    ``prefix[i] = ||G(0, i) L||`` (``i = 0..N``), ``suffix[i] = ||R G(i + 1, N)||`` and
    ``between[j, i] = ||G(j, i)||`` (``G(j, i) = X*_{i-1} ... X*_j``, the identity for
    ``j >= i``), 2-norms.
    """

    prefix: list[float]
    suffix: list[float]
    between: FloatArray

    @classmethod
    def of(cls, phases: list[Phase], lift: FloatArray, reduce_rows: FloatArray) -> ProductNorms:
        """The norms of the nominal run's products (the factors ``X* = S expm(A t)``).

        ``between`` has ``N^2 / 2`` entries: the products of ``d`` consecutive factors are
        formed for every start at once (``G(j, j + d) = X*_{j+d-1} G(j, j + d - 1)``, one
        stacked product per ``d``) and their 2-norms taken as one stacked SVD.
        """
        n_ph = len(phases)
        factors = np.array([ph.salt @ ph.e_nominal for ph in phases])
        between = np.ones((n_ph + 1, n_ph + 1))
        product = factors.copy()  # G(j, j + 1) for j = 0..N-1
        for d in range(1, n_ph + 1):
            starts = np.arange(n_ph - d + 1)
            between[starts, starts + d] = np.linalg.svd(product, compute_uv=False)[:, 0]
            if d < n_ph:
                product = factors[d:] @ product[:-1]  # G(j, j + d + 1) = X*_{j+d} G(j, j + d)
        prefix, current = [], lift.copy()
        for i in range(n_ph + 1):
            prefix.append(float(np.linalg.norm(current, 2)))
            if i < n_ph:
                current = factors[i] @ current
        suffix, current = [0.0] * n_ph, reduce_rows.copy()
        for i in range(n_ph - 1, -1, -1):
            suffix[i] = float(np.linalg.norm(current, 2))
            current = current @ factors[i]
        return cls(prefix, suffix, between)
