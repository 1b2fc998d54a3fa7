"""The periodic motions a machine with friction with memory settles on, from many starts.

Each start is a run of :func:`~stickslip.analysis.memory.simulation.simulate_memory`: steady
sliding at the drive speed with the contact kicked to move at ``-F V`` (``F`` in
:data:`DEFAULT_KICKS`: ``-1`` starts stuck to the drive, large ``F`` throws it forward). A run
that settles on a periodic orbit has it proven by Newton shooting on the section ``q_c' = 0``
with its Floquet multipliers (:func:`~stickslip.analysis.memory.cycles.shoot_cycle`); the
distinct orbits are listed (periods within 1e-6, amplitudes within 1e-5 relative are one), with
the kicks that reach each, and so are the starts that end in steady sliding.

The search finds the stable orbits the starts reach. Unstable ones (the saddle cycle between
the basins of steady sliding and of stick-slip) are not searched with these laws: a run never
stays on them, and shooting from near them falls onto steady sliding or the stable cycle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from stickslip.analysis.memory.simulation import MemoryResult, simulate_memory
from stickslip.analysis.verdict import Verdict
from stickslip.model.state_friction import MemorySystem

#: Kicks ``F`` of the starts (the contact starts at ``-F V``): stuck, slowed, thrown forward.
DEFAULT_KICKS = (-1.0, -0.75, -0.5, -0.25, 0.25, 0.5, 1.0, 2.0, 4.0)
#: Relative tolerances under which two orbits are the same.
SAME_PERIOD = 1e-6
SAME_AMPLITUDE = 1e-5


@dataclass
class MemoryCycle:
    """One periodic motion: a run's verdict and orbit, and the kicks that reach it."""

    run: MemoryResult = field(repr=False)
    kicks: list[float]

    @property
    def kind(self) -> str:
        """``stick-slip`` or ``slip-oscillation``."""
        return self.run.verdict.value

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (SI)."""
        orbit = self.run.orbit
        assert orbit is not None
        return {"kind": self.kind, "period_s": self.run.period, "amplitude_m": self.run.amplitude,
                "min_slip_speed_m_s": self.run.min_slip_speed,
                "stick_ratio": None if math.isnan(self.run.stick_ratio) else self.run.stick_ratio,
                "stable": orbit.stable,
                "floquet_multipliers": [[float(m.real), float(m.imag)] for m in orbit.multipliers],
                "multiplier_moduli": [float(abs(m)) for m in orbit.multipliers],
                "trivial_multiplier": [float(orbit.trivial_multiplier.real),
                                       float(orbit.trivial_multiplier.imag)],
                "shooting_residual": orbit.residual, "kicks": self.kicks}


@dataclass
class MemoryCycleSearch:
    """Result of :func:`find_memory_cycles`."""

    system: MemorySystem = field(repr=False)
    cycles: list[MemoryCycle]
    steady_kicks: list[float]
    undetermined: dict[float, str]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``cycles``, the kicks that end in steady sliding, the undetermined ones."""
        return {"cycles": [c.to_dict() for c in self.cycles], "n_cycles": len(self.cycles),
                "steady_sliding_kicks": self.steady_kicks,
                "undetermined_kicks": {str(k): why for k, why in self.undetermined.items()},
                "kicks": sorted([*self.steady_kicks, *self.undetermined,
                                 *(k for c in self.cycles for k in c.kicks)]),
                "unstable_cycles": "not searched (friction with memory: stable cycles only)",
                "friction": self.system.friction.to_dict(), "machine": self.system.to_dict()}

    def summary(self) -> str:
        """A few lines for the terminal."""
        lines = [f"cycles      {self.system.n_dof} DOF, {self.system.friction.describe()}"]
        if not self.cycles:
            lines.append("none found  no start settled on a periodic motion")
        for i, c in enumerate(self.cycles, start=1):
            d = c.to_dict()
            mods = ", ".join(f"{m:.3g}" for m in d["multiplier_moduli"])
            lines.append(f"cycle {i}     {d['kind']}: period {d['period_s']:.8g} s, amplitude "
                         f"{d['amplitude_m']:.6g} m, {'stable' if d['stable'] else 'UNSTABLE'} "
                         f"(|Floquet multipliers| {mods}; shooting residual "
                         f"{d['shooting_residual']:.1e}); reached from kicks "
                         + ", ".join(f"{k:g}" for k in c.kicks))
        if self.steady_kicks:
            lines.append("steady      kicks " + ", ".join(f"{k:g}" for k in self.steady_kicks)
                         + " end in steady sliding")
        for k, why in self.undetermined.items():
            lines.append(f"undecided   kick {k:g}: {why}")
        lines.append("search      stable periodic motions reached from the kicks; unstable cycles "
                     "are not searched with friction with memory")
        return "\n".join(lines)


def find_memory_cycles(system: MemorySystem, *, kicks: tuple[float, ...] = DEFAULT_KICKS,
                       t_max: float | None = None) -> MemoryCycleSearch:
    """The periodic motions that runs from kicked steady sliding settle on (module notes).

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and a constant drive speed (SI; not the quasi-static slider: its
        contact has no velocity to kick).
    kicks : tuple of float
        The kicks ``F``: each run starts with the contact moving at ``-F V``.
    t_max : float, optional
        Horizon of each run, s (default that of :func:`simulate_memory`).

    Returns
    -------
    MemoryCycleSearch
        The distinct orbits with the kicks that reach them, and the other outcomes.
    """
    if system.quasi_static:
        raise ValueError("the quasi-static slider (m = 0) cannot be kicked: cycles need the "
                         "slider's mass")
    cycles: list[MemoryCycle] = []
    steady: list[float] = []
    undetermined: dict[float, str] = {}
    for kick in kicks:
        run = simulate_memory(system, kick=float(kick), t_max=t_max)
        if run.verdict is Verdict.STEADY_SLIDING:
            steady.append(float(kick))
        elif run.orbit is None:
            undetermined[float(kick)] = run.reason
        else:
            same = [c for c in cycles
                    if abs(c.run.period - run.period) <= SAME_PERIOD * run.period
                    and abs(c.run.amplitude - run.amplitude) <= SAME_AMPLITUDE * max(run.amplitude, 1e-300)]
            if same:
                same[0].kicks.append(float(kick))
            else:
                cycles.append(MemoryCycle(run, [float(kick)]))
    cycles.sort(key=lambda c: c.run.amplitude)
    return MemoryCycleSearch(system, cycles, steady, undetermined)


__all__ = ["DEFAULT_KICKS", "MemoryCycle", "MemoryCycleSearch", "find_memory_cycles"]
