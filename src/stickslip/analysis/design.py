"""The paper's design procedure (Fig. 16) in physical units, checked by simulation.

Given a slider (mass, spring, damper, friction, load, belt speed) the procedure answers:
does it stick-slip on a rigid base; what foundation (Eqs. 28-30) suppresses it; below
which belt speed and above which normal load stick-slip starts, by the paper's closed forms
(Eqs. 33, 37-39) and by certified simulation.

``lambda = (mu_s - mu_k) W / (V sqrt(m k))`` grows with the load and falls with the speed,
so stick-slip (``lambda`` above its critical value) happens for ``V < V_c`` and ``W > W_c``.

The closed forms are the paper's, for its Coulomb law (``mu = mu_k`` while sliding). The
simulated critical speed and load are those of the machine's own friction law: a law whose
dimensionless form moves with ``V`` or ``W`` (Stribeck, linear, table) has its own onset along
each, found by the exact boundary search of
:func:`stickslip.analysis.critical.speed_and_load_onsets`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from stickslip.analysis.critical import Onset, SpeedLoadOnsets, onset_note, speed_and_load_onsets
from stickslip.analysis.simulation import EngineOptions, SimulationResult, simulate
from stickslip.analysis.theory import (
    FITTED_ZETA_RANGE,
    MAX_DESIGN_ZETA,
    critical_lambda_approx,
    critical_lambda_exact,
    equivalent_damping_fit,
    optimal_foundation_fit,
)
from stickslip.analysis.verdict import RunStatus, Verdict
from stickslip.model._validate import MIN_RATIO, positive, within
from stickslip.model.friction import CoulombFriction
from stickslip.model.parameters import Foundation
from stickslip.model.physical import (
    PhysicalFoundation,
    PhysicalSystem,
    foundation_to_dimensionless,
    foundation_to_physical,
)
from stickslip.model.structure import Structure, elastic_foundation, rigid_base

#: Friction law of the closed-form rows (Eqs. 36, 37, 39): the paper's.
COULOMB_LAW = "coulomb (the paper's law, mu = mu_k while sliding)"

#: ``progress(stage, runs)``: the design procedure's current stage and the simulations it has
#: made so far (called when a stage starts, with 0, and after every run).
DesignProgress = Callable[[str, int], None]


@dataclass(frozen=True)
class CriticalValues:
    """Critical ``lambda`` and what it means for the machine (SI units).

    Attributes
    ----------
    lam : float
        Critical ``lambda`` at the critical speed (dimensionless); NaN when a search ended at
        a bound of its range (``note`` says which).
    speed : float
        m/s: stick-slip below this belt speed (at the operating load); ``inf``: at every speed.
    load : float
        N: stick-slip above this normal load (at the operating speed); ``0``: at every load.
    lam_load : float or None
        Critical ``lambda`` at the critical load, when it differs from ``lam`` (a friction law
        whose dimensionless form moves with ``V`` or ``W``).
    law : str
        The friction law of these values (:data:`COULOMB_LAW` for the paper's procedure).
    note : str
        What the numbers are when they are not a converged crossing (a bound of the search,
        undetermined runs, the exact limit at ``zeta = 0``); empty otherwise.
    """

    lam: float
    speed: float
    load: float
    lam_load: float | None = None
    law: str = COULOMB_LAW
    note: str = ""

    def to_dict(self) -> dict[str, float | str | None]:
        def num(x: float | None) -> float | None:
            return x if x is not None and math.isfinite(x) else None

        return {"lambda": num(self.lam), "speed": num(self.speed), "load": num(self.load),
                "lambda_load": num(self.lam if self.lam_load is None else self.lam_load),
                "law": self.law, "note": self.note or None}


@dataclass(frozen=True)
class DesignReport:
    """Outcome of :func:`design_foundation` (all physical values in SI units).

    ``critical`` maps ``rigid_theory`` (Eq. 39), ``rigid_exact`` (Eq. 36),
    ``rigid_simulation``, ``foundation_theory`` (Eq. 37 with ``zeta_eq``) and
    ``foundation_simulation`` to :class:`CriticalValues`. The theory and exact rows are the
    paper's Coulomb procedure; the simulation rows use the machine's friction law.
    ``status`` maps ``rigid`` and ``foundation`` to the run status of the verdict at the
    operating point (why a verdict is undetermined: horizon, event or step budget).
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
    status: dict[str, RunStatus] | None = None
    options: EngineOptions = field(default_factory=EngineOptions)

    def to_dict(self) -> dict[str, Any]:
        """JSON keys of the ``design`` command (issue 6)."""
        crit = self.critical

        def pick(attr: str) -> dict[str, Any]:
            return {k: v.to_dict()[attr] for k, v in crit.items()}

        status = self.status or {}

        f = self.foundation
        r = self.recommended
        dimensionless = self.foundation_dimensionless
        return {
            "lambda": self.lam,
            "zeta": self.zeta,
            # the ratio to the 15 digits its inputs carry: mu_s = 0.5, mu_k = 0.3 report 1.5,
            # not the 1.4999999999999998 the engine runs with (mu_k / (mu_s - mu_k) in floats)
            "gamma": float(f"{self.gamma:.15g}"),
            "zeta_eq": self.zeta_eq,
            "zeta_eq_source": self.zeta_eq_source,
            "verdict": self.verdicts,
            "critical_lambda": pick("lambda"),
            "critical_speed": pick("speed"),
            "critical_load": pick("load"),
            "critical_lambda_load": pick("lambda_load"),
            "critical_law": pick("law"),
            "critical_note": pick("note"),
            "verdict_status": {k: {"status": v.label, "message": v.message} for k, v in status.items()},
            "t_max": self.options.t_max,
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
    """The speed and load of a closed-form critical ``lambda`` (Coulomb law)."""
    if not math.isfinite(lam) or lam <= 0.0:
        return CriticalValues(lam, math.inf if lam <= 0 else 0.0,
                              0.0 if lam <= 0 else math.inf)
    return CriticalValues(lam, system.speed_for_lambda(lam), system.load_for_lambda(lam))


def _label(stick_slip: bool) -> str:
    return Verdict.STICK_SLIP.value if stick_slip else Verdict.STEADY_SLIDING.value


def _searched(system: PhysicalSystem, onsets: SpeedLoadOnsets, exact_limit: float | None) -> CriticalValues:
    """Critical values of the onset searches along the speed and the load, with their notes.

    ``exact_limit``: the closed-form critical ``lambda`` when it is known to be 0 (the
    undamped rigid base, Eq. 36): a search that finds stick-slip at its lower bound then
    reports that limit (every speed, every load) instead of the bound.
    """
    law = system.slider().friction.describe() if onsets.own_law else COULOMB_LAW
    speed_on, load_on = onsets.speed, onsets.load
    if exact_limit == 0.0 and speed_on.at_lower_bound and load_on.at_lower_bound:
        return CriticalValues(
            0.0, math.inf, 0.0, law=law,
            note=(f"zeta = 0, undamped: the exact limit lambda_c = 0 of Eq. (36); the simulation "
                  f"agrees, stick-slip at lambda = {speed_on.lam_min:g}, the lowest searched"))

    def value(onset: Onset, si_at: Callable[[float], float]) -> tuple[float, float]:
        if onset.at_lower_bound or onset.above_range:
            return math.nan, math.nan
        return onset.lam, si_at(onset.lam)

    lam, speed = value(speed_on, system.speed_for_lambda)
    lam_load, load = value(load_on, system.load_for_lambda)
    notes = [f"{axis}: {text}" for axis, text in (
        ("speed", onset_note(speed_on, "belt speed", system.speed_for_lambda, "m/s",
                              ("fastest", "slowest"))),
        ("load", onset_note(load_on, "normal load", system.load_for_lambda, "N",
                             ("lightest", "heaviest"), count_runs=onsets.own_law)),
    ) if text]
    return CriticalValues(lam, speed, load, lam_load if onsets.own_law else None, law, "; ".join(notes))


def _status_warning(where: str, status: RunStatus, options: EngineOptions) -> str:
    """Why the verdict ``where`` is undetermined, and how to decide it."""
    why = status.message.split(";")[0]
    if status is RunStatus.T_MAX:
        how = (f"a longer horizon may decide it: t_max = {options.t_max:g} now (dimensionless time "
               f"omega_n t), try {10 * options.t_max:g} (--t-max on the command line)")
    elif status is RunStatus.MAX_EVENTS:
        how = (f"the run switched mode {options.max_events:,} times (chattering or a very long "
               "transient); a larger event budget may decide it")
    else:
        why, how = status.message.split(":")[0], status.message.partition(":")[2].strip()
    return f"the verdict {where} is undetermined: {why}; {how}"


def _assessed_foundation(system: PhysicalSystem) -> tuple[PhysicalFoundation, Foundation, str, float, str]:
    """The foundation to assess, its dimensionless groups, source, ``zeta_eq`` and that one's source.

    The given foundation with its Eq. (32) ``zeta_eq``, else the recommended one of
    Eqs. (28)-(30) with Eq. (33).
    """
    zeta = system.zeta
    if system.foundation is not None:
        from stickslip.analysis.frequency_response import equivalent_damping

        dimensionless = foundation_to_dimensionless(system.foundation, system.mass, system.stiffness)
        return (system.foundation, dimensionless, "existing foundation (given)",
                equivalent_damping(elastic_foundation(zeta, dimensionless)),
                "Eq. (32): 1 / (2 H_max) of this foundation")
    dimensionless = optimal_foundation_fit(zeta)
    return (foundation_to_physical(dimensionless, system.mass, system.stiffness), dimensionless,
            "recommended: Fig. 16 procedure, Eqs. (28)-(30)", equivalent_damping_fit(zeta), "Eq. (33)")


def _warnings(system: PhysicalSystem, runs: dict[str, SimulationResult], options: EngineOptions
              ) -> list[str]:
    """What the reader of a design report must know: undamped, outside the fit, law, undecided runs."""
    zeta, law = system.zeta, system.slider().friction
    warnings = []
    if zeta == 0.0:
        warnings.append("c = 0 (undamped slider, zeta = 0): on a rigid base it stick-slips at every "
                        "speed and load (Eq. 36); give the slider's damping c if it has any")
    if zeta > FITTED_ZETA_RANGE:
        warnings.append(
            f"zeta={zeta:.3g} is outside the range 0 <= zeta <= 0.4 on which Eqs. (28)-(33) are "
            "fitted: trust the simulated verdicts, not the theory column"
        )
    if not isinstance(law, CoulombFriction):
        warnings.append(
            "the theory and Eq. 36 rows are the paper's procedure for its Coulomb law (mu = mu_k "
            "while sliding); the simulation rows and verdicts use the machine's friction law "
            f"({law.describe()}), whose critical speed and load are searched separately "
            "(the law moves with the belt speed and the load)"
        )
    for where, result in runs.items():
        if result.verdict is Verdict.UNDETERMINED:
            warnings.append(_status_warning(where, result.status, options))
    return warnings


def design_foundation(system: PhysicalSystem, *, lam_max: float = 200.0,
                      rtol: float = 1e-6, stick_slip_optimum: bool = False,
                      max_foundation_deflection: float | None = None,
                      options: EngineOptions | None = None,
                      progress: DesignProgress | None = None) -> DesignReport:
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
    options : EngineOptions, optional
        Engine limits of every simulation (horizon ``t_max`` in dimensionless time
        ``tau = omega_n t``, event budget); the defaults of :class:`EngineOptions`.
    progress : callable, optional
        ``progress(stage, runs)`` when a stage starts and after every simulation (a progress
        display for long runs).

    Returns
    -------
    DesignReport
        Verdicts, critical values (theory: the paper's Coulomb procedure; simulation: the
        machine's friction law) and the foundations, in SI units.
    """
    slider = system.slider()
    lam, zeta, gamma = slider.lam, system.zeta, slider.gamma
    if zeta > MAX_DESIGN_ZETA:
        raise ValueError(
            f"zeta={zeta:.4g} (c={system.damping:g} N s/m) is above {MAX_DESIGN_ZETA}: the slider is "
            "so damped that the design procedure (Eqs. 28-33, fitted for zeta <= 0.4) does not apply"
        )
    opts = options or EngineOptions()
    runs = 0
    stage = ""

    def start(name: str) -> None:
        nonlocal stage
        stage = name
        if progress is not None:
            progress(stage, runs)

    def count(*_: object) -> None:
        nonlocal runs
        runs += 1
        if progress is not None:
            progress(stage, runs)

    recommended = foundation_to_physical(optimal_foundation_fit(zeta), system.mass, system.stiffness)
    foundation, dimensionless, source, zeta_eq, zeta_eq_source = _assessed_foundation(system)
    rigid = rigid_base(zeta)
    with_foundation = elastic_foundation(zeta, dimensionless)
    lam_hi = max(lam_max, 4.0 * lam)
    own = "" if isinstance(slider.friction, CoulombFriction) else " (the machine's friction law)"

    def searched(structure: Structure, exact_limit: float | None) -> CriticalValues:
        onsets = speed_and_load_onsets(structure, system, lam_min=1e-3, lam_max=lam_hi, rtol=rtol,
                                       options=opts, on_run=count)
        return _searched(system, onsets, exact_limit)

    start("verdicts at the operating point")
    run_rigid = simulate(rigid, slider, options=opts, record=False)
    count()
    run_found = simulate(with_foundation, slider, options=opts, record=False)
    count()
    start(f"critical speed and load, rigid base{own}")
    rigid_limit = 0.0 if zeta == 0.0 and not own else None
    rigid_sim = searched(rigid, rigid_limit)
    start(f"critical speed and load, with foundation{own}")
    found_sim = searched(with_foundation, None)
    crit = {
        "rigid_theory": _critical(system, critical_lambda_approx(zeta)),
        "rigid_exact": _critical(system, critical_lambda_exact(zeta)),
        "rigid_simulation": rigid_sim,
        "foundation_theory": _critical(system, critical_lambda_approx(zeta_eq)),
        "foundation_simulation": found_sim,
    }
    verdicts = {
        "rigid": {
            "theory": _label(lam >= crit["rigid_theory"].lam),
            "exact": _label(lam >= crit["rigid_exact"].lam),
            "simulation": run_rigid.verdict.value,
        },
        "foundation": {
            "theory": _label(lam >= crit["foundation_theory"].lam),
            "simulation": run_found.verdict.value,
        },
    }
    status = {"rigid": run_rigid.status, "foundation": run_found.status}
    warnings = _warnings(system, {"on the rigid base": run_rigid, "with the foundation": run_found}, opts)
    optimum = None
    if stick_slip_optimum:
        start("stick-slip-optimal foundation (Coulomb law" + (", then the machine's)" if own else ")"))
        optimum = _stick_slip_optimum(system, zeta, gamma, lam,
                                      (lambda f: searched(f, None)) if own else None)
    start("stability of steady sliding")
    stability = stability_margin(system, {"rigid": rigid, "foundation": with_foundation})
    stable_best = None
    if not isinstance(slider.friction, CoulombFriction) or max_foundation_deflection is not None:
        start("stability-optimal foundation")
        stable_best = stability_optimum(system, max_foundation_deflection)
    return DesignReport(system, lam, zeta, gamma, zeta_eq, zeta_eq_source, foundation, dimensionless,
                        source, recommended, verdicts, crit, tuple(warnings), optimum, stability,
                        stable_best, status, opts)


#: Significant digits of the foundation ``design`` prints (its as-printed stability is checked).
PRINTED_DIGITS = 4


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
        ``mu_k W``) and the bound ``max_foundation_deflection`` (m); ``delta_crit_as_printed``
        and ``sigma_crit_as_printed``: the same for the foundation built from ``m_a``, ``k_a``,
        ``c_a`` rounded to :data:`PRINTED_DIGITS` significant digits (the optimum can sit on the
        edge of a window of instability, which the rounded foundation may cross).
    """
    from stickslip.analysis.stability import critical_weakening
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
    # d_max / own = 1 / K^2 bounds K = sqrt(k_a / k), which must stay in [MIN_RATIO, MAX_PARAMETER]
    within("max_foundation_deflection", d_max, own * MIN_RATIO**2, own / MIN_RATIO**2,
           f"in m: 1e-12 to 1e12 times the slider spring's deflection mu_k W / k = {own:.4g} m")
    result = optimal_foundation_stability(system.zeta, max_deflection_ratio=d_max / own)
    phys = foundation_to_physical(result.foundation, system.mass, system.stiffness)
    per_slope = 2.0 * math.sqrt(system.mass * system.stiffness) / system.load
    # the optimum can sit on the edge of a window of instability: the foundation built from
    # the printed values (m_a, k_a, c_a to PRINTED_DIGITS) may lose stability earlier
    printed = PhysicalFoundation(*(float(f"{x:.{PRINTED_DIGITS}g}") for x in (phys.m_a, phys.k_a, phys.c_a)))
    printed_delta = critical_weakening(elastic_foundation(
        system.zeta, foundation_to_dimensionless(printed, system.mass, system.stiffness)))
    return {
        "m_a": phys.m_a, "k_a": phys.k_a, "c_a": phys.c_a,
        "M": result.foundation.mass_ratio, "K": result.foundation.stiffness_ratio,
        "zeta_a": result.foundation.damping_ratio,
        "delta_crit": result.delta_crit,
        "sigma_crit": result.delta_crit * per_slope,
        "foundation_deflection": system.mu_k * system.load / phys.k_a,
        "max_foundation_deflection": d_max,
        "source": "largest exact delta_crit, M <= M_opt of Eq. (28), foundation deflection <= bound",
        "delta_crit_as_printed": printed_delta,
        "sigma_crit_as_printed": printed_delta * per_slope,
    }


def stability_margin(system: PhysicalSystem, structures: dict[str, Structure]) -> dict[str, Any]:
    """Linear stability of steady sliding for each structure, and its margin in SI units.

    For each structure: the growth rate of small motions about steady sliding under the
    system's friction law (per second: ``omega_n`` times the dimensionless rate), whether it is
    stable, the critical weakening ``delta_crit``
    (:func:`stickslip.analysis.stability.critical_weakening`) and the friction slope it allows,
    ``sigma_crit = 2 delta_crit sqrt(m k) / W`` in s/m (``d mu / d v_r`` may fall by at most that
    much at the belt speed), next to the law's own local weakening ``delta_local``; the margin is
    ``delta_crit - delta_local`` (positive: stable). ``neutral``: the growth rate is zero to
    round-off (:attr:`~stickslip.analysis.stability.SteadySlidingStability.neutral`), marginally
    stable, e.g. an undamped slider on a rigid base. ``safe_disturbance``: the largest knock
    about steady sliding certified never to start stick-slip
    (:func:`stickslip.analysis.disturbance.safe_disturbance`), in J, m/s and m. ``boundaries``:
    where steady sliding changes stability along the belt speed and the load (the Hopf
    boundary, :func:`stickslip.analysis.stability_boundaries.stability_boundaries`).

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
    from stickslip.analysis.stability_boundaries import stability_boundaries, steady_sliding_report

    slider = system.slider()
    per_slope = 2.0 * math.sqrt(system.mass * system.stiffness) / system.load
    out: dict[str, Any] = {"units": {"growth_rate": "1/s", "sigma": "s/m"}}
    for name, structure in structures.items():
        report = steady_sliding_report(structure, slider, stability_boundaries(system, structure),
                                       natural_frequency=system.natural_frequency,
                                       per_slope=per_slope)
        safe = safe_disturbance(structure, slider)
        report["safe_disturbance"] = {**safe.physical(system), "sentence": safe.sentence(system)}
        out[name] = report
    return out


def coulomb_tuning_note(law: str, *, onset_own_law: bool = False) -> str | None:
    """The sentence that says a stick-slip optimum assumes Coulomb friction, or None for Coulomb.

    The stick-slip-optimal foundation and absorber are tuned with the Coulomb law whatever the
    machine's law (:mod:`stickslip.analysis.stick_slip_tuning` says why); the report puts this
    sentence beside them.

    Parameters
    ----------
    law : str
        The machine's friction law (``coulomb``, ``linear``, ``stribeck``, ``table``, ...).
    onset_own_law : bool
        The onset reported beside the result is the machine's own law (a ``[structure]``
        machine's absorber); otherwise it is Coulomb too.

    Returns
    -------
    str or None
        The sentence (no final full stop), or None for the Coulomb law.
    """
    if law == "coulomb":
        return None
    if onset_own_law:
        return (f"assumes Coulomb friction: it is tuned with the paper's law mu = mu_k while "
                f"sliding, not the machine's {law} law; its V_c and W_c are the machine's own law")
    return (f"assumes Coulomb friction: it is tuned, and its onset lambda_c computed, with the "
            f"paper's law mu = mu_k while sliding, not the machine's {law} law")


def _stick_slip_optimum(system: PhysicalSystem, zeta: float, gamma: float, lam: float,
                        assess: Callable[[Structure], CriticalValues] | None = None) -> dict[str, Any]:
    """The stick-slip-optimal foundation in SI units, beside the absorber optimum.

    Tuned for the Coulomb law whatever the machine's (``assumption`` says so for another law);
    ``assess``, the machine's own-law boundary search, gives ``own_law``: its critical values.
    """
    from stickslip.analysis.stick_slip_tuning import optimal_foundation_stick_slip

    result = optimal_foundation_stick_slip(zeta, gamma, lam_max=max(100.0, 4.0 * lam))
    phys = foundation_to_physical(result.foundation, system.mass, system.stiffness)
    crit = _critical(system, result.lambda_crit)
    # no onset up to lam_max: the critical values are bounds (lambda_c >= lam_max, so V_c is at
    # most the speed and W_c at least the load of lam_max), not the 0 and inf of lambda = inf
    bounded = math.isinf(result.lambda_crit)
    return {
        "m_a": phys.m_a, "k_a": phys.k_a, "c_a": phys.c_a,
        "M": result.foundation.mass_ratio, "K": result.foundation.stiffness_ratio,
        "zeta_a": result.foundation.damping_ratio,
        "lambda_crit": crit.to_dict()["lambda"],
        "lambda_crit_at_least": result.lam_max if math.isinf(result.lambda_crit) else None,
        "critical_speed": None if bounded else crit.to_dict()["speed"],
        "critical_load": None if bounded else crit.to_dict()["load"],
        "critical_speed_at_most": system.speed_for_lambda(result.lam_max) if bounded else None,
        "critical_load_at_least": system.load_for_lambda(result.lam_max) if bounded else None,
        "absorber_optimum_lambda_crit": result.reference_lambda_crit,
        "source": "maximum simulated stick-slip onset, M <= M_opt of Eq. (28)",
        "friction_law": COULOMB_LAW,
        "assumption": coulomb_tuning_note(system.friction.law),
        "own_law": None if assess is None else assess(elastic_foundation(zeta, result.foundation)).to_dict(),
    }
