"""The paper's design procedure (Fig. 16) in physical units, checked by simulation.

Given a slider (mass, spring, damper, friction, load, belt speed) the procedure answers:
does it stick-slip on a rigid base; what foundation (Eqs. 28-30) suppresses it; below
which belt speed and above which normal load stick-slip starts, by the paper's closed forms
(Eqs. 33, 37-39) and by certified simulation.

``lambda = (mu_s - mu_k) W / (V sqrt(m k))`` grows with the load and falls with the speed,
so stick-slip (``lambda`` above its critical value) happens for ``V < V_c`` and ``W > W_c``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from stickslip.analysis.critical import lowest_onset
from stickslip.analysis.simulation import simulate
from stickslip.analysis.theory import (
    FITTED_ZETA_RANGE,
    MAX_DESIGN_ZETA,
    critical_lambda_approx,
    critical_lambda_exact,
    equivalent_damping_fit,
    optimal_foundation_fit,
)
from stickslip.analysis.verdict import Verdict
from stickslip.model._validate import positive
from stickslip.model.friction import CoulombFriction
from stickslip.model.parameters import Foundation
from stickslip.model.physical import (
    PhysicalFoundation,
    PhysicalSystem,
    foundation_to_dimensionless,
    foundation_to_physical,
)
from stickslip.model.structure import Structure, elastic_foundation, rigid_base


@dataclass(frozen=True)
class CriticalValues:
    """Critical ``lambda`` and what it means for the machine (SI units)."""

    lam: float
    speed: float  # m/s: stick-slip below this belt speed
    load: float  # N: stick-slip above this normal load

    def to_dict(self) -> dict[str, float | None]:
        def num(x: float) -> float | None:
            return x if math.isfinite(x) else None

        return {"lambda": num(self.lam), "speed": num(self.speed), "load": num(self.load)}


@dataclass(frozen=True)
class DesignReport:
    """Outcome of :func:`design_foundation` (all physical values in SI units).

    ``critical`` maps ``rigid_theory`` (Eq. 39), ``rigid_exact`` (Eq. 36),
    ``rigid_simulation``, ``foundation_theory`` (Eq. 37 with ``zeta_eq``) and
    ``foundation_simulation`` to :class:`CriticalValues`.
    """

    system: PhysicalSystem
    lam: float
    zeta: float
    gamma: float
    zeta_eq: float
    zeta_eq_source: str
    foundation: PhysicalFoundation
    foundation_dimensionless: Foundation
    foundation_source: str
    recommended: PhysicalFoundation
    verdicts: dict[str, dict[str, str]]
    critical: dict[str, CriticalValues]
    warnings: tuple[str, ...] = ()
    stick_slip_optimum: dict[str, Any] | None = None
    stability: dict[str, Any] | None = None
    stability_optimum: dict[str, Any] | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON keys of the ``design`` command (issue 6)."""
        crit = self.critical

        def pick(attr: str) -> dict[str, float | None]:
            return {k: v.to_dict()[attr] for k, v in crit.items()}

        f = self.foundation
        r = self.recommended
        dimensionless = self.foundation_dimensionless
        return {
            "lambda": self.lam,
            "zeta": self.zeta,
            "gamma": self.gamma,
            "zeta_eq": self.zeta_eq,
            "zeta_eq_source": self.zeta_eq_source,
            "verdict": self.verdicts,
            "critical_lambda": pick("lambda"),
            "critical_speed": pick("speed"),
            "critical_load": pick("load"),
            "foundation": {
                "m_a": f.m_a, "k_a": f.k_a, "c_a": f.c_a,
                "M": dimensionless.mass_ratio, "K": dimensionless.stiffness_ratio,
                "zeta_a": dimensionless.damping_ratio,
                "source": self.foundation_source,
            },
            "recommended_foundation": {"m_a": r.m_a, "k_a": r.k_a, "c_a": r.c_a,
                                       "source": "Fig. 16 procedure: Eqs. (28)-(30)"},
            "system": {
                "m": self.system.mass, "k": self.system.stiffness, "c": self.system.damping,
                "mu_s": self.system.mu_s, "mu_k": self.system.mu_k,
                "load": self.system.load, "speed": self.system.speed,
                "natural_frequency_rad_s": self.system.natural_frequency,
            },
            "units": {"speed": "m/s", "load": "N", "m_a": "kg", "k_a": "N/m", "c_a": "N s/m"},
            "warnings": list(self.warnings),
            "stick_slip_optimal_foundation": self.stick_slip_optimum,
            "friction": self.system.slider().friction.describe(),
            "stability": self.stability,
            "stability_optimal_foundation": self.stability_optimum,
        }

    def plot(self, **kwargs: Any) -> Any:
        """The design procedure (paper Fig. 16) as a flowchart with these numbers, a ``PlotResult``.

        Delegates to :func:`stickslip.plot.design.design_flowchart_plot` (its keywords).
        """
        from stickslip.plot.design import design_flowchart_plot

        return design_flowchart_plot(self, **kwargs)


def _critical(system: PhysicalSystem, lam: float) -> CriticalValues:
    if not math.isfinite(lam) or lam <= 0.0:
        return CriticalValues(lam, math.inf if lam <= 0 else 0.0,
                              0.0 if lam <= 0 else math.inf)
    return CriticalValues(lam, system.speed_for_lambda(lam), system.load_for_lambda(lam))


def _label(stick_slip: bool) -> str:
    return Verdict.STICK_SLIP.value if stick_slip else Verdict.STEADY_SLIDING.value


def design_foundation(system: PhysicalSystem, *, lam_max: float = 200.0,
                      rtol: float = 1e-6, stick_slip_optimum: bool = False,
                      max_foundation_deflection: float | None = None) -> DesignReport:
    """Run the design procedure of the paper's Fig. 16 and check it by simulation.

    Parameters
    ----------
    system : PhysicalSystem
        The slider in SI units. When ``system.foundation`` is set, that existing foundation
        is assessed (its ``zeta_eq = 1/(2 H_max)``, Eq. 32); otherwise the recommended
        foundation of Eqs. (28)-(30) is assessed (``zeta_eq`` from Eq. 33).
    lam_max : float
        Upper end of the lambda range searched by simulation.
    rtol : float
        Relative tolerance of the simulated critical lambda.
    stick_slip_optimum : bool
        Also search the foundation that maximises the simulated stick-slip onset (with the
        mass bounded by the recommended ``m_a``) and report it in SI units, with its critical
        speed and load (a few seconds more).
    max_foundation_deflection : float, optional
        Largest static deflection the foundation may take under the kinetic friction force
        ``mu_k W``, in m: the bound of the stability-optimal foundation, which is searched
        (and reported as ``stability_optimal_foundation``) when the friction law depends on
        the sliding speed. Default: four times the slider spring's deflection under the same
        force, ``4 mu_k W / k`` (the dimensionless default
        :data:`~stickslip.analysis.stability_tuning.MAX_FOUNDATION_DEFLECTION_RATIO`).

    Returns
    -------
    DesignReport
        Verdicts, critical values (theory and simulation) and the foundations, in SI units.
    """
    slider = system.slider()
    lam, zeta, gamma = slider.lam, system.zeta, slider.gamma
    if zeta > MAX_DESIGN_ZETA:
        raise ValueError(
            f"zeta={zeta:.4g} (c={system.damping:g} N s/m) is above {MAX_DESIGN_ZETA}: the slider is "
            "so damped that the design procedure (Eqs. 28-33, fitted for zeta <= 0.4) does not apply"
        )
    recommended_dimless = optimal_foundation_fit(zeta)
    recommended = foundation_to_physical(recommended_dimless, system.mass, system.stiffness)
    if system.foundation is not None:
        foundation = system.foundation
        dimensionless = foundation_to_dimensionless(foundation, system.mass, system.stiffness)
        source = "existing foundation (given)"
        from stickslip.analysis.frequency_response import equivalent_damping

        zeta_eq = equivalent_damping(elastic_foundation(zeta, dimensionless))
        zeta_eq_source = "Eq. (32): 1 / (2 H_max) of this foundation"
    else:
        foundation, dimensionless = recommended, recommended_dimless
        source = "recommended: Fig. 16 procedure, Eqs. (28)-(30)"
        zeta_eq = equivalent_damping_fit(zeta)
        zeta_eq_source = "Eq. (33)"
    rigid = rigid_base(zeta)
    with_foundation = elastic_foundation(zeta, dimensionless)
    lam_hi = max(lam_max, 4.0 * lam)
    crit = {
        "rigid_theory": _critical(system, critical_lambda_approx(zeta)),
        "rigid_exact": _critical(system, critical_lambda_exact(zeta)),
        "rigid_simulation": _critical(
            system, lowest_onset(rigid, gamma=gamma, lam_min=1e-3, lam_max=lam_hi, rtol=rtol)),
        "foundation_theory": _critical(system, critical_lambda_approx(zeta_eq)),
        "foundation_simulation": _critical(
            system, lowest_onset(with_foundation, gamma=gamma, lam_min=1e-3, lam_max=lam_hi, rtol=rtol)),
    }
    sim_rigid = simulate(rigid, slider, record=False).verdict
    sim_found = simulate(with_foundation, slider, record=False).verdict
    verdicts = {
        "rigid": {
            "theory": _label(lam >= crit["rigid_theory"].lam),
            "exact": _label(lam >= crit["rigid_exact"].lam),
            "simulation": sim_rigid.value,
        },
        "foundation": {
            "theory": _label(lam >= crit["foundation_theory"].lam),
            "simulation": sim_found.value,
        },
    }
    warnings = []
    if zeta > FITTED_ZETA_RANGE:
        warnings.append(
            f"zeta={zeta:.3g} is outside the range 0 <= zeta <= 0.4 on which Eqs. (28)-(33) are "
            "fitted: trust the simulated verdicts, not the theory column"
        )
    if not isinstance(slider.friction, CoulombFriction):
        warnings.append(
            "critical speeds and loads follow the paper's procedure for the Coulomb law; the "
            f"simulated verdicts at the operating point use the friction law ({slider.friction.describe()})"
        )
    optimum = _stick_slip_optimum(system, zeta, gamma, lam) if stick_slip_optimum else None
    stability = stability_margin(system, {"rigid": rigid, "foundation": with_foundation})
    stable_best = None
    if not isinstance(slider.friction, CoulombFriction) or max_foundation_deflection is not None:
        stable_best = stability_optimum(system, max_foundation_deflection)
    return DesignReport(system, lam, zeta, gamma, zeta_eq, zeta_eq_source, foundation, dimensionless,
                        source, recommended, verdicts, crit, tuple(warnings), optimum, stability,
                        stable_best)


def stability_optimum(system: PhysicalSystem, max_foundation_deflection: float | None = None
                      ) -> dict[str, Any]:
    """The foundation that lets steady sliding tolerate the steepest friction weakening, in SI.

    The search is :func:`~stickslip.analysis.stability_tuning.optimal_foundation_stability`
    (exact ``delta_crit`` from the characteristic polynomial), with the foundation's static
    deflection under the kinetic friction force bounded: ``mu_k W / k_a <= d_max``. In the
    dimensionless form this is ``1 / K^2 <= d_max k / (mu_k W)``, the ratio of ``d_max`` to the
    slider spring's own deflection ``mu_k W / k``.

    Parameters
    ----------
    system : PhysicalSystem
        The machine in SI units.
    max_foundation_deflection : float, optional
        ``d_max`` in m; default ``4 mu_k W / k``.

    Returns
    -------
    dict
        ``m_a`` kg, ``k_a`` N/m, ``c_a`` N s/m, ``M``, ``K``, ``zeta_a``, ``delta_crit`` and the
        friction slope it tolerates ``sigma_crit`` (s/m), ``foundation_deflection`` (m, under
        ``mu_k W``) and the bound ``max_foundation_deflection`` (m).
    """
    from stickslip.analysis.stability_tuning import (
        MAX_FOUNDATION_DEFLECTION_RATIO,
        optimal_foundation_stability,
    )

    own = system.mu_k * system.load / system.stiffness  # slider spring's deflection under mu_k W, m
    if max_foundation_deflection is None:
        d_max = MAX_FOUNDATION_DEFLECTION_RATIO * own
    else:
        d_max = positive("max_foundation_deflection", max_foundation_deflection)
    if own <= 0.0:
        raise ValueError("a foundation deflection bound needs a kinetic friction force mu_k W > 0")
    result = optimal_foundation_stability(system.zeta, max_deflection_ratio=d_max / own)
    phys = foundation_to_physical(result.foundation, system.mass, system.stiffness)
    per_slope = 2.0 * math.sqrt(system.mass * system.stiffness) / system.load
    return {
        "m_a": phys.m_a, "k_a": phys.k_a, "c_a": phys.c_a,
        "M": result.foundation.mass_ratio, "K": result.foundation.stiffness_ratio,
        "zeta_a": result.foundation.damping_ratio,
        "delta_crit": result.delta_crit,
        "sigma_crit": result.delta_crit * per_slope,
        "foundation_deflection": system.mu_k * system.load / phys.k_a,
        "max_foundation_deflection": d_max,
        "source": "largest exact delta_crit, M <= M_opt of Eq. (28), foundation deflection <= bound",
    }


def stability_margin(system: PhysicalSystem, structures: dict[str, Structure]) -> dict[str, Any]:
    """Linear stability of steady sliding for each structure, and its margin in SI units.

    For each structure: the growth rate of small motions about steady sliding under the
    system's friction law (per second: ``omega_n`` times the dimensionless rate), whether it is
    stable, the critical weakening ``delta_crit``
    (:func:`stickslip.analysis.stability.critical_weakening`) and the friction slope it allows,
    ``sigma_crit = 2 delta_crit sqrt(m k) / W`` in s/m (``d mu / d v_r`` may fall by at most that
    much at the belt speed), next to the law's own local weakening ``delta_local``; the margin is
    ``delta_crit - delta_local`` (positive: stable). ``safe_disturbance``: the largest knock
    about steady sliding certified never to start stick-slip
    (:func:`stickslip.analysis.disturbance.safe_disturbance`), in J, m/s and m.

    Parameters
    ----------
    system : PhysicalSystem
        The machine in SI units.
    structures : dict of str to Structure
        The structures to assess, by name (e.g. ``rigid`` and ``foundation``).

    Returns
    -------
    dict
        Per structure the keys above, plus ``units``.
    """
    from stickslip.analysis.disturbance import safe_disturbance
    from stickslip.analysis.stability import critical_weakening, steady_sliding_stability

    slider = system.slider()
    per_slope = 2.0 * math.sqrt(system.mass * system.stiffness) / system.load
    out: dict[str, Any] = {"units": {"growth_rate": "1/s", "sigma": "s/m"}}
    for name, structure in structures.items():
        stab = steady_sliding_stability(structure, slider)
        delta_crit = critical_weakening(structure)
        out[name] = {
            "stable": bool(stab.stable),
            "growth_rate": stab.growth_rate * system.natural_frequency,
            "delta_local": stab.delta_local,
            "delta_crit": delta_crit,
            "margin": delta_crit - stab.delta_local,
            "sigma_local": stab.delta_local * per_slope,
            "sigma_crit": delta_crit * per_slope,
            "safe_disturbance": {**safe_disturbance(structure, slider).physical(system),
                                 "sentence": safe_disturbance(structure, slider).sentence(system)},
        }
    return out


def _stick_slip_optimum(system: PhysicalSystem, zeta: float, gamma: float,
                        lam: float) -> dict[str, Any]:
    """The stick-slip-optimal foundation in SI units, beside the absorber optimum."""
    from stickslip.analysis.stick_slip_tuning import optimal_foundation_stick_slip

    result = optimal_foundation_stick_slip(zeta, gamma, lam_max=max(100.0, 4.0 * lam))
    phys = foundation_to_physical(result.foundation, system.mass, system.stiffness)
    crit = _critical(system, result.lambda_crit)
    return {
        "m_a": phys.m_a, "k_a": phys.k_a, "c_a": phys.c_a,
        "M": result.foundation.mass_ratio, "K": result.foundation.stiffness_ratio,
        "zeta_a": result.foundation.damping_ratio,
        "lambda_crit": crit.to_dict()["lambda"],
        "lambda_crit_at_least": result.lam_max if math.isinf(result.lambda_crit) else None,
        "critical_speed": crit.to_dict()["speed"],
        "critical_load": crit.to_dict()["load"],
        "absorber_optimum_lambda_crit": result.reference_lambda_crit,
        "source": "maximum simulated stick-slip onset, M <= M_opt of Eq. (28)",
    }
