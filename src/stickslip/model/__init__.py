"""Model layer: parameters, structures, physical units and initial conditions."""

from stickslip.model.friction import (
    CoulombFriction,
    FrictionLaw,
    LinearFriction,
    StribeckFriction,
    TableFriction,
    read_friction_table,
)
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
    "CoulombFriction",
    "Foundation",
    "FrictionLaw",
    "InitialState",
    "LinearFriction",
    "PhysicalFoundation",
    "PhysicalSystem",
    "Slider",
    "StribeckFriction",
    "Structure",
    "TableFriction",
    "chain_structure",
    "elastic_foundation",
    "foundation_to_dimensionless",
    "foundation_to_physical",
    "read_friction_table",
    "rigid_base",
    "startup_state",
]
