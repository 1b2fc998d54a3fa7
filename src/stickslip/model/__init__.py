"""Model layer: parameters, structures, physical units and initial conditions."""

from stickslip.model.initial import STARTUP_DESCRIPTION, InitialState, startup_state
from stickslip.model.parameters import Foundation, Slider
from stickslip.model.physical import (
    PhysicalFoundation,
    PhysicalSystem,
    foundation_to_dimensionless,
    foundation_to_physical,
)
from stickslip.model.structure import Structure, chain_structure, elastic_foundation, rigid_base

__all__ = [
    "STARTUP_DESCRIPTION",
    "Foundation",
    "InitialState",
    "PhysicalFoundation",
    "PhysicalSystem",
    "Slider",
    "Structure",
    "chain_structure",
    "elastic_foundation",
    "foundation_to_dimensionless",
    "foundation_to_physical",
    "rigid_base",
    "startup_state",
]
