"""Model layer: parameters, structures, friction laws, foundation choices, units, initial states.

Names load on first use (PEP 562), so that importing one light module of this layer (for
example :mod:`stickslip.model.units` for the command line's help text) does not import numpy.
Every name of ``__all__`` is public, the rest is private.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from stickslip._lazy import lazy_exports

_EXPORTS: dict[str, str] = {
    "STARTUP_DESCRIPTION": "stickslip.model.initial",
    "InitialState": "stickslip.model.initial",
    "startup_state": "stickslip.model.initial",
    "CoulombFriction": "stickslip.model.friction",
    "FrictionLaw": "stickslip.model.friction",
    "LinearFriction": "stickslip.model.friction",
    "StribeckFriction": "stickslip.model.friction",
    "TableFriction": "stickslip.model.friction",
    "read_friction_table": "stickslip.model.friction_input",
    "parse_friction": "stickslip.model.friction_input",
    "FRICTION_SYNTAX": "stickslip.model.friction_input",
    "DvaSpec": "stickslip.model.dva",
    "DVA_SYNTAX": "stickslip.model.dva",
    "PhysicalFriction": "stickslip.model.physical",
    "physical_friction_from_config": "stickslip.model.physical",
    "Foundation": "stickslip.model.parameters",
    "Slider": "stickslip.model.parameters",
    "PhysicalFoundation": "stickslip.model.physical",
    "PhysicalSystem": "stickslip.model.physical",
    "foundation_to_dimensionless": "stickslip.model.physical",
    "foundation_to_physical": "stickslip.model.physical",
    "Structure": "stickslip.model.structure",
    "chain_structure": "stickslip.model.structure",
    "elastic_foundation": "stickslip.model.structure",
    "rigid_base": "stickslip.model.structure",
    "to_si": "stickslip.model.units",
}

__all__ = [
    "DVA_SYNTAX",
    "FRICTION_SYNTAX",
    "STARTUP_DESCRIPTION",
    "CoulombFriction",
    "DvaSpec",
    "Foundation",
    "FrictionLaw",
    "InitialState",
    "LinearFriction",
    "PhysicalFoundation",
    "PhysicalFriction",
    "PhysicalSystem",
    "Slider",
    "StribeckFriction",
    "Structure",
    "TableFriction",
    "chain_structure",
    "elastic_foundation",
    "foundation_to_dimensionless",
    "foundation_to_physical",
    "parse_friction",
    "physical_friction_from_config",
    "read_friction_table",
    "rigid_base",
    "startup_state",
    "to_si",
]


__getattr__, __dir__ = lazy_exports(__name__, globals(), _EXPORTS)


if TYPE_CHECKING:  # pragma: no cover
    from stickslip.model.dva import DVA_SYNTAX, DvaSpec
    from stickslip.model.friction import (
        CoulombFriction,
        FrictionLaw,
        LinearFriction,
        StribeckFriction,
        TableFriction,
    )
    from stickslip.model.friction_input import FRICTION_SYNTAX, parse_friction, read_friction_table
    from stickslip.model.initial import STARTUP_DESCRIPTION, InitialState, startup_state
    from stickslip.model.parameters import Foundation, Slider
    from stickslip.model.physical import (
        PhysicalFoundation,
        PhysicalFriction,
        PhysicalSystem,
        foundation_to_dimensionless,
        foundation_to_physical,
        physical_friction_from_config,
    )
    from stickslip.model.structure import Structure, chain_structure, elastic_foundation, rigid_base
    from stickslip.model.units import to_si
