"""Friction with memory: rate-and-state and LuGre sliders (runs, stability, cycles, design).

The steady sliding of a slider whose friction has an internal state, its linear stability
(Hopf stiffness, Rice and Ruina's critical stiffness), runs of the stiff engine, periodic orbits
by shooting, their continuation in the drive speed, and the design report. Names load on first
use (PEP 562).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from stickslip._lazy import lazy_exports

#: Public name -> module that defines it.
_EXPORTS: dict[str, str] = {
    "MemoryResult": "stickslip.analysis.memory.simulation",
    "simulate_memory": "stickslip.analysis.memory.simulation",
    "MemoryStability": "stickslip.analysis.memory.stability",
    "memory_stability": "stickslip.analysis.memory.stability",
    "rice_ruina_critical_speed": "stickslip.analysis.memory.stability",
    "SteadySliding": "stickslip.analysis.memory.friction",
    "steady_sliding": "stickslip.analysis.memory.friction",
    "hopf_stiffness": "stickslip.analysis.memory.friction",
    "rice_ruina_critical_stiffness": "stickslip.analysis.memory.friction",
    "PeriodicOrbit": "stickslip.analysis.memory.cycles",
    "shoot_cycle": "stickslip.analysis.memory.cycles",
    "MemoryCycle": "stickslip.analysis.memory.cycle_search",
    "MemoryCycleSearch": "stickslip.analysis.memory.cycle_search",
    "find_memory_cycles": "stickslip.analysis.memory.cycle_search",
    "MemoryContinuation": "stickslip.analysis.memory.continuation",
    "continue_memory_orbits": "stickslip.analysis.memory.continuation",
    "MemoryDesign": "stickslip.analysis.memory.design",
    "memory_design": "stickslip.analysis.memory.design",
}

__all__ = [
    "MemoryContinuation",
    "MemoryCycle",
    "MemoryCycleSearch",
    "MemoryDesign",
    "MemoryResult",
    "MemoryStability",
    "PeriodicOrbit",
    "SteadySliding",
    "continue_memory_orbits",
    "find_memory_cycles",
    "hopf_stiffness",
    "memory_design",
    "memory_stability",
    "rice_ruina_critical_speed",
    "rice_ruina_critical_stiffness",
    "shoot_cycle",
    "simulate_memory",
    "steady_sliding",
]

__getattr__, __dir__ = lazy_exports(__name__, globals(), _EXPORTS)


if TYPE_CHECKING:  # pragma: no cover - for type checkers and IDEs only
    from stickslip.analysis.memory.continuation import (
        MemoryContinuation,
        continue_memory_orbits,
    )
    from stickslip.analysis.memory.cycle_search import (
        MemoryCycle,
        MemoryCycleSearch,
        find_memory_cycles,
    )
    from stickslip.analysis.memory.cycles import (
        PeriodicOrbit,
        shoot_cycle,
    )
    from stickslip.analysis.memory.design import (
        MemoryDesign,
        memory_design,
    )
    from stickslip.analysis.memory.friction import (
        SteadySliding,
        hopf_stiffness,
        rice_ruina_critical_stiffness,
        steady_sliding,
    )
    from stickslip.analysis.memory.simulation import (
        MemoryResult,
        simulate_memory,
    )
    from stickslip.analysis.memory.stability import (
        MemoryStability,
        memory_stability,
        rice_ruina_critical_speed,
    )
