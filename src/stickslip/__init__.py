"""stickslip: exact stick-slip simulation and dynamic-vibration-absorber tuning.

Implements and extends "Discussion of Stick-Slip Dynamics of 2DOF Sliding Systems Based on
Dynamic Vibration Absorbers Analysis" (equation and figure numbers refer to it).

The public API is flat: everything a user needs is imported from ``stickslip`` itself::

    from stickslip import Slider, elastic_foundation, optimal_foundation_fit, simulate

    result = simulate(elastic_foundation(0.1, optimal_foundation_fit(0.1)), Slider(15.0))
    result.verdict, result.period, result.plot()

The subpackages underneath (``model``, ``kernel``, ``analysis``, ``io``, ``sweep``, ``plot``,
``reproduction``, ``cli``, ``app``) are the implementation; their layout may change between
versions. Names are loaded on first use, so ``import stickslip`` stays fast and pulls in
neither numba, scipy, xarray nor matplotlib until they are needed.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from stickslip._lazy import lazy_exports


def _installed_version() -> str:
    """The version in the installed package metadata (pyproject.toml is its one source)."""
    from importlib import metadata

    try:
        return metadata.version("stickslip")
    except metadata.PackageNotFoundError:  # pragma: no cover - running from an uninstalled tree
        return "0+unknown"

#: Public name -> module that defines it.
_EXPORTS: dict[str, str] = {
    # model: parameters, structures, initial states, physical units
    "Slider": "stickslip.model.parameters",
    "Foundation": "stickslip.model.parameters",
    "Structure": "stickslip.model.structure",
    "chain_structure": "stickslip.model.structure",
    "rigid_base": "stickslip.model.structure",
    "elastic_foundation": "stickslip.model.structure",
    "InitialState": "stickslip.model.initial",
    "startup_state": "stickslip.model.initial",
    "STARTUP_DESCRIPTION": "stickslip.model.initial",
    "PhysicalSystem": "stickslip.model.physical",
    "PhysicalFoundation": "stickslip.model.physical",
    "to_si": "stickslip.model.units",
    # analysis: one simulation and its verdict
    "simulate": "stickslip.analysis.simulation",
    "EngineOptions": "stickslip.analysis.simulation",
    "SimulationResult": "stickslip.analysis.simulation",
    "TimeHistory": "stickslip.analysis.simulation",
    "Verdict": "stickslip.analysis.verdict",
    "RunStatus": "stickslip.analysis.verdict",
    "Mode": "stickslip.analysis.verdict",
    # analysis: closed forms of the paper
    "optimal_foundation_fit": "stickslip.analysis.theory",
    "peak_response_fit": "stickslip.analysis.theory",
    "equivalent_damping_fit": "stickslip.analysis.theory",
    "critical_lambda_exact": "stickslip.analysis.theory",
    "critical_lambda_approx": "stickslip.analysis.theory",
    "stick_slip_period": "stickslip.analysis.theory",
    "stick_slip_amplitude_ratio": "stickslip.analysis.theory",
    "analytic_boundaries": "stickslip.analysis.analytic_boundary",
    # analysis: absorber frequency response and tuning
    "frequency_response": "stickslip.analysis.frequency_response",
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
    # analysis: critical lambda, foundation choices, design procedure
    "lowest_onset": "stickslip.analysis.critical",
    "Crossing": "stickslip.analysis.critical",
    "DvaSpec": "stickslip.model.dva",
    "design_foundation": "stickslip.analysis.design",
    "DesignReport": "stickslip.analysis.design",
    # sweep: maps and boundaries over parameter space
    "Axis": "stickslip.sweep.grid",
    "occurrence_map": "stickslip.sweep.occurrence",
    "OccurrenceMap": "stickslip.sweep.occurrence",
    "MapConfig": "stickslip.sweep.occurrence",
    "stick_slip_boundary": "stickslip.sweep.boundary",
    "BoundaryResult": "stickslip.sweep.boundary",
    # plot: the common return type of every *_plot function
    "PlotResult": "stickslip.plot.figure",
    # reproduction of the paper
    "reproduce": "stickslip.reproduction.run",
}

__all__ = [
    "STARTUP_DESCRIPTION",
    "Axis",
    "BoundaryResult",
    "Crossing",
    "DesignReport",
    "DvaSpec",
    "EngineOptions",
    "Foundation",
    "InitialState",
    "MapConfig",
    "Mode",
    "OccurrenceMap",
    "PhysicalFoundation",
    "PhysicalSystem",
    "PlotResult",
    "ResponseCurves",
    "ResponsePeak",
    "RunStatus",
    "SimulationResult",
    "Slider",
    "StickSlipTuning",
    "Structure",
    "TimeHistory",
    "TuningCurve",
    "TuningResult",
    "Verdict",
    "__version__",
    "analytic_boundaries",
    "chain_structure",
    "critical_lambda_approx",
    "critical_lambda_exact",
    "design_foundation",
    "elastic_foundation",
    "equivalent_damping",
    "equivalent_damping_fit",
    "frequency_response",
    "lowest_onset",
    "occurrence_map",
    "optimal_foundation_exact",
    "optimal_foundation_fit",
    "optimal_foundation_stick_slip",
    "peak_response_fit",
    "reproduce",
    "response_curves",
    "response_peak",
    "rigid_base",
    "simulate",
    "startup_state",
    "stick_slip_amplitude_ratio",
    "stick_slip_boundary",
    "stick_slip_period",
    "to_si",
    "tune_foundation",
    "tuning_curve",
]


_getattr_export, __dir__ = lazy_exports(__name__, globals(), _EXPORTS)


def __getattr__(name: str) -> Any:
    """Import a public name from its module on first use (PEP 562)."""
    if name == "__version__":
        version = globals()["__version__"] = _installed_version()
        return version
    return _getattr_export(name)


if TYPE_CHECKING:  # pragma: no cover - for type checkers and IDEs only
    __version__: str
    from stickslip.analysis.absorber_tuning import (
        TuningCurve,
        TuningResult,
        optimal_foundation_exact,
        tune_foundation,
        tuning_curve,
    )
    from stickslip.analysis.analytic_boundary import analytic_boundaries
    from stickslip.analysis.critical import Crossing, lowest_onset
    from stickslip.analysis.design import DesignReport, design_foundation
    from stickslip.analysis.frequency_response import (
        ResponseCurves,
        ResponsePeak,
        equivalent_damping,
        frequency_response,
        response_curves,
        response_peak,
    )
    from stickslip.analysis.simulation import EngineOptions, SimulationResult, TimeHistory, simulate
    from stickslip.analysis.stick_slip_tuning import StickSlipTuning, optimal_foundation_stick_slip
    from stickslip.analysis.theory import (
        critical_lambda_approx,
        critical_lambda_exact,
        equivalent_damping_fit,
        optimal_foundation_fit,
        peak_response_fit,
        stick_slip_amplitude_ratio,
        stick_slip_period,
    )
    from stickslip.analysis.verdict import Mode, RunStatus, Verdict
    from stickslip.model.dva import DvaSpec
    from stickslip.model.initial import STARTUP_DESCRIPTION, InitialState, startup_state
    from stickslip.model.parameters import Foundation, Slider
    from stickslip.model.physical import PhysicalFoundation, PhysicalSystem
    from stickslip.model.structure import Structure, chain_structure, elastic_foundation, rigid_base
    from stickslip.model.units import to_si
    from stickslip.plot.figure import PlotResult
    from stickslip.reproduction.run import reproduce
    from stickslip.sweep.boundary import BoundaryResult, stick_slip_boundary
    from stickslip.sweep.grid import Axis
    from stickslip.sweep.occurrence import MapConfig, OccurrenceMap, occurrence_map
