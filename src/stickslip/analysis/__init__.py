"""Analysis layer: simulation and its verdict, the paper's closed forms, tuning, design.

Modules, bottom to top (each imports only from those above it in this list, and from
``model`` and ``kernel``): ``verdict``, ``stability``, ``frequency_response``, ``optimise``,
``theory`` (closed forms with the ranges they are fitted on), ``disturbance``, ``simulation``,
``critical``, ``cycles``, ``peak_minimiser``, ``absorber_tuning``, ``stick_slip_tuning``,
``stability_tuning``, ``dva`` (resolving a foundation choice), ``analytic_boundary``,
``design``. ``tuning`` is the deprecated former home of the tuning (one release).

Families beyond the paper have sub-packages, each with a lazy face: ``memory`` (friction with
memory: rate-and-state and LuGre), ``contact`` (normal-load coupling, separation, complex
eigenvalues, tangential compliance) and ``identification`` (a machine from a measured record).

Names load on first use (PEP 562); every name of ``__all__`` is public, the rest is private.
The function ``frequency_response`` shares its name with its module, so it is reached as
``stickslip.frequency_response`` (or from its module), not from this face.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from stickslip._lazy import alias_moved_modules, lazy_exports

#: Public name -> module that defines it.
_EXPORTS: dict[str, str] = {
    # analysis: one simulation and its verdict
    "simulate": "stickslip.analysis.simulation",
    "EngineOptions": "stickslip.analysis.simulation",
    "SimulationResult": "stickslip.analysis.simulation",
    "TimeHistory": "stickslip.analysis.simulation",
    "Verdict": "stickslip.analysis.verdict",
    "RunStatus": "stickslip.analysis.verdict",
    "Mode": "stickslip.analysis.verdict",
    # analysis: closed forms of the paper and the boundaries of a foundation choice
    "optimal_foundation_fit": "stickslip.analysis.theory",
    "peak_response_fit": "stickslip.analysis.theory",
    "equivalent_damping_fit": "stickslip.analysis.theory",
    "critical_lambda_exact": "stickslip.analysis.theory",
    "critical_lambda_approx": "stickslip.analysis.theory",
    "critical_lambda_linear": "stickslip.analysis.theory",
    "stick_slip_period": "stickslip.analysis.theory",
    "stick_slip_amplitude_ratio": "stickslip.analysis.theory",
    "resolve_dva": "stickslip.analysis.dva",
    "analytic_boundaries": "stickslip.analysis.analytic_boundary",
    "AnalyticBoundary": "stickslip.analysis.analytic_boundary",
    # analysis: absorber frequency response and tuning
    "response_peak": "stickslip.analysis.frequency_response",
    "ResponsePeak": "stickslip.analysis.frequency_response",
    "equivalent_damping": "stickslip.analysis.frequency_response",
    "response_curves": "stickslip.analysis.frequency_response",
    "ResponseCurves": "stickslip.analysis.frequency_response",
    "tune_foundation": "stickslip.analysis.absorber_tuning",
    "TuningResult": "stickslip.analysis.absorber_tuning",
    "optimal_foundation_exact": "stickslip.analysis.absorber_tuning",
    "tuning_curve": "stickslip.analysis.absorber_tuning",
    "TuningCurve": "stickslip.analysis.absorber_tuning",
    "optimal_foundation_stick_slip": "stickslip.analysis.stick_slip_tuning",
    "StickSlipTuning": "stickslip.analysis.stick_slip_tuning",
    "optimal_foundation_stability": "stickslip.analysis.stability_tuning",
    "StabilityTuning": "stickslip.analysis.stability_tuning",
    # analysis: onsets, cycles, stability of steady sliding, disturbances, design
    "lowest_onset": "stickslip.analysis.critical",
    "Crossing": "stickslip.analysis.critical",
    "find_cycles": "stickslip.analysis.cycles",
    "cycle_exists": "stickslip.analysis.cycles",
    "Cycle": "stickslip.analysis.cycles",
    "CycleSearch": "stickslip.analysis.cycles",
    "steady_sliding_stability": "stickslip.analysis.stability",
    "SteadySlidingStability": "stickslip.analysis.stability",
    "critical_weakening": "stickslip.analysis.stability",
    "safe_disturbance": "stickslip.analysis.disturbance",
    "SafeDisturbance": "stickslip.analysis.disturbance",
    "design_foundation": "stickslip.analysis.design",
    "DesignReport": "stickslip.analysis.design",
    "stability_margin": "stickslip.analysis.design",
    # the shared optimiser, the H-infinity peak minimiser, limits and helpers
    "nelder_mead": "stickslip.analysis.optimise",
    "best_seed": "stickslip.analysis.optimise",
    "box_simplex": "stickslip.analysis.optimise",
    "ordered_bounds": "stickslip.analysis.optimise",
    "minimise_peak": "stickslip.analysis.peak_minimiser",
    "PeakMinimum": "stickslip.analysis.peak_minimiser",
    "DEFAULT_MASS_BOUNDS": "stickslip.analysis.absorber_tuning",
    "STIFFNESS_BOUNDS": "stickslip.analysis.absorber_tuning",
    "DAMPING_BOUNDS": "stickslip.analysis.absorber_tuning",
    "check_tuning_zeta": "stickslip.analysis.absorber_tuning",
    "MAX_DESIGN_ZETA": "stickslip.analysis.theory",
    "FITTED_ZETA_RANGE": "stickslip.analysis.theory",
    "MAX_TUNING_ZETA": "stickslip.analysis.theory",
    "check_fitted_zeta": "stickslip.analysis.theory",
    "nakano_boundary_residual": "stickslip.analysis.theory",
    "stick_slip_frequency_ratio": "stickslip.analysis.theory",
    "stick_slip_predicted": "stickslip.analysis.theory",
    "optimal_mass_ratio_fit": "stickslip.analysis.theory",
    "optimal_stiffness_ratio_fit": "stickslip.analysis.theory",
    "optimal_damping_ratio_fit": "stickslip.analysis.theory",
    "equivalent_damping_from_peak": "stickslip.analysis.theory",
    "fitted_zeta_warning": "stickslip.analysis.dva",
    "equivalent_damping_ratio": "stickslip.analysis.analytic_boundary",
    "VERDICTS": "stickslip.analysis.verdict",
    "STATUSES": "stickslip.analysis.verdict",
    "CERTIFIED_VERDICTS": "stickslip.analysis.verdict",
    "verdict_codes": "stickslip.analysis.verdict",
    "verdict_flag_attributes": "stickslip.analysis.verdict",
    "status_flag_attributes": "stickslip.analysis.verdict",
}

__all__ = [
    "CERTIFIED_VERDICTS",
    "DAMPING_BOUNDS",
    "DEFAULT_MASS_BOUNDS",
    "FITTED_ZETA_RANGE",
    "MAX_DESIGN_ZETA",
    "MAX_TUNING_ZETA",
    "STATUSES",
    "STIFFNESS_BOUNDS",
    "VERDICTS",
    "AnalyticBoundary",
    "Crossing",
    "Cycle",
    "CycleSearch",
    "DesignReport",
    "EngineOptions",
    "Mode",
    "PeakMinimum",
    "ResponseCurves",
    "ResponsePeak",
    "RunStatus",
    "SafeDisturbance",
    "SimulationResult",
    "StabilityTuning",
    "SteadySlidingStability",
    "StickSlipTuning",
    "TimeHistory",
    "TuningCurve",
    "TuningResult",
    "Verdict",
    "analytic_boundaries",
    "best_seed",
    "box_simplex",
    "check_fitted_zeta",
    "check_tuning_zeta",
    "critical_lambda_approx",
    "critical_lambda_exact",
    "critical_lambda_linear",
    "critical_weakening",
    "cycle_exists",
    "design_foundation",
    "equivalent_damping",
    "equivalent_damping_fit",
    "equivalent_damping_from_peak",
    "equivalent_damping_ratio",
    "find_cycles",
    "fitted_zeta_warning",
    "lowest_onset",
    "minimise_peak",
    "nakano_boundary_residual",
    "nelder_mead",
    "optimal_damping_ratio_fit",
    "optimal_foundation_exact",
    "optimal_foundation_fit",
    "optimal_foundation_stability",
    "optimal_foundation_stick_slip",
    "optimal_mass_ratio_fit",
    "optimal_stiffness_ratio_fit",
    "ordered_bounds",
    "peak_response_fit",
    "resolve_dva",
    "response_curves",
    "response_peak",
    "safe_disturbance",
    "simulate",
    "stability_margin",
    "status_flag_attributes",
    "steady_sliding_stability",
    "stick_slip_amplitude_ratio",
    "stick_slip_frequency_ratio",
    "stick_slip_period",
    "stick_slip_predicted",
    "tune_foundation",
    "tuning_curve",
    "verdict_codes",
    "verdict_flag_attributes",
]

__getattr__, __dir__ = lazy_exports(__name__, globals(), _EXPORTS)

#: Modules that moved into the family sub-packages ``memory``, ``contact`` and
#: ``identification`` (their former names import, with a DeprecationWarning, for one release).
_MOVED_INTO_FAMILIES = {
    "memory_arclength": "memory.arclength",
    "memory_continuation": "memory.continuation",
    "memory_cycle_search": "memory.cycle_search",
    "memory_cycles": "memory.cycles",
    "memory_design": "memory.design",
    "memory_friction": "memory.friction",
    "memory_simulation": "memory.simulation",
    "memory_stability": "memory.stability",
    "contact_boundary": "contact.boundary",
    "contact_continuation": "contact.continuation",
    "contact_cycles": "contact.cycles",
    "contact_design": "contact.design",
    "contact_engine": "contact.engine",
    "contact_pool": "contact.pool",
    "complex_eigenvalue_maps": "contact.eigenvalue_maps",
    "complex_eigenvalues": "contact.eigenvalues",
    "friction_coupling": "contact.friction_coupling",
    "squeal_minimal_model": "contact.squeal_minimal_model",
    "identification_estimates": "identification.estimates",
    "identification_problem": "identification.problem",
    "identification_result": "identification.result",
    "fit_statistics": "identification.fit_statistics",
    "lugre_fit": "identification.lugre_fit",
    "rate_state_fit": "identification.rate_state_fit",
}
alias_moved_modules({f"{__name__}.{old}": f"{__name__}.{new}"
                     for old, new in _MOVED_INTO_FAMILIES.items()})


if TYPE_CHECKING:  # pragma: no cover - for type checkers and IDEs only
    from stickslip.analysis.absorber_tuning import (
        DAMPING_BOUNDS,
        DEFAULT_MASS_BOUNDS,
        STIFFNESS_BOUNDS,
        TuningCurve,
        TuningResult,
        check_tuning_zeta,
        optimal_foundation_exact,
        tune_foundation,
        tuning_curve,
    )
    from stickslip.analysis.analytic_boundary import (
        AnalyticBoundary,
        analytic_boundaries,
        equivalent_damping_ratio,
    )
    from stickslip.analysis.critical import Crossing, lowest_onset
    from stickslip.analysis.cycles import Cycle, CycleSearch, cycle_exists, find_cycles
    from stickslip.analysis.design import DesignReport, design_foundation, stability_margin
    from stickslip.analysis.disturbance import SafeDisturbance, safe_disturbance
    from stickslip.analysis.dva import fitted_zeta_warning, resolve_dva
    from stickslip.analysis.frequency_response import (
        ResponseCurves,
        ResponsePeak,
        equivalent_damping,
        response_curves,
        response_peak,
    )
    from stickslip.analysis.optimise import best_seed, box_simplex, nelder_mead, ordered_bounds
    from stickslip.analysis.peak_minimiser import PeakMinimum, minimise_peak
    from stickslip.analysis.simulation import EngineOptions, SimulationResult, TimeHistory, simulate
    from stickslip.analysis.stability import (
        SteadySlidingStability,
        critical_weakening,
        steady_sliding_stability,
    )
    from stickslip.analysis.stability_tuning import StabilityTuning, optimal_foundation_stability
    from stickslip.analysis.stick_slip_tuning import StickSlipTuning, optimal_foundation_stick_slip
    from stickslip.analysis.theory import (
        FITTED_ZETA_RANGE,
        MAX_DESIGN_ZETA,
        MAX_TUNING_ZETA,
        check_fitted_zeta,
        critical_lambda_approx,
        critical_lambda_exact,
        critical_lambda_linear,
        equivalent_damping_fit,
        equivalent_damping_from_peak,
        nakano_boundary_residual,
        optimal_damping_ratio_fit,
        optimal_foundation_fit,
        optimal_mass_ratio_fit,
        optimal_stiffness_ratio_fit,
        peak_response_fit,
        stick_slip_amplitude_ratio,
        stick_slip_frequency_ratio,
        stick_slip_period,
        stick_slip_predicted,
    )
    from stickslip.analysis.verdict import (
        CERTIFIED_VERDICTS,
        STATUSES,
        VERDICTS,
        Mode,
        RunStatus,
        Verdict,
        status_flag_attributes,
        verdict_codes,
        verdict_flag_attributes,
    )
