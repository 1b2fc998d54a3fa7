"""The friction laws with memory in the stiff engine: values and first and second partials.

Rate-and-state in the regularised form and LuGre (:mod:`stickslip.model.state_friction` states
the laws); the quasi-static slider's slip speed. Compiled, chosen by an integer code, so that
no Python callback runs in the engine's loop (:mod:`stickslip.kernel.stiff`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)

#: Law codes (as :mod:`stickslip.model.state_friction`).
LAW_RATE_STATE_AGING = 0
LAW_RATE_STATE_SLIP = 1
LAW_LUGRE = 2

#: Entries of the law's value array.
N_LAW = 12
(L_F, L_G, L_FV, L_FS, L_GV, L_GS, L_FVV, L_FVS, L_FSS, L_GVV, L_GVS, L_GSS) = range(12)

#: Largest exponent used before asinh's argument is replaced by its logarithm.
_LOG_SWITCH = 30.0


@njit(cache=True)
def force_resolution(law: int, p: np.ndarray) -> float:
    """The friction force (N) the law resolves at any slip speed: ``N a`` (rate-and-state's
    direct effect), ``N mu_c`` (LuGre's Coulomb level); see :func:`slip_speed_scale`."""
    return abs(p[0] * (p[4] if law == LAW_LUGRE else p[1]))


@njit(cache=True)
def slip_speed_scale(rtol: float, force: float, force_slope: float, resolution: float) -> float:
    """Error scale (m/s) of the slip speed that keeps the friction force accurate to ``rtol``.

    An error ``dv`` in the slip speed is an error ``F_v dv`` in the friction force ``F``; the
    force is wanted to ``rtol max(|F|, resolution)``, so ``dv`` to that over ``|F_v|``. Near
    ``v = 0`` rate-and-state's ``F_v = N a / sqrt(v^2 + v_reg^2)`` is enormous (``v_reg = 2
    v_ref exp(-psi/a)``): the scale is then ``rtol sqrt(v^2 + v_reg^2)``, relative control of
    the slip speed, where an absolute tolerance of ``rtol V`` let creep at 1e-14 m/s flip sign
    and the friction with it. ``inf`` when the force does not depend on ``v``.
    """
    if force_slope == 0.0:
        return np.inf
    return rtol * max(abs(force), resolution) / abs(force_slope)


@njit(cache=True, error_model="numpy")
def law_values(law: int, p: np.ndarray, v: float, s: float, out: np.ndarray) -> None:
    """Friction force ``F`` (N), state rate ``G`` and their first and second partials in ``(v, s)``.

    ``p``: rate-and-state ``[N, a, b, d_c, mu_ref, v_ref, 0]``, state ``psi``; LuGre
    ``[N, sigma0, sigma1, sigma2, mu_c, mu_s, v_s]``, state ``z`` (m). ``v``: slip speed, m/s.
    """
    load = p[0]
    sv = 1.0 if v > 0.0 else (-1.0 if v < 0.0 else 0.0)
    av = abs(v)
    if law == LAW_LUGRE:
        s0, s1, s2, mc, ms, vs = p[1], p[2], p[3], p[4], p[5], p[6]
        ex = math.exp(-(v / vs) ** 2)
        g = load * (mc + (ms - mc) * ex)
        g1 = load * (ms - mc) * ex * (-2.0 * v / (vs * vs))
        g2 = load * (ms - mc) * ex * (4.0 * v * v / vs**4 - 2.0 / (vs * vs))
        hh = av / g
        h1 = sv / g - av * g1 / (g * g)
        h2 = -2.0 * sv * g1 / (g * g) - av * g2 / (g * g) + 2.0 * av * g1 * g1 / (g * g * g)
        G = v - s0 * s * hh
        Gv = 1.0 - s0 * s * h1
        Gs = -s0 * hh
        Gvv = -s0 * s * h2
        Gvs = -s0 * h1
        out[L_F] = s0 * s + s1 * G + s2 * v
        out[L_G] = G
        out[L_FV] = s1 * Gv + s2
        out[L_FS] = s0 + s1 * Gs
        out[L_GV] = Gv
        out[L_GS] = Gs
        out[L_FVV] = s1 * Gvv
        out[L_FVS] = s1 * Gvs
        out[L_FSS] = 0.0
        out[L_GVV] = Gvv
        out[L_GVS] = Gvs
        out[L_GSS] = 0.0
        return
    a, b, dc, mu0, vref = p[1], p[2], p[3], p[4], p[5]
    # F = N a asinh(X), X = v E, E = exp(psi/a) / (2 v_ref); r = 1 / sqrt(1 + X^2)
    le = s / a - math.log(2.0 * vref)
    if av > 0.0 and le + math.log(av) > _LOG_SWITCH:
        lx = le + math.log(av)
        # X huge: asinh(X) = ln(2X) + 1/(4 X^2) ..., r = 1/X (1 - ...), to round-off
        out[L_F] = sv * load * a * (lx + math.log(2.0))
        out[L_FV] = load * a / av
        out[L_FS] = sv * load
        out[L_FVV] = -sv * (load * a / av) / av  # av * av may underflow to 0; this may be inf
        out[L_FVS] = 0.0
        out[L_FSS] = 0.0
    else:
        e = math.exp(le)
        x = v * e
        r = 1.0 / math.sqrt(1.0 + x * x)
        out[L_F] = load * a * math.asinh(x)
        out[L_FV] = load * a * r * e
        out[L_FS] = load * r * x
        out[L_FVV] = -load * a * x * r * r * r * e * e
        out[L_FVS] = load * e * r * r * r
        out[L_FSS] = load * x * r * r * r / a
    if law == LAW_RATE_STATE_AGING:
        w = vref * math.exp((mu0 - s) / b) if b > 0.0 else vref
        out[L_G] = (b / dc) * (w - av) if b > 0.0 else 0.0
        out[L_GV] = -(b / dc) * sv
        out[L_GS] = -w / dc if b > 0.0 else 0.0
        out[L_GVV] = 0.0
        out[L_GVS] = 0.0
        out[L_GSS] = w / (b * dc) if b > 0.0 else 0.0
    else:
        if av > 0.0:
            lg = b * math.log(av / vref) + s - mu0
            out[L_G] = -(av / dc) * lg
            out[L_GV] = -(sv / dc) * (lg + b)
            out[L_GVV] = -(b / dc) / av
        else:
            out[L_G] = 0.0
            out[L_GV] = 0.0
            out[L_GVV] = 0.0
        out[L_GS] = -av / dc
        out[L_GVS] = -sv / dc
        out[L_GSS] = 0.0


@njit(cache=True, error_model="numpy")
def quasi_static_speed(p: np.ndarray, kq: float, x: float, psi: float) -> tuple[float, float, float]:
    """Slip speed of the quasi-static slider and its partials: ``v``, ``dv/dx``, ``dv/dpsi``.

    ``k x = N a asinh(v exp(psi/a) / (2 v_ref))`` gives ``v = 2 v_ref exp(-psi/a) sinh(k x / (N a))``.
    """
    load, a, vref = p[0], p[1], p[5]
    arg = kq * x / (load * a)
    c = 2.0 * vref * math.exp(-psi / a)
    v = c * math.sinh(arg)
    return v, c * math.cosh(arg) * kq / (load * a), -v / a
