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

import itertools
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis import _phase_flow as flow
from stickslip.analysis._band_variation import BandVariation, band_growth
from stickslip.analysis._interval_bounds import clear_of_zero, end_drift, interval_floor
from stickslip.analysis._product_norms import ProductNorms
from stickslip.analysis._tube_coordinates import Coordinates
from stickslip.analysis._tube_phase import Phase
from stickslip.analysis.return_map import ReturnMap
from stickslip.kernel.linalg import expm
from stickslip.kernel.system import SLIP_I, STICK, mode_kind_band

FloatArray = NDArray[np.float64]

#: Relative round-off allowance, the floor of :func:`rounding_allowance`.
ROUNDING = 1e-13


def _functions(pmap: ReturnMap, mode: int, guard: bool = False) -> list[tuple[FloatArray, float]]:
    """Every event surface of ``mode``: ``n . z = g0`` (the engine's events, Eq. 20 and bands);
    with ``guard``, a slip mode above band 0 has the belt speed ``u = 0`` last (the one true
    event the equal-time variant watches for there)."""
    lam, gamma = float(pmap.slider.lam), float(pmap.slider.gamma)
    kind, band = mode_kind_band(mode)
    if kind == STICK:
        return [(pmap.stick_normal, lam), (pmap.stick_normal, -lam * (1.0 + 2.0 * gamma))]
    edges = pmap.edges
    sign = -1.0 if kind == SLIP_I else 1.0
    out = [(pmap.slip_normal, 1.0 + sign * float(edges[band]))]
    if band + 1 < edges.size and math.isfinite(float(edges[band + 1])):
        out.append((pmap.slip_normal, 1.0 + sign * float(edges[band + 1])))
    if guard and band > 0:
        out.append((pmap.slip_normal, 1.0))
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
    run = pmap.recorded_run(pmap.state(b), q)
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
    bands = BandVariation.of(pmap.edges, pmap.flow_matrix, pmap.flow_constant, pmap.n, to_y, to_z)
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
        kind, band = mode_kind_band(mode)
        slip_bands = bands if kind != STICK else None
        functions = [(nv @ to_z, g0) for nv, g0 in _functions(pmap, mode, slip_bands is not None)]
        values_end = [abs(float(nv @ z_end) - g0) for nv, g0 in functions]
        ending = int(np.argmin(values_end))
        if values_end[ending] > 1e-7 * scale:
            return None  # the recorded phase end is on no surface: not a phase this proof knows
        start_zero = [abs(float(nv @ z0) - g0) <= 1e-9 * scale for nv, g0 in functions]
        duration = t1 - t0
        norm_a = float(np.linalg.norm(a))
        times, zs, m_norm, m_two = flow.sampled_flow(a, c, z0, duration, norm_a, bands is not None)
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
                             bk, float(np.linalg.norm(pmap.flow_matrix[mode])),
                            slip_bands, kind, band,
                            (0 if band == 0 else len(functions) - 1) if slip_bands else -1,
                            m_two=m_two))
    for one, after in itertools.pairwise(phases):
        one.edge_end = (one.bands is not None and after.bands is not None and not one.belt_decision
                        and after.kind == one.kind and abs(after.band - one.band) == 1)
    return phases, z_hit


@dataclass
class Tube:
    """Outcome of :func:`tube_bound` at one radius."""

    ok: bool
    jacobian_bound: float = math.inf  # E(r)
    breakaway_deviation: list[float] = field(default_factory=list)  # Z at each breakaway
    failed_phase: int = -1  # the phase whose check failed (not ok); -1 when ok
    failed_deviation: float = math.nan  # the deviation Z the tube carried into that phase
    deltas: list[float] = field(default_factory=list)  # Delta_i >= ||X_i - X_i*|| per phase
    weights: list[float] = field(default_factory=list)  # >= ||(X_i - X_i*) G(0, i) L||


def _end_time_deviation(ph: Phase, z_dev: float, extra: float = 0.0, kappa: float = 0.0,
                        equal_time: bool = False, tight: bool = False,
                        open_window: list[bool] | None = None) -> float | None:
    """``T``: how far the phase's end moves for starts within ``z_dev``; None without a bound.

    The event checks of :func:`tube_bound` for one phase: every event surface clear of the
    perturbed motions except in the windows next to the surfaces the phase starts on and ends
    on, where the rate keeps its sign (see its docstring). The deviation at phase time ``s``
    is ``M(s) z_dev + extra``. With ``equal_time`` (:mod:`stickslip.analysis._band_variation`)
    the band edges are no events: only the belt speed ``u = 0`` is watched, a phase ending
    at an edge has ``T = 0``, the perturbed field may differ by ``kappa`` times the deviation
    (another band's), also in the curvature of a tangential departure from ``u = 0``. With
    ``tight`` (the equal-time variant's run) the norms are the sampled 2-norms and the end's
    spread along a surface is ``||n expm(A t*)||``, a row's norm. ``open_window`` (equal times):
    ``[True]`` when a tangential departure's window from ``u = 0`` is still open at the
    phase's start (it spans the phases before, from the breakaway): ``g'' `` must keep its
    sign on until ``|g*|`` clears the deviation, so ``g`` cannot return to zero; set to
    whether it is open still at the phase's end.
    """
    m_norm = ph.m_two if tight and ph.m_two is not None else ph.m_norm
    grow = np.exp(ph.norm_a * ph.hs)
    m_int = np.maximum(m_norm[:-1], m_norm[1:]) * grow
    f_int = np.maximum(ph.flow_norm[:-1], ph.flow_norm[1:]) * grow
    # a deviation bound coef * (M z_dev + extra), kept in the association of the band-by-band
    # tube before the equal-time variant (extra = kappa = 0 there: the same floating values)
    def bounded(coef: float, m: float | FloatArray) -> Any:
        return coef * m * z_dev + coef * extra

    # |d^k/ds^k (n . z*)| <= ||n A^k|| F: the linear interpolant's error is that times h^2 / 8
    h2 = f_int * ph.hs ** 2 / 8.0
    t_dev = 0.0
    ends = not (equal_time and ph.edge_end)  # the phase ends at an event
    order = [e for e in range(len(ph.functions))
             if not (ph.is_equal_time_edge(e) if equal_time else e == ph.zero_surface > 0)]
    carried_in = bool(open_window and open_window[0]) and equal_time
    through = False  # the tangential window reaches the phase's end
    for e in order:  # (the guard u = 0 above band 0 is the equal-time variant's alone)
        nv, _g0 = ph.functions[e]
        n_norm = float(np.linalg.norm(nv))
        na_norm = float(np.linalg.norm(nv @ ph.a))
        clear = clear_of_zero(ph.g[:, e], na_norm * h2, bounded(n_norm, m_int))
        n_int = clear.size
        lo = 0
        carried = carried_in and e == ph.zero_surface
        if ph.start_zero[e] or carried:
            while lo < n_int and not clear[lo]:
                lo += 1
        if equal_time and e == ph.zero_surface and (ph.tangential[e] or carried) \
                and lo == n_int and not ends:
            through = True
        hi = n_int
        if e == ph.ending and ends:
            while hi > lo and not clear[hi - 1]:
                hi -= 1
        if not np.all(clear[lo:hi]):
            return None
        rate_gain = na_norm + n_norm * kappa  # |n . (f(z) - f(z*))| per unit deviation
        for window in ((0, lo), (hi, n_int)):
            a_idx, b_idx = window
            if b_idx <= a_idx:
                continue
            m_w = float(np.max(m_int[a_idx:b_idx]))
            if a_idx == 0 and (ph.tangential[e] or carried):
                # g = g' = 0 at the start for every perturbed motion: g'' keeps its sign
                curvs = ph.curv[0:b_idx + 1, e]
                na2 = float(np.linalg.norm(nv @ ph.a @ ph.a))
                na3 = float(np.linalg.norm(nv @ ph.a @ ph.a @ ph.a))
                floor = interval_floor(curvs, na3 * h2[a_idx:b_idx])
                # another band k: n A_k f_k(z) - n A f(z*) = n (A_k - A) f_k(z) + n A (A delta
                # + r), |n (A_k - A) f_k(z)| <= kappa |g'| (rank one), ||r|| <= kappa ||delta||
                slope = kappa * (float(np.max(np.abs(ph.rate[0:b_idx + 1, e]))) + bounded(rate_gain, m_w))
                rho2 = float(np.min(floor)) - bounded(na2, m_w) - bounded(na_norm * kappa, m_w) - slope
                if not (np.all(curvs > 0) or np.all(curvs < 0)) or rho2 <= 0.0:
                    return None
                continue
            rates = ph.rate[a_idx:b_idx + 1, e]
            if not (np.all(rates > 0) or np.all(rates < 0)):
                return None
            na2 = float(np.linalg.norm(nv @ ph.a @ ph.a))
            floor = interval_floor(rates, na2 * h2[a_idx:b_idx])
            rho = float(np.min(floor)) - bounded(rate_gain, m_w)
            if rho <= 0.0:
                return None
            if window[0] == hi and e == ph.ending:
                row = float(np.linalg.norm(nv @ ph.e_nominal)) if tight else math.inf
                eps_end = min(n_norm * float(m_norm[-1]), row) * z_dev + n_norm * extra
                t_dev = eps_end / rho
                if not t_dev * ph.norm_a < 1.0:
                    return None  # the end moves by a phase's worth: no bound
                ext = math.exp(ph.norm_a * t_dev)
                rate_end = abs(float(ph.rate[-1, e]))
                if rate_end - rate_gain * (float(ph.flow_norm[-1]) * ext * t_dev
                                           + float(m_norm[-1]) * ext * z_dev + extra) <= 0.0:
                    return None
        if e == ph.ending and ends and hi == n_int:
            # the end itself clear: impossible (g* vanishes there); treat as failure
            return None
    ext = math.exp(ph.norm_a * t_dev)
    f_end = float(np.linalg.norm(ph.f_minus))
    if open_window is not None:
        open_window[:] = [through]
    for e in order:
        nv = ph.functions[e][0]
        if e == ph.ending or (through and e == ph.zero_surface):
            continue  # the other surfaces past t*, up to t* + T (the open window: no zero)
        n_norm = float(np.linalg.norm(nv))
        spread = n_norm * float(m_norm[-1]) * ext * z_dev + n_norm * extra
        # the nominal continuation moves g by at most T |n . f(z*)| + ||n^T A|| ||f|| T^2 e/2
        # (f(z*(t* + s)) = expm(A s) f(z*(t*)); see end_drift), or by ||n|| ||f|| e T
        along = min(n_norm * float(ph.flow_norm[-1]) * ext * t_dev,
                    end_drift(nv, ph.a, ph.f_minus, f_end, ph.norm_a, t_dev))
        if abs(float(ph.g[-1, e])) <= spread + along:
            return None
    return t_dev


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
    return step_allowance(sum(engine_steps(ph.duration, ph.engine_norm_a) for ph in phases), scale)


def engine_steps(duration: float, norm_a: float) -> float:
    """At most ``2 t ||A||_F + 1`` engine steps in a phase of duration ``t`` (``h ||A|| <= 1/2``)."""
    return 2.0 * duration * norm_a + 1.0


def step_allowance(steps: float, scale: float) -> float:
    """:data:`STEP_ROUNDING` machine epsilons of ``scale`` per step (at least :data:`ROUNDING`
    of it): the allowance of :func:`rounding_allowance` for ``steps`` engine steps."""
    return max(ROUNDING, STEP_ROUNDING * float(np.finfo(np.float64).eps) * steps) * scale


# longer than 120 lines: its docstring holds the tube's whole derivation
def tube_bound(phases: list[Phase], norms: ProductNorms, stick_normal: FloatArray,
               lam: float, gamma: float, radius: float, scale: float,
               coords: Coordinates | None = None, equal_time: bool = False) -> Tube:
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
    ||G(0, i) L||`` bounds ``||D P^q - J||``. The equal-time variant (``equal_time``, see
    :mod:`stickslip.analysis._band_variation`: the band edges are no events) bounds
    ``||(X_i - X_i*) G(0, i) L||`` by ``||S|| ||expm(A t) - expm(A t*)|| ||G(0, i) L|| +
    ||S - S*|| ||expm(A t*) G(0, i) L||`` instead, the saltation's variation on the flowed
    product rather than on ``||expm(A t*)||`` times its norm (and ``expm(A (t* + s)) -
    expm(A t*) = int_0^s expm(A u) du A expm(A t*)``: ``||A expm(A t*) G(0, i) L||`` times
    ``T e^{||A|| T}``); likewise ``||(X_j - X_j*) G(i + 1, j)||`` in ``D_i`` for a phase ``j``
    ending at a breakaway (``ProductNorms.flowed_from``, ``rate_from``).
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
    carried = np.empty(len(phases))  # Delta_j Z_j (filled phase by phase)
    weights: list[float] = []  # bounds of ||(X_i - X_i*) G(0, i) L||
    window = [False]  # a tangential departure's window open across band edges
    split: dict[int, tuple[float, float, float, float]] = {}  # ||S||, T e^{||A|| T}, extra / Z, ||dS||
    breakaway_dev: list[float] = []
    low_level = -lam * (1.0 + 2.0 * gamma)
    for i, ph in enumerate(phases):
        z_devs.append(z_dev)
        et = equal_time and ph.bands is not None
        if not et:
            window[0] = False
        timed = _phase_timing(ph, z_dev, et, equal_time, window)
        if timed is None:
            return Tube(False, failed_phase=i, failed_deviation=z_dev)
        if not ph.edge_end:
            window[0] = False  # the slip ends: no window goes on
        extra, t_dev = timed
        ext = math.exp(ph.norm_a * t_dev)
        m_end = float(ph.m_two[-1]) if equal_time and ph.m_two is not None else float(ph.m_norm[-1])
        z_event = (m_end * ext * z_dev + extra
                   + float(ph.flow_norm[-1]) * ext * t_dev + rounding)
        if et and ph.edge_end:
            # equal times across the edge: X = expm(A t) against the perturbed Psi (saltation
            # the identity for a continuous law; the nominal's own is rounding from it)
            salt_off = ph.salt_off
            delta_i = extra / z_dev + salt_off if z_dev > 0.0 else salt_off
            weight = delta_i * norms.prefix[i]
        else:
            if ph.belt_decision:
                force = float(stick_normal @ ph.z_end)
                if min(abs(force - lam), abs(force - low_level)) <= stick_norm * z_event:
                    return Tube(False, failed_phase=i, failed_deviation=z_dev)
            # the factor X = S expm(A t) and its variation over the tube
            d_salt = _saltation_variation(ph, z_event)
            if d_salt is None:
                return Tube(False, failed_phase=i, failed_deviation=z_dev)
            d_exp = ph.norm_a * t_dev * m_end * ext + (extra / z_dev if z_dev > 0.0 else 0.0)
            delta_i = (ph.salt_norm + d_salt) * d_exp + d_salt * ph.e_norm
            # ||(X - X*) G L|| <= ||S|| ||expm(A t) - expm(A t*)|| ||G L|| + ||S - S*||
            # ||expm(A t*) G L||, expm(A (t* + s)) - expm(A t*) = int_0^s expm(A u) du A
            # expm(A t*) (and Psi's extra)
            shift = (t_dev * ext * norms.flowed_rate[i] if norms.flowed_rate else 0.0) + (
                (extra / z_dev if z_dev > 0.0 else 0.0) * norms.prefix[i])
            weight = (delta_i * norms.prefix[i] if not (equal_time and norms.flowed) else
                      (ph.salt_norm + d_salt) * shift + d_salt * norms.flowed[i])
            if equal_time and i in norms.flowed_from:
                split[i] = (ph.salt_norm + d_salt, t_dev * ext,
                            extra / z_dev if z_dev > 0.0 else 0.0, d_salt)
        deltas.append(delta_i)
        weights.append(weight)
        carried[i] = delta_i * z_devs[-1]
        tight = norms.prefix[i + 1] * radius + float(norms.between[1:i + 2, i + 1] @ carried[:i + 1])
        z_dev = min(z_event, tight + rounding)
        if ph.breakaway:
            breakaway_dev.append(z_dev * coords.to_state_norm)  # in the engine's coordinates
    n_ph = len(phases)
    suffix, delta = np.array(norms.suffix), np.array(deltas)
    d_suffix = np.zeros(n_ph + 1)
    for i in range(n_ph - 1, -1, -1):
        j = slice(i + 1, n_ph)
        terms = delta[j] * norms.between[i + 1, j]  # bounds of ||(X_j - X_j*) G(i + 1, j)||
        for k, (s_norm, t_shift, x_coef, d_salt) in split.items():
            if k > i:  # as the weights: the saltation's variation on the flowed product
                terms[k - i - 1] = (s_norm * (t_shift * norms.rate_from[k][i + 1]
                                              + x_coef * norms.between[i + 1, k])
                                    + d_salt * norms.flowed_from[k][i + 1])
        d_suffix[i] = float((suffix[j] + d_suffix[j]) @ terms)
    if equal_time:
        bound = float((suffix + d_suffix[:n_ph]) @ np.array(weights))
    else:  # (the same floating sum as before the equal-time variant)
        bound = float(((suffix + d_suffix[:n_ph]) * delta) @ np.array(norms.prefix[:n_ph]))
    return Tube(True, bound, breakaway_dev, deltas=deltas, weights=weights)


def _saltation_variation(ph: Phase, z_event: float) -> float | None:
    """A bound of ``||S - S*||`` over event states within ``z_event`` (None: the rate may vanish).

    ``S = I + (f^+ - f^-) n^T / (n . f^-)``: ``f^+ - f^-`` moves by ``||A^+ - A^-|| Z_e`` (at
    a friction-band edge by ``||(A^+ - A^-) P|| Z_e``, ``P`` the projector onto the surface,
    which holds both event points: zero to rounding for a continuous law) and ``n . f^-`` by
    ``||n^T A^-|| Z_e`` (see :func:`tube_bound`).
    """
    nv = ph.functions[ph.ending][0]
    n_norm = float(np.linalg.norm(nv))
    u_star = ph.f_plus - ph.f_minus
    p_star = float(nv @ ph.f_minus)
    dp = float(np.linalg.norm(nv @ ph.a)) * z_event
    if abs(p_star) - dp <= 0.0:
        return None
    jump = ph.a_plus - ph.a
    if not (ph.belt_decision or ph.breakaway):
        # a friction-band edge: (f+ - f-)(z) - (f+ - f-)(z*) = (A+ - A-) P (z - z*) (the law
        # is continuous there: A+ - A- is in n's column alone, and (A+ - A-) P vanishes up to
        # rounding)
        jump = jump - np.outer(jump @ nv, nv) / float(nv @ nv)
    du = float(np.linalg.norm(jump)) * z_event
    return n_norm * (du / (abs(p_star) - dp)
                     + float(np.linalg.norm(u_star)) * dp / ((abs(p_star) - dp) * abs(p_star)))


def _phase_timing(ph: Phase, z_dev: float, et: bool, tight: bool,
                  window: list[bool] | None = None) -> tuple[float, float] | None:
    """``(extra, T)`` of a phase of :func:`tube_bound` (None: no bound).

    Band by band ``extra = 0``. At equal times (``et``) past an event at the phase's
    end the growth is bounded over ``T < 1 / ||A||`` first, then over the ``T`` found with it;
    ``window`` carries a tangential departure's open window across band edges (see
    :func:`_end_time_deviation`).
    """
    kappa = extra = 0.0
    past = 0.0 if ph.edge_end else 1.0 / ph.norm_a
    for _ in range(2 if et and past else 1 if et else 0):
        grown = _equal_time_growth(ph, z_dev, past)
        if grown is None:
            return None
        kappa, _, extra = grown
        if past:
            t_found = _end_time_deviation(ph, z_dev, extra, kappa, et, tight,
                                          None if window is None else list(window))
            if t_found is None:
                return None
            past = t_found
    t_dev = _end_time_deviation(ph, z_dev, extra, kappa, et, tight, window)
    return None if t_dev is None else (extra, t_dev)


def _equal_time_floors(ph: Phase, past: float) -> tuple[float, FloatArray, list[Any]]:
    """``(M_bar, h2, floors)`` of :func:`_equal_time_growth`: what depends on the phase and the
    window ``past`` only (no radius), formed once per phase and window and kept in its cache."""
    key = ("equal-time floors", past)
    if key not in ph.cache:
        m_norm = ph.m_two if ph.m_two is not None else ph.m_norm
        grow = np.exp(ph.norm_a * ph.hs)
        m_bar = float(np.max(np.maximum(m_norm[:-1], m_norm[1:]) * grow))
        f_int = np.maximum(ph.flow_norm[:-1], ph.flow_norm[1:]) * grow
        h2 = f_int * ph.hs ** 2 / 8.0
        if past:
            m_bar = max(m_bar, float(m_norm[-1]) * math.exp(ph.norm_a * past))
        floors = []
        for e in range(len(ph.functions)):
            if not ph.is_equal_time_edge(e):
                continue
            nv = ph.functions[e][0]
            floors.append((e, float(np.linalg.norm(nv @ ph.a)),
                           interval_floor(ph.rate[:, e], float(np.linalg.norm(nv @ ph.a @ ph.a)) * h2),
                           end_drift(nv, ph.a, ph.f_minus, float(np.linalg.norm(ph.f_minus)),
                                     ph.norm_a, past)))
        ph.cache[key] = (m_bar, h2, floors)
    return ph.cache[key]


def _equal_time_growth(ph: Phase, z_dev: float, past: float) -> tuple[float, float, float] | None:
    """``(kappa, M_bar, extra)`` of an equal-time slip phase (None: no consistent bound).

    ``M_bar`` bounds ``||expm(A s)||`` over the phase and, past an event at its end, over
    the window ``past >= T`` (``1 / ||A||``, the most the end-time check of
    :func:`_end_time_deviation` allows, or a ``T`` it found with a larger
    ``extra``); ``extra = M_bar Z (exp(M_bar kappa tau) - 1)`` is the deviation's part beyond
    ``M(s) Z``, ``tau`` the time the nominal speed spends within the speed deviation of a
    band edge (see :func:`~stickslip.analysis._band_variation.band_growth`).

    Parameters
    ----------
    ph : Phase
        The nominal slip phase (its ``bands`` set).
    z_dev : float
        ``Z``: the deviation bound at its start.
    past : float
        The window past its end (0 when it ends at a band edge).

    Returns
    -------
    (float, float, float) or None
    """
    assert ph.bands is not None
    m_bar, h2, floors = _equal_time_floors(ph, past)

    def exposure(d: float) -> float:
        tau = 0.0
        for e, na_norm, rho, drift in floors:
            near = ~clear_of_zero(ph.g[:, e], na_norm * h2, np.full(h2.size, d))
            crossing = ph.hs.copy()
            rising = rho > 0.0  # at least rho: within d of the edge for at most 2 d / rho
            with np.errstate(over="ignore"):  # a vanishing rate: the whole interval
                crossing[rising] = np.minimum(ph.hs[rising], 2.0 * d / rho[rising])
            tau += float(np.sum(crossing[near]))
            if past and abs(float(ph.g[-1, e])) <= d + drift:
                tau += past  # the window past an event at the end
        return tau

    grown = band_growth(ph.bands, ph.kind, ph.band, z_dev, m_bar, exposure)
    if grown is None:
        return None
    kappa, growth = grown
    return kappa, m_bar, m_bar * z_dev * (growth - 1.0)
