"""The LuGre friction force along an imposed velocity history (arrays only).

For a prescribed sliding velocity ``v(t)`` the bristle deflection obeys the scalar linear ODE
``z' = v - a(v) z`` with ``a(v) = sigma0 |v| / g(v)``, ``g(v) = F_c + (F_s - F_c) exp(-(v/v_s)^2)``
(Canudas de Wit et al. 1995). Holding ``v`` at the interval's mean ``(v_i + v_{i+1}) / 2``
(second order in the sample interval), the interval is solved exactly:
``z_{i+1} = z_ss + (z_i - z_ss) exp(-a h)``, ``z_ss = g sign(v) / sigma0`` (``z`` constant
where ``v = 0``), stable for any stiffness ``sigma0``. The force at each sample is
``F = sigma0 z + sigma1 z' + sigma2 v`` with ``z' = v - a(v) z`` at the sample's own velocity.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)


@njit(cache=True)
def _rate(v, sigma0, f_c, f_s, v_s):
    """``a(v) = sigma0 |v| / g(v)``."""
    g = f_c + (f_s - f_c) * np.exp(-(v / v_s) ** 2)
    return sigma0 * abs(v) / g, g


@njit(cache=True)
def lugre_force(t, v, sigma0, sigma1, sigma2, f_c, f_s, v_s, z0):
    """Friction force (N) at the samples ``t`` (s) of the velocity history ``v`` (m/s).

    ``z0`` is the bristle deflection (m) at ``t[0]``. Returns the force array and the final
    deflection.
    """
    n = t.shape[0]
    force = np.empty(n)
    z = z0
    for i in range(n):
        a_i, _ = _rate(v[i], sigma0, f_c, f_s, v_s)
        force[i] = sigma0 * z + sigma1 * (v[i] - a_i * z) + sigma2 * v[i]
        if i + 1 < n:
            vm = 0.5 * (v[i] + v[i + 1])
            if vm != 0.0:
                a_m, g_m = _rate(vm, sigma0, f_c, f_s, v_s)
                z_ss = g_m * np.sign(vm) / sigma0
                z = z_ss + (z - z_ss) * np.exp(-a_m * (t[i + 1] - t[i]))
    return force, z
