"""stickslip: exact stick-slip simulation and dynamic-vibration-absorber tuning.

Implements and extends "Discussion of Stick-Slip Dynamics of 2DOF Sliding Systems Based on
Dynamic Vibration Absorbers Analysis" (equation and figure numbers refer to it).
"""

from stickslip.analysis.simulation import (
    Mode,
    RunStatus,
    SimulationResult,
    TimeHistory,
    Verdict,
    simulate,
)
from stickslip.model import (
    STARTUP_DESCRIPTION,
    Foundation,
    InitialState,
    PhysicalFoundation,
    PhysicalSystem,
    Slider,
    Structure,
    chain_structure,
    elastic_foundation,
    rigid_base,
    startup_state,
)

__version__ = "0.1.0"

__all__ = [
    "STARTUP_DESCRIPTION",
    "Foundation",
    "InitialState",
    "Mode",
    "PhysicalFoundation",
    "PhysicalSystem",
    "RunStatus",
    "SimulationResult",
    "Slider",
    "Structure",
    "TimeHistory",
    "Verdict",
    "__version__",
    "chain_structure",
    "elastic_foundation",
    "rigid_base",
    "simulate",
    "startup_state",
]
