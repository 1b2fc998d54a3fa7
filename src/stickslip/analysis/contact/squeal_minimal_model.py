r"""The minimal model of brake squeal of Hoffmann et al. (2002) and its closed-form flutter boundary.

N. Hoffmann et al., "A minimal model for studying properties of the mode-coupling type
instability in friction induced oscillations", Mechanics Research Communications 29 (2002)
197-205: a point mass ``m`` on a belt, held by a
tangential spring ``k_1``, a normal spring ``k_2`` and a spring ``k_3`` inclined at the angle
``alpha`` to the belt, pressed on the belt through the contact stiffness ``k_n``. Its
stiffness (normal coordinate positive away from the belt) is
``K = [[k_11, k_12], [k_12, k_22]]`` with ``k_11 = k_1 + k_3 cos^2 alpha``,
``k_12 = k_3 cos alpha sin alpha``, ``k_22 = k_2 + k_3 sin^2 alpha``
(:func:`hoffmann_stiffness`). Undamped, ``det(K(\mu) - m \omega^2 I) = 0`` is a quadratic in
``\lambda = \omega^2``:

.. math::

    m^2 \lambda^2 - m (k_{11} + k_{22} + k_n) \lambda
        + k_{11}(k_{22} + k_n) - k_{12}(k_{12} + \mu k_n) = 0,

whose two roots merge where its discriminant vanishes,
``(k_11 - k_22 - k_n)^2 + 4 k_12 (k_12 + \mu k_n) = 0``:

.. math::

    \mu_{crit} = -\frac{(k_{11} - k_{22} - k_n)^2 + 4 k_{12}^2}{4 k_{12} k_n}
    \quad (k_{12} < 0),

(:func:`hoffmann_critical_mu`). With ``k_12 > 0`` the coupling stiffens instead and only a
belt running the other way flutters. With damping the boundary moves, and not always up:
damping that is unequal between the two modes can lower it (Hoffmann and Gaul 2003, "Effects
of damping on mode-coupling instability in friction induced oscillations", ZAMM 83,
524-534), the destabilising effect of damping.

Its linearisation is that of :mod:`stickslip.analysis.contact.eigenvalues` with ``M = m I``
and this ``K``; the tests check that analysis's critical ``mu`` against
:func:`hoffmann_critical_mu`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


def hoffmann_stiffness(k1: float, k2: float, k3: float, alpha: float) -> FloatArray:
    """Stiffness of the minimal model of Hoffmann et al. (2002), normal DOF away from the belt.

    Parameters
    ----------
    k1, k2, k3 : float
        Tangential, normal and inclined springs, N/m.
    alpha : float
        Angle of the inclined spring to the belt direction, rad.

    Returns
    -------
    ndarray, shape (2, 2)
        ``[[k1 + k3 cos^2 a, k3 cos a sin a], [k3 cos a sin a, k2 + k3 sin^2 a]]``, N/m
        (DOF 0 tangential, DOF 1 normal; the contact spring is not included).
    """
    c, s = math.cos(alpha), math.sin(alpha)
    return np.array([[k1 + k3 * c * c, k3 * c * s], [k3 * c * s, k2 + k3 * s * s]])


def hoffmann_critical_mu(mass: float, stiffness: Sequence[Sequence[float]] | FloatArray,
                         normal_stiffness: float) -> float:
    """Closed-form flutter boundary of the undamped minimal model (Hoffmann et al. 2002).

    ``mu_crit = -((k11 - k22 - k_n)^2 + 4 k12^2) / (4 k12 k_n)``: the zero of the discriminant
    of the 2x2 quadratic eigenproblem (module docstring). The mass does not enter (both DOF
    carry the same point mass); it is kept for the reader's check of units.

    Parameters
    ----------
    mass : float
        The point mass, kg (> 0).
    stiffness : array_like, shape (2, 2)
        Symmetric structural stiffness, N/m, DOF 0 tangential, DOF 1 normal (away from the belt).
    normal_stiffness : float
        Contact stiffness ``k_n``, N/m.

    Returns
    -------
    float
        The critical friction coefficient (dimensionless); ``inf`` when ``k12 >= 0`` (no
        flutter for a belt moving in the positive tangential direction).
    """
    if not mass > 0.0:
        raise ValueError(f"mass = {mass!r} must be positive")
    k = np.asarray(stiffness, dtype=float)
    k11, k12, k22 = float(k[0, 0]), float(k[0, 1]), float(k[1, 1]) + normal_stiffness
    if k12 >= 0.0:
        return math.inf
    return -((k11 - k22) ** 2 + 4.0 * k12 * k12) / (4.0 * k12 * normal_stiffness)
