"""The contact itself: normal-load coupling, separation, complex eigenvalues, tangential compliance.

The exact piecewise-affine contact engine (lift-off, re-contact, a Jenkins element), its
periodic attractors, boundaries and continuation over speed or load, the design report, and
the complex-eigenvalue analysis of steady sliding (root loci, stability maps, the Hoffmann
minimal model of brake squeal). Names load on first use (PEP 562).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from stickslip._lazy import lazy_exports

#: Public name -> module that defines it.
_EXPORTS: dict[str, str] = {
    "ContactEvent": "stickslip.analysis.contact.engine",
    "ContactRun": "stickslip.analysis.contact.engine",
    "ContactSystem": "stickslip.analysis.contact.engine",
    "contact_system": "stickslip.analysis.contact.engine",
    "simulate_contact": "stickslip.analysis.contact.engine",
    "ContactCycle": "stickslip.analysis.contact.cycles",
    "ContactCycleSearch": "stickslip.analysis.contact.cycles",
    "find_contact_cycles": "stickslip.analysis.contact.cycles",
    "ContactBoundary": "stickslip.analysis.contact.boundary",
    "ContactCrossing": "stickslip.analysis.contact.boundary",
    "contact_boundary": "stickslip.analysis.contact.boundary",
    "ContactContinuation": "stickslip.analysis.contact.continuation",
    "continue_contact": "stickslip.analysis.contact.continuation",
    "ContactDesign": "stickslip.analysis.contact.design",
    "design_contact": "stickslip.analysis.contact.design",
    "run_points": "stickslip.analysis.contact.pool",
    "StabilityResult": "stickslip.analysis.contact.eigenvalues",
    "complex_eigenvalue_analysis": "stickslip.analysis.contact.eigenvalues",
    "OperatingRanges": "stickslip.analysis.contact.eigenvalue_maps",
    "RootLocus": "stickslip.analysis.contact.eigenvalue_maps",
    "StabilityMap": "stickslip.analysis.contact.eigenvalue_maps",
    "operating_ranges": "stickslip.analysis.contact.eigenvalue_maps",
    "root_locus": "stickslip.analysis.contact.eigenvalue_maps",
    "stability_map": "stickslip.analysis.contact.eigenvalue_maps",
    "CriticalFriction": "stickslip.analysis.contact.critical_coefficient",
    "FrictionCoupledSystem": "stickslip.analysis.contact.friction_coupling",
    "coupled_system": "stickslip.analysis.contact.friction_coupling",
    "critical_friction": "stickslip.analysis.contact.critical_coefficient",
    "hoffmann_critical_mu": "stickslip.analysis.contact.squeal_minimal_model",
    "hoffmann_stiffness": "stickslip.analysis.contact.squeal_minimal_model",
}

__all__ = [
    "ContactBoundary",
    "ContactContinuation",
    "ContactCrossing",
    "ContactCycle",
    "ContactCycleSearch",
    "ContactDesign",
    "ContactEvent",
    "ContactRun",
    "ContactSystem",
    "CriticalFriction",
    "FrictionCoupledSystem",
    "OperatingRanges",
    "RootLocus",
    "StabilityMap",
    "StabilityResult",
    "complex_eigenvalue_analysis",
    "contact_boundary",
    "contact_system",
    "continue_contact",
    "coupled_system",
    "critical_friction",
    "design_contact",
    "find_contact_cycles",
    "hoffmann_critical_mu",
    "hoffmann_stiffness",
    "operating_ranges",
    "root_locus",
    "run_points",
    "simulate_contact",
    "stability_map",
]

__getattr__, __dir__ = lazy_exports(__name__, globals(), _EXPORTS)


if TYPE_CHECKING:  # pragma: no cover - for type checkers and IDEs only
    from stickslip.analysis.contact.boundary import (
        ContactBoundary,
        ContactCrossing,
        contact_boundary,
    )
    from stickslip.analysis.contact.continuation import (
        ContactContinuation,
        continue_contact,
    )
    from stickslip.analysis.contact.critical_coefficient import CriticalFriction, critical_friction
    from stickslip.analysis.contact.cycles import (
        ContactCycle,
        ContactCycleSearch,
        find_contact_cycles,
    )
    from stickslip.analysis.contact.design import (
        ContactDesign,
        design_contact,
    )
    from stickslip.analysis.contact.eigenvalue_maps import (
        OperatingRanges,
        RootLocus,
        StabilityMap,
        operating_ranges,
        root_locus,
        stability_map,
    )
    from stickslip.analysis.contact.eigenvalues import (
        StabilityResult,
        complex_eigenvalue_analysis,
    )
    from stickslip.analysis.contact.engine import (
        ContactEvent,
        ContactRun,
        ContactSystem,
        contact_system,
        simulate_contact,
    )
    from stickslip.analysis.contact.friction_coupling import FrictionCoupledSystem, coupled_system
    from stickslip.analysis.contact.pool import (
        run_points,
    )
    from stickslip.analysis.contact.squeal_minimal_model import (
        hoffmann_critical_mu,
        hoffmann_stiffness,
    )
