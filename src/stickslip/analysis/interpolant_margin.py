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
from stickslip.model.friction import FrictionLaw
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure


def interpolant_mismatch(structure: Structure, slider: Slider) -> tuple[str, str] | None:
    """Which certificate of a smooth law's interpolant does not hold for the law, and why.

    A smooth law (Stribeck) runs as its piecewise-linear interpolant, and the engine's
    certificates are the interpolant's: its slope at the belt speed is the secant of the band
    that holds ``u = 1``, where the law's own linearisation has the tangent
    (:func:`steady_sliding_stability`). Near the law's stability limit the two can fall on
    either side of it:

    * ``"steady"``: the law's steady sliding is not linearly stable, the interpolant's is. An
      independent audit found steady sliding certified on the rigid base at ``zeta = 0.99
      zeta_0`` (``zeta_0`` the zero of the net damping ``2 zeta + F'(1)`` of
      ``stribeck:vs=0.2,n=1``, ``lambda = 2``, tolerance 1e-4) where the law's steady sliding
      grows (3.4e-4 per unit tau) and its true motion reaches the belt speed at tau = 3,233.
      Steady-sliding certificates, and the disturbance margin built on them, are withheld.
    * ``"oscillation"``: the law's steady sliding is linearly stable, the interpolant's is not
      (its band steeper than the tangent). The interpolant's own small slip oscillation about
      steady sliding is then certified where the law settles: ``stribeck:vs=0.3,n=1``,
      ``lambda = 1``, ``zeta = 0.06`` (between the zeros 0.05945 and 0.06065 of the two net
      dampings) gave a slip oscillation of amplitude 0.0145 at tolerance 1e-4 and steady
      sliding at 1e-6. Slip-oscillation certificates are withheld.

    Parameters
    ----------
    structure : Structure
        Dimensionless matrices, contact on DOF 0.
    slider : Slider
        ``lambda``, ``gamma`` and the friction law.

    Returns
    -------
    tuple of str or None
        ``(kind, reason)``, the reason with both growth rates; None for exact laws (Coulomb,
        linear, tables: the engine runs the law itself) and when the two agree.
    """
    law = slider.friction
    if law.exact:
        return None
    exact = steady_sliding_stability(structure, slider)
    sides = band_slopes_at_belt_speed(law, slider.lam, slider.gamma)
    growth = max(float(np.max(np.linalg.eigvals(slip_matrix(structure, s)).real)) for s in sides)
    rates = (f"(growth rate {exact.growth_rate:.6g} per unit tau with its slope {exact.slope:.6g} "
             f"at the belt speed; the interpolant's {growth:.6g} with the band's slope "
             f"{sides[0]:.6g})")
    if not exact.stable and growth < 0.0:
        return "steady", (f"the law's steady sliding is not linearly stable but that of its "
                          f"piecewise-linear interpolant is {rates}: a steady-sliding certificate "
                          "of the interpolant does not hold for the law; lower the law's "
                          "tolerance until the two agree")
    if exact.stable and growth >= 0.0:
        return "oscillation", (f"the law's steady sliding is linearly stable but that of its "
                               f"piecewise-linear interpolant is not {rates}: a slip oscillation "
                               "of the interpolant may be its own, not the law's; lower the "
                               "law's tolerance until the two agree")
    return None


def interpolant_steady_mismatch(structure: Structure, slider: Slider) -> str | None:
    """The reason of :func:`interpolant_mismatch` when it withholds steady sliding, else None.

    Parameters
    ----------
    structure : Structure
        Dimensionless matrices, contact on DOF 0.
    slider : Slider
        ``lambda``, ``gamma`` and the friction law.

    Returns
    -------
    str or None
        The reason, or None.
    """
    found = interpolant_mismatch(structure, slider)
    return found[1] if found is not None and found[0] == "steady" else None


def band_slopes_at_belt_speed(law: FrictionLaw, lam: float, gamma: float) -> list[float]:
    """The interpolant's slope at ``u = 1``: its band's, and the band's below too when ``u = 1``
    is a node (as :func:`~stickslip.analysis.stability.one_sided_slopes` reads them).

    Parameters
    ----------
    law : FrictionLaw
        The friction law (its band table).
    lam, gamma : float
        ``lambda`` and ``gamma`` of the contact.

    Returns
    -------
    list of float
        One slope, or two at a node (the band above first).
    """
    edges, _, slopes = law.bands(lam, gamma)
    b = int(np.searchsorted(edges, 1.0, side="right") - 1)
    return [float(slopes[b])] + ([float(slopes[b - 1])] if b > 0 and edges[b] == 1.0 else [])
