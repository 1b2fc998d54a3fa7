"""The smooth stiff engine's system: right-hand side, Jacobian and its derivative, arrays only.

The state of the dynamic form is ``y = (q, q', s)`` with ``y' = A y + b F(v, s) + e_s G(v, s)``
and the slip speed ``v = V - q_c'`` (see :mod:`stickslip.kernel.stiff`). Callers see this
*state form*. The integrator works in the *slip form* ``w``: ``y`` with its component ``q_c'``
replaced by the slip speed ``v`` itself, ``w = D y + V e_c'`` with ``D`` the identity but for
``-1`` at ``q_c'``. The two carry the same information, but a slip speed far below the
round-off of ``V`` (rate-and-state friction holds a slider that has healed for a while at slip
speeds of ``1e-26`` m/s and less; its slope ``dF/dv = N a exp(psi/a) / (2 v_ref)`` is then
``1e26`` N s/m) has no representation as ``V - q_c'``: in the state form such a slider cannot
move off ``q_c' = V``. In the slip form ``f_w = D f(y)``, ``J_w = D J D`` and
``(dJ_w/dw . u) Phi_w = D (dJ/dy . D u) D Phi_w``; ``D`` being its own inverse, one function
(:func:`swap_slip_form`) converts either way, ``Phi`` included (``Phi_w = D Phi``). The
quasi-static slider (``y = (x, psi)``) has no velocity of its own and has one form.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)
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
    law_values,
    quasi_static_speed,
)

#: System kinds.
KIND_DYNAMIC = 0
KIND_QUASI_STATIC = 1


@njit(cache=True, error_model="numpy")
def contact_speed(kind: int, law: int, p: np.ndarray, kq: float, iv: int, y: np.ndarray,
                  speed: float) -> float:
    """The contact's velocity ``q_c'`` (m/s, ground frame) in the state form: the section function."""
    if kind == KIND_QUASI_STATIC:
        v, _, _ = quasi_static_speed(p, kq, y[0], y[1])
        return speed - v
    return y[iv]


@njit(cache=True, error_model="numpy")
def slip_speed(kind: int, p: np.ndarray, kq: float, iv: int, w: np.ndarray) -> float:
    """The slip speed ``v = V - q_c'`` (m/s) in the slip form, to full relative precision."""
    if kind == KIND_QUASI_STATIC:
        v, _, _ = quasi_static_speed(p, kq, w[0], w[1])
        return v
    return w[iv]


@njit(cache=True, error_model="numpy")
def swap_slip_form(z: np.ndarray, n: int, iv: int, speed: float) -> None:
    """Convert ``z = (y, vec Phi)`` (or ``y`` alone) between the state and the slip form, in place.

    ``q_c' <-> V - q_c'`` and the row ``q_c'`` of ``Phi`` changes sign; the map is an involution.
    """
    z[iv] = speed - z[iv]
    if z.shape[0] > n:
        for j in range(n):
            z[n + iv * n + j] = -z[n + iv * n + j]


@njit(cache=True, inline="always", error_model="numpy")
def system_rhs(kind: int, law: int, p: np.ndarray, amat: np.ndarray, bvec: np.ndarray, iv: int,
               is_: int, kq: float, y: np.ndarray, speed: float, slip_form: bool,
               lv: np.ndarray, f: np.ndarray) -> None:
    """``f = y'`` (state form) or ``w'`` (slip form) for drive speed ``speed`` (m/s)."""
    n = y.shape[0]
    if kind == KIND_QUASI_STATIC:
        v, _, _ = quasi_static_speed(p, kq, y[0], y[1])
        law_values(law, p, v, y[1], lv)
        f[0] = speed - v
        f[1] = lv[L_G]
        return
    if slip_form:
        v = y[iv]
        qv = speed - y[iv]
    else:
        v = speed - y[iv]
        qv = y[iv]
    law_values(law, p, v, y[is_], lv)
    for i in range(n):
        acc = 0.0
        for j in range(n):
            acc += amat[i, j] * (qv if j == iv else y[j])
        f[i] = acc + bvec[i] * lv[L_F]
    f[is_] = lv[L_G]
    if slip_form:
        f[iv] = -f[iv]


@njit(cache=True, error_model="numpy")
def rhs(kind: int, law: int, p: np.ndarray, amat: np.ndarray, bvec: np.ndarray, iv: int,
        is_: int, kq: float, y: np.ndarray, speed: float, lv: np.ndarray, f: np.ndarray) -> None:
    """``f = y'`` at ``y`` (state form) for drive speed ``speed`` (m/s); ``lv`` receives the law's values."""
    system_rhs(kind, law, p, amat, bvec, iv, is_, kq, y, speed, False, lv, f)


@njit(cache=True, inline="always", error_model="numpy")
def system_jacobian(kind: int, law: int, p: np.ndarray, amat: np.ndarray, bvec: np.ndarray,
                    iv: int, is_: int, kq: float, y: np.ndarray, speed: float, slip_form: bool,
                    lv: np.ndarray, jac: np.ndarray) -> None:
    """The exact Jacobian ``df/dy`` (state form) or ``D (df/dy) D`` (slip form)."""
    n = y.shape[0]
    if kind == KIND_QUASI_STATIC:
        v, vx, vp = quasi_static_speed(p, kq, y[0], y[1])
        law_values(law, p, v, y[1], lv)
        jac[0, 0] = -vx
        jac[0, 1] = -vp
        jac[1, 0] = lv[L_GV] * vx
        jac[1, 1] = lv[L_GV] * vp + lv[L_GS]
        return
    v = y[iv] if slip_form else speed - y[iv]
    law_values(law, p, v, y[is_], lv)
    for i in range(n):
        for j in range(n):
            jac[i, j] = amat[i, j]
    for i in range(n):
        jac[i, iv] -= bvec[i] * lv[L_FV]
        jac[i, is_] += bvec[i] * lv[L_FS]
    jac[is_, iv] = -lv[L_GV]
    jac[is_, is_] = lv[L_GS]
    if slip_form:
        for j in range(n):
            jac[iv, j] = -jac[iv, j]
        for i in range(n):
            jac[i, iv] = -jac[i, iv]


@njit(cache=True, error_model="numpy")
def jacobian(kind: int, law: int, p: np.ndarray, amat: np.ndarray, bvec: np.ndarray, iv: int,
             is_: int, kq: float, y: np.ndarray, speed: float, lv: np.ndarray,
             jac: np.ndarray) -> None:
    """The exact Jacobian ``df/dy`` at ``y`` (state form)."""
    system_jacobian(kind, law, p, amat, bvec, iv, is_, kq, y, speed, False, lv, jac)


@njit(cache=True, inline="always", error_model="numpy")
def system_jacobian_derivative_times(kind: int, law: int, p: np.ndarray, amat: np.ndarray,
                                     bvec: np.ndarray, iv: int, is_: int, kq: float,
                                     y: np.ndarray, speed: float, slip_form: bool, u: np.ndarray,
                                     phi: np.ndarray, lv: np.ndarray, out: np.ndarray) -> None:
    """``out = (dJ/dy . u) Phi`` in either form: the lower-left block of the augmented Jacobian."""
    n = y.shape[0]
    if kind == KIND_QUASI_STATIC:
        scale = 0.0
        for i in range(n):
            scale = max(scale, abs(u[i]) / (1.0 + abs(y[i])))
        if scale == 0.0:
            out[:, :] = 0.0
            return
        eps = 1e-6 / scale
        yp = y + eps * u
        ym = y - eps * u
        jp = np.empty((n, n))
        jm = np.empty((n, n))
        jacobian(kind, law, p, amat, bvec, iv, is_, kq, yp, speed, lv, jp)
        jacobian(kind, law, p, amat, bvec, iv, is_, kq, ym, speed, lv, jm)
        d = (jp - jm) / (2.0 * eps)
        for i in range(n):
            for j in range(n):
                acc = 0.0
                for k in range(n):
                    acc += d[i, k] * phi[k, j]
                out[i, j] = acc
        return
    # the state form's -u[iv] and -phi[iv, j] are the slip form's +u[iv] and +phi[iv, j]
    sgn = 1.0 if slip_form else -1.0
    v = y[iv] if slip_form else speed - y[iv]
    law_values(law, p, v, y[is_], lv)
    dv = sgn * u[iv]
    ds = u[is_]
    af = lv[L_FVV] * dv + lv[L_FVS] * ds
    bf = lv[L_FVS] * dv + lv[L_FSS] * ds
    ag = lv[L_GVV] * dv + lv[L_GVS] * ds
    bg = lv[L_GVS] * dv + lv[L_GSS] * ds
    for j in range(n):
        rf = sgn * af * phi[iv, j] + bf * phi[is_, j]
        rg = sgn * ag * phi[iv, j] + bg * phi[is_, j]
        for i in range(n):
            out[i, j] = bvec[i] * rf
        out[is_, j] = rg
        if slip_form:
            out[iv, j] = -out[iv, j]


@njit(cache=True, error_model="numpy")
def jacobian_derivative_times(kind: int, law: int, p: np.ndarray, amat: np.ndarray,
                              bvec: np.ndarray, iv: int, is_: int, kq: float, y: np.ndarray,
                              speed: float, u: np.ndarray, phi: np.ndarray, lv: np.ndarray,
                              out: np.ndarray) -> None:
    """``out = (dJ/dy . u) Phi`` (state form)."""
    system_jacobian_derivative_times(kind, law, p, amat, bvec, iv, is_, kq, y, speed, False, u,
                                     phi, lv, out)
