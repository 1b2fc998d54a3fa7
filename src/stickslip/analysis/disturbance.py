"""Disturbances of steady sliding: the certified safe margin.

Above the stick-slip boundary the sliding system is usually bistable: steady sliding is
stable, yet a large enough knock tips it into stick-slip. :func:`safe_disturbance` answers
"how large a disturbance is certainly harmless?" without simulation, from the same Lyapunov
certificate that proves steady sliding in the engine.

Derivation. At steady sliding the slider rests (``xi' = 0``, sliding speed ``u = 1``) inside
the velocity band ``[u_a, u_b)`` of the friction law that contains ``u = 1`` (Coulomb:
``[0, inf)``). While the slider's velocity stays within ``|xi'| < v_lim = min(1 - u_a,
u_b - 1)`` the motion is the linear slip-I dynamics of that band, ``z' = A z`` for the
deviation ``z = (q - q_eq, q')`` from the equilibrium. Let ``V(z) = z' P z`` be a quadratic
Lyapunov function (``A' P + P A <= 0``): the mechanical energy ``E(z) = (q' K q + v' M v)/2``
when the band's damping ``C + s e_0 e_0'`` is positive semi-definite, or the solution of
``A' P + P A = -I`` when ``A`` is Hurwitz. ``V`` never increases, and by Cauchy-Schwarz in
the ``P`` inner product ``|xi'| <= sqrt(kappa V)`` with ``kappa = (P^-1)_vv``. Hence a start
with ``V(z_0) < c* = v_lim^2 / kappa`` keeps ``|xi'| < v_lim`` for all time: the dynamics stay
linear (self-consistently), the velocity never reaches the belt speed, and the slider never
sticks again. The norm reported is the mechanical energy of the deviation: the largest
``E*`` with ``{E <= E*}`` inside ``{V < c*}`` is ``c* / lambda_max(P_E^-1 P)`` (``= c*`` for
``P = P_E``). A pure velocity kick ``dv`` of the slider from steady sliding is certified
harmless while ``dv^2 P_vv < c*``; a pure displacement ``dx`` while ``dx^2 P_xx < c*``. The best
of the available certificates is reported for each measure.

For the undamped rigid base with the Coulomb law the energy certificate is exact: a kick
``dv < V`` keeps the slider below the belt speed, and any larger kick reaches it.
Dimensionless units: energy in ``m V^2``, velocity in ``V``, displacement in ``V / omega_n``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.interpolant_margin import interpolant_steady_mismatch
from stickslip.analysis.stability import linearised_damping, slip_matrix
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure

if TYPE_CHECKING:
    from stickslip.model.physical import PhysicalSystem

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class SafeDisturbance:
    """Certified harmless disturbances of steady sliding (dimensionless).

    Attributes
    ----------
    energy : float
        Largest mechanical energy of a deviation from steady sliding (units ``m V^2``) below
        which the slider certainly never sticks again; 0 when nothing is certified.
    velocity_kick : float
        Largest change of the slider velocity alone (units of the belt speed ``V``).
    displacement : float
        Largest displacement of the slider alone (units ``V / omega_n``).
    velocity_limit : float
        ``v_lim``: the slider speed that keeps the sliding speed inside the friction band of
        steady sliding (1 for the Coulomb law: the belt speed).
    certificate : str
        Which Lyapunov function gave the energy margin (``energy`` or ``lyapunov``), or why
        there is none.
    """

    energy: float
    velocity_kick: float
    displacement: float
    velocity_limit: float
    certificate: str

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (dimensionless)."""
        return {"energy": self.energy, "velocity_kick": self.velocity_kick,
                "displacement": self.displacement, "velocity_limit": self.velocity_limit,
                "certificate": self.certificate,
                "units": {"energy": "m V^2", "velocity_kick": "V", "displacement": "V/omega_n"}}

    def physical(self, system: PhysicalSystem) -> dict[str, float]:
        """The margins in SI units: energy in J, velocity kick in m/s, displacement in m."""
        return {
            "energy_J": self.energy * system.mass * system.speed**2,
            "velocity_kick_m_s": self.velocity_kick * system.speed,
            "displacement_m": self.displacement * system.length_scale,
        }

    def sentence(self, system: PhysicalSystem | None = None) -> str:
        """One line for people: how large a knock cannot start stick-slip."""
        if self.energy <= 0.0:
            return f"no disturbance is certified harmless ({self.certificate})"
        band = ("" if self.velocity_limit >= 1.0 else
                f" (certified within the law's velocity band around V, |dv| < {self.velocity_limit:.3g} V: "
                "conservative for a curved law)")
        if system is None:
            return (f"a velocity kick below {self.velocity_kick:.4g} V, a displacement below "
                    f"{self.displacement:.4g} V/omega_n or any disturbance of energy below "
                    f"{self.energy:.4g} m V^2 cannot start stick-slip{band}")
        p = self.physical(system)
        return (f"a velocity kick below {p['velocity_kick_m_s'] * 1e3:.4g} mm/s, a displacement "
                f"below {p['displacement_m'] * 1e3:.4g} mm or any disturbance of energy below "
                f"{p['energy_J']:.4g} J cannot start stick-slip{band}")


def _band_at_belt_speed(slider: Slider) -> tuple[float, float]:
    """``(v_lim, slope)``: distance of ``u = 1`` to its band's edges, and the band's slope."""
    edges, _, slopes = slider.friction.bands(slider.lam, slider.gamma)
    b = int(np.searchsorted(edges, 1.0, side="right") - 1)
    lo, hi = float(edges[b]), float(edges[b + 1])
    return min(1.0 - lo, hi - 1.0), float(slopes[b])


def _lyapunov_matrices(structure: Structure, slope: float) -> list[tuple[str, FloatArray]]:
    """The quadratic Lyapunov functions available for slip-I of the band (name, ``P``)."""
    from scipy.linalg import solve_continuous_lyapunov

    n = structure.n_dof
    out: list[tuple[str, FloatArray]] = []
    energy = np.zeros((2 * n, 2 * n))
    energy[:n, :n] = 0.5 * structure.stiffness
    energy[n:, n:] = 0.5 * structure.mass
    damping = linearised_damping(structure, slope)
    if np.linalg.eigvalsh(0.5 * (damping + damping.T)).min() >= -1e-14 * max(1.0, abs(damping).max()):
        out.append(("energy", energy))
    a = slip_matrix(structure, slope)
    if np.max(np.linalg.eigvals(a).real) < 0.0:
        with warnings.catch_warnings():
            # SciPy warns (and perturbs a) when two eigenvalues nearly cancel, as on a very
            # stiff or very soft foundation; the solution is checked below either way
            warnings.simplefilter("ignore", RuntimeWarning)
            p = solve_continuous_lyapunov(a.T, -np.eye(2 * n))
        p = 0.5 * (p + p.T)
        q = -(a.T @ p + p @ a)  # a function the margins rest on must decrease: q > 0
        if np.all(np.isfinite(p)) and np.linalg.eigvalsh(p).min() > 0.0 \
                and np.linalg.eigvalsh(0.5 * (q + q.T)).min() > 0.0:
            out.append(("lyapunov", p))
    return out


def safe_disturbance(structure: Structure, slider: Slider) -> SafeDisturbance:
    """The largest disturbances of steady sliding certified never to start stick-slip.

    Parameters
    ----------
    structure : Structure
        Dimensionless matrices, contact on DOF 0 (rigid base, foundation or chain).
    slider : Slider
        ``lambda``, ``gamma`` and the friction law (the band around the belt speed matters).

    Returns
    -------
    SafeDisturbance
        Energy, velocity-kick and displacement margins (see the module docstring for the
        derivation); all zero with the reason when no Lyapunov function exists (steady
        sliding unstable, or its equilibrium on a band edge).
    """
    structure = structure.contact_first()[0]  # the margins below read the contact at 0
    n = structure.n_dof
    v_lim, slope = _band_at_belt_speed(slider)
    if not v_lim > 0.0:
        return SafeDisturbance(0.0, 0.0, 0.0, 0.0, "steady sliding lies on a band edge of the law")
    mismatch = interpolant_steady_mismatch(structure, slider)
    if mismatch is not None:
        return SafeDisturbance(0.0, 0.0, 0.0, v_lim, "the law's steady sliding is not linearly "
                               "stable, only its interpolant's")
    candidates = _lyapunov_matrices(structure, slope)
    if not candidates:
        return SafeDisturbance(0.0, 0.0, 0.0, v_lim, "steady sliding is not stable")
    p_energy = np.zeros((2 * n, 2 * n))
    p_energy[:n, :n] = 0.5 * structure.stiffness
    p_energy[n:, n:] = 0.5 * structure.mass
    best_energy, best_name, kick, shift = 0.0, "", 0.0, 0.0
    for name, p in candidates:
        kappa = float(np.linalg.solve(p, np.eye(2 * n)[:, n])[n])
        level = v_lim**2 / kappa
        growth = float(np.max(np.linalg.eigvals(np.linalg.solve(p_energy, p)).real))
        energy = level / growth
        if energy > best_energy:
            best_energy, best_name = energy, name
        kick = max(kick, math.sqrt(level / p[n, n]))
        shift = max(shift, math.sqrt(level / p[0, 0]))
    return SafeDisturbance(best_energy, kick, shift, v_lim, best_name)
