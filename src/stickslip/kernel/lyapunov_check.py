"""The steady-sliding check of a run: quadratic Lyapunov bounds on the slider's velocity.

:func:`~stickslip.kernel.system.prepare_bands` gives the functions (the energy, and the
equilibrium band's ``a' P + P a = -I``) with the slip-I bands where each holds and the margin
its bound must stay below; the run loop (:mod:`stickslip.kernel.engine`) evaluates them in
slip-I. Arrays in, arrays out; inlined into the run loop, which calls them on every step of
the equilibrium's bands (a call with seven array arguments cost fourteen atomic reference
counts, :mod:`stickslip.kernel._leaf`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)


@njit(cache=True, inline="always")
def lyapunov_applies(band, lyap_lo, lyap_hi, n_lyap):
    """True when some Lyapunov function holds in slip-I of ``band``."""
    for p in range(n_lyap):
        if lyap_lo[p] <= band <= lyap_hi[p]:
            return True
    return False


@njit(cache=True, inline="always")
def lyapunov_bound(w, z_eq, lyap, kappa, n_lyap, band, lyap_lo, lyap_hi, margin):
    """Smallest bound on ``sup |v_0|`` over the future, and whether one certifies steady sliding.

    Each Lyapunov function ``p`` valid in slip-I of ``band`` gives ``|v_0| <= bound_p`` for
    as long as the motion stays in its bands; ``bound_p < margin[p]`` proves that it does, for
    ever. The functions are centred at the steady-sliding equilibrium ``z_eq`` (the origin
    for the Coulomb law, where ``w - z_eq`` is ``w`` exactly).
    """
    nz = lyap.shape[1]
    best = np.inf
    certified = False
    for p in range(n_lyap):
        if band < lyap_lo[p] or band > lyap_hi[p]:
            continue
        acc = 0.0
        for i in range(nz):
            row = 0.0
            for j in range(nz):
                row += lyap[p, i, j] * (w[j] - z_eq[j])
            acc += (w[i] - z_eq[i]) * row
        bound = np.sqrt(max(acc, 0.0) * kappa[p])
        best = min(best, bound)
        if bound < margin[p]:
            certified = True
    return best, certified
