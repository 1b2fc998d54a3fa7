"""stickslip: exact stick-slip simulation and dynamic-vibration-absorber tuning.

Implements and extends "Discussion of Stick-Slip Dynamics of 2DOF Sliding Systems Based on
Dynamic Vibration Absorbers Analysis" (equation and figure numbers refer to it).

The public API is flat: everything a user needs is imported from ``stickslip`` itself::

    from stickslip import Slider, elastic_foundation, optimal_foundation_fit, simulate

    result = simulate(elastic_foundation(0.1, optimal_foundation_fit(0.1)), Slider(15.0))
    result.verdict, result.period, result.plot()

The subpackages underneath (``model``, ``kernel``, ``analysis``, ``io``, ``sweep``, ``plot``,
``reproduction``, ``cli``, ``app``) are the implementation. Each subpackage's face (its
``__init__``) lists, in ``__all__``, the names it offers beyond the flat API; every other
module-level name, and the whole of ``kernel``, ``cli`` and ``app``, is private: it may change
between versions without a deprecation period. Names are loaded on first use, so
``import stickslip`` stays fast and pulls in neither numba, scipy, xarray nor matplotlib until
they are needed.
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
    "PhysicalFriction": "stickslip.model.physical",
    "foundation_to_dimensionless": "stickslip.model.physical",
    "foundation_to_physical": "stickslip.model.physical",
    "to_si": "stickslip.model.units",
    # model: friction laws and foundation choices
    "CoulombFriction": "stickslip.model.friction",
    "LinearFriction": "stickslip.model.friction",
    "StribeckFriction": "stickslip.model.friction",
    "TableFriction": "stickslip.model.friction",
    "parse_friction": "stickslip.model.friction_input",
    "read_friction_table": "stickslip.model.friction_input",
    "DvaSpec": "stickslip.model.dva",
    # analysis: one simulation and its verdict
    "simulate": "stickslip.analysis.simulation",
    # friction with memory (rate-and-state, LuGre): the smooth stiff engine
    "RateStateFriction": "stickslip.model.state_friction",
    "LuGreFriction": "stickslip.model.state_friction",
    "MemorySystem": "stickslip.model.state_friction",
    "SpeedSchedule": "stickslip.model.state_friction",
    "MemoryResult": "stickslip.analysis.memory.simulation",
    "simulate_memory": "stickslip.analysis.memory.simulation",
    "hopf_stiffness": "stickslip.analysis.memory.friction",
    "rice_ruina_critical_stiffness": "stickslip.analysis.memory.friction",
    "memory_stability": "stickslip.analysis.memory.stability",
    "MemoryStability": "stickslip.analysis.memory.stability",
    "find_memory_cycles": "stickslip.analysis.memory.cycle_search",
    # the contact itself: normal-load coupling, separation, complex eigenvalues, compliance
    "Machine": "stickslip.model.machine",
    "Contact": "stickslip.model.contact",
    "contact_system": "stickslip.analysis.contact.engine",
    "simulate_contact": "stickslip.analysis.contact.engine",
    "ContactRun": "stickslip.analysis.contact.engine",
    "find_contact_cycles": "stickslip.analysis.contact.cycles",
    "complex_eigenvalue_analysis": "stickslip.analysis.contact.eigenvalues",
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
    # io: datasets on disk
    "read_dataset": "stickslip.io.netcdf",
    "write_dataset": "stickslip.io.netcdf",
    "write_map_csv": "stickslip.io.csv",
    # sweep: maps, boundaries and basins over parameter or state space
    "Axis": "stickslip.sweep.grid",
    "occurrence_map": "stickslip.sweep.occurrence",
    "OccurrenceMap": "stickslip.sweep.occurrence",
    "MapConfig": "stickslip.sweep.map_config",
    "stick_slip_boundary": "stickslip.sweep.boundary",
    "BoundaryResult": "stickslip.sweep.boundary",
    "basin_stability": "stickslip.sweep.basin",
    "BasinResult": "stickslip.sweep.basin",
    "basin_map": "stickslip.sweep.basin_maps",
    "BasinMap": "stickslip.sweep.basin_maps",
    "ExecutionOptions": "stickslip.sweep.execution",
    "identify": "stickslip.analysis.identification.record_fit",
    "IdentificationResult": "stickslip.analysis.identification.result",
    "MeasuredRecord": "stickslip.analysis.identification.estimates",
    "read_record": "stickslip.io.record",
    "continue_cycles": "stickslip.analysis.continuation",
    "ContinuationResult": "stickslip.analysis.continuation",
    "hopf_weakenings": "stickslip.analysis.stability",
    "sample_box": "stickslip.sweep.basin",
    "equilibrium_state": "stickslip.sweep.basin",
    # plot: the common return type of every *_plot function
    "PlotResult": "stickslip.plot.figure",
    # reproduction of the paper
    "reproduce": "stickslip.reproduction.run",
}

__all__ = [
    "STARTUP_DESCRIPTION",
    "AnalyticBoundary",
    "Axis",
    "BasinMap",
    "BasinResult",
    "BoundaryResult",
    "Contact",
    "ContactRun",
    "ContinuationResult",
    "CoulombFriction",
    "Crossing",
    "Cycle",
    "CycleSearch",
    "DesignReport",
    "DvaSpec",
    "EngineOptions",
    "ExecutionOptions",
    "Foundation",
    "IdentificationResult",
    "InitialState",
    "LinearFriction",
    "LuGreFriction",
    "Machine",
    "MapConfig",
    "MeasuredRecord",
    "MemoryResult",
    "MemoryStability",
    "MemorySystem",
    "Mode",
    "OccurrenceMap",
    "PhysicalFoundation",
    "PhysicalFriction",
    "PhysicalSystem",
    "PlotResult",
    "RateStateFriction",
    "ResponseCurves",
    "ResponsePeak",
    "RunStatus",
    "SafeDisturbance",
    "SimulationResult",
    "Slider",
    "SpeedSchedule",
    "StabilityTuning",
    "SteadySlidingStability",
    "StickSlipTuning",
    "StribeckFriction",
    "Structure",
    "TableFriction",
    "TimeHistory",
    "TuningCurve",
    "TuningResult",
    "Verdict",
    "__version__",
    "analytic_boundaries",
    "basin_map",
    "basin_stability",
    "chain_structure",
    "complex_eigenvalue_analysis",
    "contact_system",
    "continue_cycles",
    "critical_lambda_approx",
    "critical_lambda_exact",
    "critical_lambda_linear",
    "critical_weakening",
    "cycle_exists",
    "design_foundation",
    "elastic_foundation",
    "equilibrium_state",
    "equivalent_damping",
    "equivalent_damping_fit",
    "find_contact_cycles",
    "find_cycles",
    "find_memory_cycles",
    "foundation_to_dimensionless",
    "foundation_to_physical",
    "frequency_response",
    "hopf_stiffness",
    "hopf_weakenings",
    "identify",
    "lowest_onset",
    "memory_stability",
    "occurrence_map",
    "optimal_foundation_exact",
    "optimal_foundation_fit",
    "optimal_foundation_stability",
    "optimal_foundation_stick_slip",
    "parse_friction",
    "peak_response_fit",
    "read_dataset",
    "read_friction_table",
    "read_record",
    "reproduce",
    "resolve_dva",
    "response_curves",
    "response_peak",
    "rice_ruina_critical_stiffness",
    "rigid_base",
    "safe_disturbance",
    "sample_box",
    "simulate",
    "simulate_contact",
    "simulate_memory",
    "stability_margin",
    "startup_state",
    "steady_sliding_stability",
    "stick_slip_amplitude_ratio",
    "stick_slip_boundary",
    "stick_slip_period",
    "to_si",
    "tune_foundation",
    "tuning_curve",
    "write_dataset",
    "write_map_csv",
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
    from stickslip.analysis.analytic_boundary import AnalyticBoundary, analytic_boundaries
    from stickslip.analysis.contact.cycles import find_contact_cycles
    from stickslip.analysis.contact.eigenvalues import complex_eigenvalue_analysis
    from stickslip.analysis.contact.engine import ContactRun, contact_system, simulate_contact
    from stickslip.analysis.continuation import ContinuationResult, continue_cycles
    from stickslip.analysis.critical import Crossing, lowest_onset
    from stickslip.analysis.cycles import Cycle, CycleSearch, cycle_exists, find_cycles
    from stickslip.analysis.design import DesignReport, design_foundation, stability_margin
    from stickslip.analysis.disturbance import SafeDisturbance, safe_disturbance
    from stickslip.analysis.dva import resolve_dva
    from stickslip.analysis.frequency_response import (
        ResponseCurves,
        ResponsePeak,
        equivalent_damping,
        frequency_response,
        response_curves,
        response_peak,
    )
    from stickslip.analysis.identification.estimates import MeasuredRecord
    from stickslip.analysis.identification.record_fit import identify
    from stickslip.analysis.identification.result import IdentificationResult
    from stickslip.analysis.memory.cycle_search import find_memory_cycles
    from stickslip.analysis.memory.friction import hopf_stiffness, rice_ruina_critical_stiffness
    from stickslip.analysis.memory.simulation import MemoryResult, simulate_memory
    from stickslip.analysis.memory.stability import MemoryStability, memory_stability
    from stickslip.analysis.simulation import EngineOptions, SimulationResult, TimeHistory, simulate
    from stickslip.analysis.stability import (
        SteadySlidingStability,
        critical_weakening,
        hopf_weakenings,
        steady_sliding_stability,
    )
    from stickslip.analysis.stability_tuning import StabilityTuning, optimal_foundation_stability
    from stickslip.analysis.stick_slip_tuning import StickSlipTuning, optimal_foundation_stick_slip
    from stickslip.analysis.theory import (
        critical_lambda_approx,
        critical_lambda_exact,
        critical_lambda_linear,
        equivalent_damping_fit,
        optimal_foundation_fit,
        peak_response_fit,
        stick_slip_amplitude_ratio,
        stick_slip_period,
    )
    from stickslip.analysis.verdict import Mode, RunStatus, Verdict
    from stickslip.io.csv import write_map_csv
    from stickslip.io.netcdf import read_dataset, write_dataset
    from stickslip.io.record import read_record
    from stickslip.model.contact import Contact
    from stickslip.model.dva import DvaSpec
    from stickslip.model.friction import CoulombFriction, LinearFriction, StribeckFriction, TableFriction
    from stickslip.model.friction_input import parse_friction, read_friction_table
    from stickslip.model.initial import STARTUP_DESCRIPTION, InitialState, startup_state
    from stickslip.model.machine import Machine
    from stickslip.model.parameters import Foundation, Slider
    from stickslip.model.physical import (
        PhysicalFoundation,
        PhysicalFriction,
        PhysicalSystem,
        foundation_to_dimensionless,
        foundation_to_physical,
    )
    from stickslip.model.state_friction import (
        LuGreFriction,
        MemorySystem,
        RateStateFriction,
        SpeedSchedule,
    )
    from stickslip.model.structure import Structure, chain_structure, elastic_foundation, rigid_base
    from stickslip.model.units import to_si
    from stickslip.plot.figure import PlotResult
    from stickslip.reproduction.run import reproduce
    from stickslip.sweep.basin import BasinResult, basin_stability, equilibrium_state, sample_box
    from stickslip.sweep.basin_maps import BasinMap, basin_map
    from stickslip.sweep.boundary import BoundaryResult, stick_slip_boundary
    from stickslip.sweep.execution import ExecutionOptions
    from stickslip.sweep.grid import Axis
    from stickslip.sweep.map_config import MapConfig
    from stickslip.sweep.occurrence import OccurrenceMap, occurrence_map
