"""The smooth stiff engine: a Rosenbrock method (RODAS4) for friction with memory, arrays only.

Friction laws with an internal state (rate-and-state, LuGre; :mod:`stickslip.model.state_friction`)
have no true stick and are stiff (LuGre's bristle stiffness, the state's fast relaxation at
high slip speed), so the exact piecewise-linear engine does not apply. This module integrates

    M q'' + C q' + K q = e_c F(v, s),   s' = G(v, s),   v = V - q_c'

(dynamic, any linear structure, contact on DOF ``c``) written as ``y' = A y + b F + e_s G``
with ``y = (q, q', s)``, or the quasi-static slider of rate-and-state (``m = 0``):
``k x = F(v, psi)`` solved for the slip speed ``v = 2 v_ref exp(-psi/a) sinh(k x / (N a))``,
``y = (x, psi)``, ``x' = V - v``. ``V`` is constant on each call (a schedule of drive speeds is
a sequence of calls). Inside a call the dynamic state is carried in the *slip form*, ``q_c'``
replaced by ``v`` itself, so that creep far below the round-off of ``V`` is resolved; the
right-hand side, Jacobian and their transformation are in :mod:`stickslip.kernel.stiff_system`.

The method is RODAS4 of Hairer and Wanner (Solving Ordinary Differential Equations II, 2nd ed.,
Springer 1996, Sec. IV.7; the coefficients of their code ``rodas.f``): six stages, order 4, an
embedded order-3 solution for the error estimate, L-stable and stiffly accurate, and a dense
output of order 3 between the step's ends. The Jacobian is the exact analytic one of the laws,
so the order is that of the method (a Rosenbrock method needs the exact Jacobian). Steps are
controlled on the error in the mixed norm ``rms(err_i / (atol_i + rtol |y_i|)) <= 1`` (with the
variational equations, optionally over ``Phi`` too).

The variational equations ``Phi' = J(y) Phi`` (``Phi(0) = I``) are integrated with ``y`` as one
augmented system by the same method, with the augmented system's exact Jacobian (its
lower-left block ``(dJ/dy . u) Phi`` holds the laws' second derivatives; for the quasi-static
slider a central difference of the analytic ``J`` with relative step ``1e-6``). ``Phi`` at a
return to the Poincare section gives the Floquet multipliers and the Newton step of shooting.

Events are located on the dense output: the section ``q_c' = 0`` crossed upwards (each period
of a periodic motion crosses it once or more, its mean velocity being zero) and the slip
reversals ``q_c' = V``, sampled at :data:`EVENT_SAMPLES` points inside each step and bisected to
round-off. Quasi-stick (the slip speed below a fraction of ``V``) is judged by the caller on
the dense output. No Python callback
runs in the loop: the laws are compiled here, chosen by an integer code. The engine is compiled
with numpy's error model: a division by zero or an overflow (a state healed far beyond its
steady value) gives inf or nan, which the step's finiteness check rejects (the step shrinks),
never an exception.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)
from stickslip.kernel import stiff_tableau as rodas
from stickslip.kernel.stiff_laws import (
    L_F,
    L_FS,
    L_FSS,
    L_FV,
    L_FVS,
    L_FVV,
    L_G,
    L_GS,
    L_GSS,
    L_GV,
    L_GVS,
    L_GVV,
    LAW_LUGRE,
    LAW_RATE_STATE_AGING,
    LAW_RATE_STATE_SLIP,
    N_LAW,
    force_resolution,
    law_values,
    quasi_static_speed,
    slip_speed_scale,
)
from stickslip.kernel.stiff_system import (
    KIND_DYNAMIC,
    KIND_QUASI_STATIC,
    contact_speed,
    jacobian,
    jacobian_derivative_times,
    rhs,
    slip_speed,
    swap_slip_form,
    system_jacobian,
    system_jacobian_derivative_times,
    system_rhs,
)

#: Run statuses.
STATUS_DONE = 0
STATUS_SECTION = 1
STATUS_MAX_STEPS = 2
STATUS_STEP_UNDERFLOW = 3

#: Points of the dense output tested for a section crossing inside each step.
EVENT_SAMPLES = 4
#: Bisection steps of an event time (halves the bracket to below 1e-15 of the step).
EVENT_BISECTIONS = 60

#: Step-size controller: safety factor and the bounds of one change (Hairer & Wanner's).
SAFETY = 0.9
FAC_MIN = 0.2
FAC_MAX = 6.0

@njit(cache=True, inline="always", error_model="numpy")
def lu_factor(a: np.ndarray, piv: np.ndarray) -> bool:
    """In-place LU with partial pivoting; False when singular."""
    n = a.shape[0]
    for k in range(n):
        m = k
        big = abs(a[k, k])
        for i in range(k + 1, n):
            if abs(a[i, k]) > big:
                big = abs(a[i, k])
                m = i
        piv[k] = m
        if big == 0.0:
            return False
        if m != k:
            for j in range(n):
                t = a[k, j]
                a[k, j] = a[m, j]
                a[m, j] = t
        inv = 1.0 / a[k, k]
        for i in range(k + 1, n):
            a[i, k] *= inv
            lik = a[i, k]
            if lik != 0.0:
                for j in range(k + 1, n):
                    a[i, j] -= lik * a[k, j]
    return True


@njit(cache=True, inline="always", error_model="numpy")
def lu_solve(lu: np.ndarray, piv: np.ndarray, b: np.ndarray) -> None:
    """Solve in place with the factors of :func:`lu_factor`."""
    n = lu.shape[0]
    for k in range(n):
        m = piv[k]
        if m != k:
            t = b[k]
            b[k] = b[m]
            b[m] = t
    for i in range(n):
        acc = b[i]
        for j in range(i):
            acc -= lu[i, j] * b[j]
        b[i] = acc
    for i in range(n - 1, -1, -1):
        acc = b[i]
        for j in range(i + 1, n):
            acc -= lu[i, j] * b[j]
        b[i] = acc / lu[i, i]


@njit(cache=True, inline="always", error_model="numpy")
def _aug_rhs(kind: int, law: int, p: np.ndarray, amat: np.ndarray, bvec: np.ndarray, iv: int,
             is_: int, kq: float, z: np.ndarray, n: int, with_phi: bool, speed: float,
             lv: np.ndarray, jw: np.ndarray, out: np.ndarray) -> None:
    """Right-hand side of the augmented system ``z = (y, vec Phi)``: ``(f(y), J(y) Phi)``."""
    y = z[:n]
    f = out[:n]
    system_rhs(kind, law, p, amat, bvec, iv, is_, kq, y, speed, True, lv, f)
    if with_phi:
        system_jacobian(kind, law, p, amat, bvec, iv, is_, kq, y, speed, True, lv, jw)
        phi = z[n:].reshape((n, n))
        dphi = out[n:].reshape((n, n))
        for i in range(n):
            for j in range(n):
                acc = 0.0
                for k in range(n):
                    acc += jw[i, k] * phi[k, j]
                dphi[i, j] = acc


@njit(cache=True, inline="always", error_model="numpy")
def _stage_solve(kind: int, law: int, p: np.ndarray, amat: np.ndarray, bvec: np.ndarray, iv: int,
                 is_: int, kq: float, z0: np.ndarray, n: int, with_phi: bool, speed: float,
                 lu: np.ndarray, piv: np.ndarray, lv: np.ndarray, hw: np.ndarray,
                 r: np.ndarray) -> None:
    """Solve ``(I/(gamma h) - J_aug) K = r`` in place (block lower-triangular ``J_aug``)."""
    ry = r[:n]
    lu_solve(lu, piv, ry)
    if with_phi:
        system_jacobian_derivative_times(kind, law, p, amat, bvec, iv, is_, kq, z0[:n], speed,
                                         True, ry, z0[n:].reshape((n, n)), lv, hw)
        rphi = r[n:].reshape((n, n))
        col = np.empty(n)
        for j in range(n):
            for i in range(n):
                col[i] = rphi[i, j] + hw[i, j]
            lu_solve(lu, piv, col)
            for i in range(n):
                rphi[i, j] = col[i]


@njit(cache=True, error_model="numpy")
def dense_value(z0: np.ndarray, z1: np.ndarray, c3: np.ndarray, c4: np.ndarray, theta: float,
                out: np.ndarray) -> None:
    """RODAS4's dense output at ``theta`` in [0, 1] of the step: order 3 (Hairer & Wanner)."""
    s1 = 1.0 - theta
    for i in range(z0.shape[0]):
        out[i] = z0[i] * s1 + theta * (z1[i] + s1 * (c3[i] + theta * c4[i]))


@njit(cache=True, error_model="numpy")
def integrate(kind: int, law: int, p: np.ndarray, amat: np.ndarray, bvec: np.ndarray, iv: int,
              is_: int, kq: float, z: np.ndarray, n: int, with_phi: bool, t0: float, t1: float,
              speed: float, rtol: float, atol: np.ndarray, phi_rtol: float, h_start: float,
              max_steps: int,
              t_out: np.ndarray, z_out: np.ndarray, stop_at_section: bool, section_after: float,
              cross_t: np.ndarray, cross_z: np.ndarray, reversal_t: np.ndarray,
              stats: np.ndarray) -> tuple[int, float, float]:
    """Integrate ``z = (y, vec Phi)`` from ``t0`` towards ``t1`` (s) at drive speed ``speed``.

    Parameters
    ----------
    kind, law, p, amat, bvec, iv, is_, kq
        The system (see the module docstring): ``amat`` (n x n) and ``bvec`` (n) of the dynamic
        form, ``iv`` the index of ``q_c'``, ``is_`` that of the state; ``kq`` the stiffness of
        the quasi-static slider (N/m).
    z : ndarray
        Initial augmented state (length ``n`` or ``n + n*n``), overwritten with the final one.
    n : int
        Length of ``y``.
    with_phi : bool
        Integrate the variational equations too.
    t0, t1 : float
        Start and end time, s.
    speed : float
        Drive speed ``V``, m/s (constant on this call).
    rtol : float
        Relative tolerance.
    atol : ndarray
        Absolute tolerance per component of ``y``.
    phi_rtol : float
        With ``with_phi``: relative tolerance on ``Phi`` in the error norm (``Phi_ij`` with
        the absolute tolerance ``phi_rtol atol_i / atol_j``); 0 leaves ``Phi`` out of it.
    h_start : float
        First step to try (s); 0 chooses one.
    max_steps : int
        Bound on attempted steps.
    t_out : ndarray
        Increasing times (s) at which ``z_out`` rows are filled from the dense output (those
        in ``[t0, t1]``; the others are left untouched).
    z_out : ndarray
        ``len(t_out)`` rows.
    stop_at_section : bool
        Stop at the first upward crossing of ``q_c' = 0`` after ``section_after``.
    section_after : float
        See above, s.
    cross_t, cross_z : ndarray
        Ring buffers for the times and states ``y`` of upward section crossings: crossing
        ``i`` (from 0) is written to row ``i mod len(cross_t)``, so the last ``len(cross_t)``
        are kept (:func:`ring_order` gives their order); ``stats[3]`` counts them all.
    reversal_t : ndarray
        Buffer for the times of slip reversals (the slip speed ``V - q_c'`` changes sign,
        located like the crossings; the first ``len(reversal_t)`` are kept).
    stats : ndarray
        Out: ``[accepted, rejected, last step h, crossings, min q_c', max q_c', reversals]``
        (the caller sets ``stats[4] = inf``, ``stats[5] = -inf``, the rest 0).

    Returns
    -------
    (status, t, h)
        :data:`STATUS_DONE`, :data:`STATUS_SECTION` (stopped at a crossing; ``t`` its time),
        :data:`STATUS_MAX_STEPS` or :data:`STATUS_STEP_UNDERFLOW`; the time reached and the
        next step to try.

    Notes
    -----
    The dynamic form is integrated in the slip form (:mod:`stickslip.kernel.stiff_system`):
    ``z``, ``z_out`` and ``cross_z`` are converted on the way in and out, so callers see the
    state form; the slip speed keeps full relative precision inside the call.

    The work is done by :func:`_integrate_slip_form` (its docstring says why it is long).
    """
    slip = kind == KIND_DYNAMIC
    if slip:
        swap_slip_form(z, n, iv, speed)
    status, t, h = _integrate_slip_form(kind, law, p, amat, bvec, iv, is_, kq, z, n, with_phi, t0,
                                        t1, speed, rtol, atol, phi_rtol, h_start, max_steps,
                                        t_out, z_out, stop_at_section, section_after, cross_t,
                                        cross_z, reversal_t, stats)
    if slip:
        swap_slip_form(z, n, iv, speed)
    return status, t, h


@njit(cache=True, error_model="numpy")
def _integrate_slip_form(kind: int, law: int, p: np.ndarray, amat: np.ndarray, bvec: np.ndarray, iv: int,
                         is_: int, kq: float, z: np.ndarray, n: int, with_phi: bool, t0: float, t1: float,
                         speed: float, rtol: float, atol: np.ndarray, phi_rtol: float, h_start: float,
                         max_steps: int,
                         t_out: np.ndarray, z_out: np.ndarray, stop_at_section: bool, section_after: float,
                         cross_t: np.ndarray, cross_z: np.ndarray, reversal_t: np.ndarray,
                         stats: np.ndarray) -> tuple[int, float, float]:
    """:func:`integrate` on ``z`` in the slip form (dynamic) or the quasi-static form.

    Why this function is longer than the house's 120 lines: the stages of RODAS4, its dense
    output, the section and reversal search and the step-size controller share the stage
    vectors of one step; split into compiled helpers they would pass a dozen arrays per call.
    """
    nz = z.shape[0]
    lv = np.empty(N_LAW)
    jac = np.empty((n, n))
    lu = np.empty((n, n))
    piv = np.empty(n, dtype=np.int64)
    jw = np.empty((n, n))
    hw = np.empty((n, n))
    ks = np.empty((rodas.STAGES, nz))
    f0 = np.empty(nz)
    fresh = False
    zt = np.empty(nz)
    dz = np.empty(nz)
    znew = np.empty(nz)
    c3 = np.empty(nz)
    c4 = np.empty(nz)
    zd = np.empty(nz)
    t = t0
    t_local = 0.0  # time since t0: the clock of the step-size floor below
    span = t1 - t0
    if span <= 0.0:
        return STATUS_DONE, t, h_start
    n_out = t_out.shape[0]
    io = 0
    while io < n_out and t_out[io] < t0:
        io += 1
    slip = kind == KIND_DYNAMIC
    while io < n_out and t_out[io] == t0:
        z_out[io, :] = z
        if slip:
            swap_slip_form(z_out[io, :], n, iv, speed)
        io += 1
    n_cross_buf = cross_t.shape[0]
    slip_prev = slip_speed(kind, p, kq, iv, z[:n])
    sec_prev = speed - slip_prev
    h = h_start
    if h <= 0.0:
        _aug_rhs(kind, law, p, amat, bvec, iv, is_, kq, z, n, False, speed, lv, jw, dz)
        d0 = 0.0
        d1 = 0.0
        for i in range(n):
            sc = atol[i] + rtol * abs(speed - z[i] if slip and i == iv else z[i])
            d0 += (z[i] / sc) ** 2
            d1 += (dz[i] / sc) ** 2
        d0 = math.sqrt(d0 / n)
        d1 = math.sqrt(d1 / n)
        h = 0.01 * d0 / d1 if d0 > 1e-5 and d1 > 1e-5 else 1e-6 * span
        h = min(max(h, 1e-12 * span), span)
    err_old = 1.0
    h_old = h
    f_resolution = force_resolution(law, p)
    v_scale = np.inf
    first = True
    tc = t
    for _attempt in range(max_steps):
        if t + h >= t1 or (t1 - (t + h)) < 1e-12 * span:
            h = t1 - t
        if not fresh:  # the Jacobian and f at z are kept through rejected attempts
            system_jacobian(kind, law, p, amat, bvec, iv, is_, kq, z[:n], speed, True, lv, jac)
            _aug_rhs(kind, law, p, amat, bvec, iv, is_, kq, z, n, with_phi, speed, lv, jw, f0)
            fresh = True
            if slip:  # the slip speed as accurate as the friction force it sets
                v_scale = slip_speed_scale(rtol, lv[L_F], lv[L_FV], f_resolution)
        for i in range(n):
            for j in range(n):
                lu[i, j] = -jac[i, j]
            lu[i, i] += 1.0 / (rodas.GAM * h)
        if not lu_factor(lu, piv):
            h *= 0.5
            continue
        for st in range(rodas.STAGES):
            for i in range(nz):
                acc = z[i]
                for jk in range(st):
                    acc += rodas.A_STAGE[st, jk] * ks[jk, i]
                zt[i] = acc
            if st == 0:
                for i in range(nz):
                    dz[i] = f0[i]
            else:
                _aug_rhs(kind, law, p, amat, bvec, iv, is_, kq, zt, n, with_phi, speed, lv, jw, dz)
            for i in range(nz):
                acc = 0.0
                for jk in range(st):
                    acc += rodas.C_STAGE[st, jk] * ks[jk, i]
                ks[st, i] = dz[i] + acc / h
            _stage_solve(kind, law, p, amat, bvec, iv, is_, kq, z, n, with_phi, speed, lu, piv, lv,
                         hw, ks[st])
        k6 = ks[rodas.STAGES - 1]
        err = 0.0
        finite = True
        for i in range(nz):
            znew[i] = zt[i] + k6[i]
            if not math.isfinite(znew[i]):
                finite = False
        if finite:
            for i in range(n):
                if slip and i == iv:  # the state form's scale, |q_c'|, or the force's
                    sc = min(atol[i] + rtol * max(abs(speed - z[i]), abs(speed - znew[i])),
                             v_scale)
                else:
                    sc = atol[i] + rtol * max(abs(z[i]), abs(znew[i]))
                err += (k6[i] / sc) ** 2
            count = n
            if with_phi and phi_rtol > 0.0:
                # Phi[i, j] has the units of y_i / y_j: its absolute tolerance is phi_rtol atol_i / atol_j
                for i in range(n):
                    for j in range(n):
                        ij = n + i * n + j
                        sc = phi_rtol * (atol[i] / atol[j] + max(abs(z[ij]), abs(znew[ij])))
                        err += (k6[ij] / sc) ** 2
                count = nz
            err = math.sqrt(err / count)
        else:
            err = 1e10
        if err <= 1.0:
            # accepted: dense output, events, outputs
            for i in range(nz):
                a3 = 0.0
                a4 = 0.0
                for jk in range(rodas.STAGES - 1):
                    a3 += rodas.D2[jk] * ks[jk, i]
                    a4 += rodas.D3[jk] * ks[jk, i]
                c3[i] = a3
                c4[i] = a4
            t_new = t + h
            stop = False
            # section crossings: sample the dense output, bisect the first sign change upwards
            prev_val = sec_prev
            prev_slip = slip_prev
            prev_th = 0.0
            for js in range(1, EVENT_SAMPLES + 2):
                th = js / (EVENT_SAMPLES + 1.0)
                if js == EVENT_SAMPLES + 1:
                    for i in range(nz):
                        zd[i] = znew[i]
                else:
                    dense_value(z, znew, c3, c4, th, zd)
                vs = slip_speed(kind, p, kq, iv, zd[:n])
                val = speed - vs
                if val < stats[4]:
                    stats[4] = val
                if val > stats[5]:
                    stats[5] = val
                if (prev_slip > 0.0) != (vs > 0.0) and prev_slip != 0.0 and vs != 0.0:
                    # slip reversal: the slip speed V - q_c' changes sign (a start at exactly
                    # zero slip is not one)
                    lo = prev_th
                    hi = th
                    below = prev_slip > 0.0
                    for _b in range(EVENT_BISECTIONS):
                        mid = 0.5 * (lo + hi)
                        dense_value(z, znew, c3, c4, mid, zd)
                        if (slip_speed(kind, p, kq, iv, zd[:n]) > 0.0) == below:
                            lo = mid
                        else:
                            hi = mid
                    nr = int(stats[6])
                    if nr < reversal_t.shape[0]:
                        reversal_t[nr] = t + hi * h
                    stats[6] += 1.0
                    if js < EVENT_SAMPLES + 1:
                        dense_value(z, znew, c3, c4, th, zd)
                    else:
                        for i in range(nz):
                            zd[i] = znew[i]
                if prev_val < 0.0 and val >= 0.0:
                    lo = prev_th
                    hi = th
                    for _b in range(EVENT_BISECTIONS):
                        mid = 0.5 * (lo + hi)
                        dense_value(z, znew, c3, c4, mid, zd)
                        if speed - slip_speed(kind, p, kq, iv, zd[:n]) < 0.0:
                            lo = mid
                        else:
                            hi = mid
                    dense_value(z, znew, c3, c4, hi, zd)
                    tc = t + hi * h
                    if n_cross_buf > 0:  # a ring: crossing i at i mod n_cross_buf
                        nc = int(stats[3]) % n_cross_buf
                        cross_t[nc] = tc
                        for i in range(cross_z.shape[1]):
                            cross_z[nc, i] = zd[i]
                        if slip:
                            swap_slip_form(cross_z[nc, :], n, iv, speed)
                    stats[3] += 1.0
                    if stop_at_section and tc > section_after:
                        while io < n_out and t_out[io] <= tc:
                            dense_value(z, znew, c3, c4, (t_out[io] - t) / h, z_out[io, :])
                            if slip:
                                swap_slip_form(z_out[io, :], n, iv, speed)
                            io += 1
                        for i in range(nz):
                            z[i] = zd[i]
                        stats[0] += 1.0
                        stats[2] = h
                        stop = True
                        break
                prev_val = val
                if vs != 0.0:
                    prev_slip = vs
                prev_th = th
            if stop:
                return STATUS_SECTION, tc, h
            while io < n_out and t_out[io] <= t_new:
                dense_value(z, znew, c3, c4, (t_out[io] - t) / h, z_out[io, :])
                if slip:
                    swap_slip_form(z_out[io, :], n, iv, speed)
                io += 1
            sec_prev = prev_val
            slip_prev = prev_slip
            for i in range(nz):
                z[i] = znew[i]
            t = t_new
            t_local += h
            fresh = False
            stats[0] += 1.0
            stats[2] = h
            # predictive controller (Gustafsson), as in Hairer & Wanner's rodas.f
            fac = max(1.0 / FAC_MAX, min(1.0 / FAC_MIN, (err ** 0.25) / SAFETY))
            if not first:
                facgus = (h_old / h) * (err * err / err_old) ** 0.25 / SAFETY
                facgus = max(1.0 / FAC_MAX, min(1.0 / FAC_MIN, facgus))
                fac = max(fac, facgus)
            first = False
            h_old = h
            err_old = max(1e-2, err)
            if t >= t1 or t1 - t <= 1e-12 * span:
                return STATUS_DONE, t1, h / fac
            h = h / fac
        else:
            stats[1] += 1.0
            fac = max(1.0 / FAC_MAX, min(1.0 / FAC_MIN, (err ** 0.25) / SAFETY)) if err < 1e9 else 10.0
            h = h / fac
        # round-off of the clock: a step below 1e-14 of the time since this call's start no
        # longer advances it. At the start there is none: the initial layer of a start at slip
        # speed 0 (rate-and-state's friction rises from 0 to mu N within a few regularisation
        # speeds, 1e-40 m/s and less) is resolved with steps as small as it needs, growing as
        # it decays (max_steps bounds it). The floor counts from t0, not from 0: a schedule's
        # hold that starts at t0 = 20 s begins such a layer too (an independent audit: a 1 kg
        # slider stopped there at "step size fell to round-off"); within one call the drive
        # speed is constant, so the motion does not depend on t itself, and steps below the
        # round-off of t shift the reported times by less than 1e-14 t
        if h < 1e-14 * t_local or h < 1e-300:
            return STATUS_STEP_UNDERFLOW, t, h
    return STATUS_MAX_STEPS, t, h



__all__ = [  # the laws' names are re-exported: one module for the engine's callers
    "KIND_DYNAMIC", "KIND_QUASI_STATIC", "LAW_LUGRE", "LAW_RATE_STATE_AGING", "LAW_RATE_STATE_SLIP",
    "L_F", "L_FS", "L_FSS", "L_FV", "L_FVS", "L_FVV", "L_G", "L_GS", "L_GSS", "L_GV", "L_GVS",
    "L_GVV", "N_LAW", "STATUS_DONE", "STATUS_MAX_STEPS", "STATUS_SECTION", "STATUS_STEP_UNDERFLOW",
    "contact_speed", "dense_value", "integrate", "jacobian", "jacobian_derivative_times",
    "law_values", "lu_factor", "lu_solve", "quasi_static_speed", "rhs",
]


def ring_order(count: int, size: int) -> np.ndarray:
    """Rows of a ring buffer of ``size`` rows in the order they were written, oldest first.

    :func:`integrate` writes section crossing ``i`` (from 0) to row ``i mod size``; after
    ``count`` crossings the buffer holds the last ``min(count, size)`` of them.

    Parameters
    ----------
    count : int
        Crossings written (``stats[3]``).
    size : int
        Rows of the buffer.

    Returns
    -------
    ndarray of int
        Row indices, oldest crossing first.
    """
    if count <= size:
        return np.arange(count)
    return (np.arange(size) + count) % size
