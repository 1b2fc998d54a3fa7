"""Where a smooth law's interpolant and the law itself disagree about steady sliding.

A smooth friction law (Stribeck) runs on the exact engine as its piecewise-linear interpolant,
and every certificate of the engine is the interpolant's. Away from the stability limit of
steady sliding that changes no verdict (the error falls with the tolerance); next to it, the
interpolant's slope at the belt speed (the secant of its band) and the law's (the tangent) can
fall on either side of zero net damping. :func:`interpolant_steady_mismatch` says when a
steady-sliding certificate of the interpolant does not hold for the law.
"""

from __future__ import annotations

import numpy as np

from stickslip.analysis.stability import slip_matrix, steady_sliding_stability
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure


def interpolant_steady_mismatch(structure: Structure, slider: Slider) -> str | None:
    """Why a steady-sliding certificate of a smooth law's interpolant does not hold for the law.

    A smooth law (Stribeck) runs as its piecewise-linear interpolant, and the engine's Lyapunov
    certificate is the interpolant's: its slope at the belt speed is the secant of the band
    that holds ``u = 1``, where the law's own linearisation has the tangent
    (:func:`steady_sliding_stability`). Near the law's stability limit the two can fall on
    either side of it: an independent audit certified steady sliding on the rigid base at
    ``zeta = 0.99 zeta_0`` (``zeta_0`` the zero of the net damping ``2 zeta + F'(1)`` of
    ``stribeck:vs=0.2,n=1``, ``lambda = 2``, tolerance 1e-4) where the law's steady sliding
    grows (3.4e-4 per unit tau) and its true motion reaches the belt speed at tau = 3,233. Such a
    certificate, and the disturbance margin built on it, is withheld.

    Parameters
    ----------
    structure : Structure
        Dimensionless matrices, contact on DOF 0.
    slider : Slider
        ``lambda``, ``gamma`` and the friction law.

    Returns
    -------
    str or None
        The reason, with both growth rates, when the law's steady sliding is not linearly
        stable while its interpolant's is; None for exact laws (Coulomb, linear, tables: the
        engine runs the law itself) and when the two agree.
    """
    law = slider.friction
    if law.exact:
        return None
    exact = steady_sliding_stability(structure, slider)
    if exact.stable:
        return None
    edges, _, slopes = law.bands(slider.lam, slider.gamma)
    b = int(np.searchsorted(edges, 1.0, side="right") - 1)
    sides = [float(slopes[b])] + ([float(slopes[b - 1])] if b > 0 and edges[b] == 1.0 else [])
    growth = max(float(np.max(np.linalg.eigvals(slip_matrix(structure, s)).real)) for s in sides)
    if growth >= 0.0:
        return None  # the interpolant's steady sliding is not stable either: nothing certified
    return (f"the law's steady sliding is not linearly stable (growth rate {exact.growth_rate:.6g} "
            f"per unit tau with its slope {exact.slope:.6g} at the belt speed) but that of its "
            f"piecewise-linear interpolant is ({growth:.6g} with the band's slope {sides[0]:.6g}): "
            "a steady-sliding certificate of the interpolant does not hold for the law; lower "
            "the law's tolerance until the two agree")
