"""``design`` for a machine whose friction has memory: verdicts, critical speeds and loads.

The paper's design procedure (its Fig. 16) is built on the Coulomb law: closed-form critical
values (Eq. 36) and a foundation tuned by Eqs. 28-30. With a law with memory (rate-and-state,
LuGre) none of those closed forms holds, so the design answers with the machine's own law:

- **steady sliding**: the linearisation with the state variable
  (:func:`~stickslip.analysis.memory.stability.memory_stability`): its verdict, the Hopf
  stiffness, and the critical drive speeds where the growth rate changes sign, scanned over
  :data:`~stickslip.analysis.memory.stability.SPEED_DECADES` decades either side of ``V``;
- **critical loads**: the same scan along the normal load ``N`` at the operating speed
  (:func:`~stickslip.analysis.memory.stability.critical_loads`);
- **two runs** at the operating point (:func:`~stickslip.analysis.memory.simulation.simulate_memory`):
  one from the start stuck to the drive (kick ``F = -1``: the slider moves with the drive
  while its position and state are those of steady sliding, the analogue of the paper's
  start-up, from stick) and one from steady sliding nudged off it (kick :data:`NUDGE`). A
  stable steady sliding with a stick-slip start-up is bistable: a large disturbance starts
  stick-slip, a small one dies out. The quasi-static slider (``m = 0``) has no velocity to
  kick: its one run starts at steady sliding.

A foundation or absorber in the machine file is part of the structure, so everything above
is the machine *with* it; the foundation the paper tunes (Eqs. 28-30) is not proposed here,
because its tuning assumes Coulomb friction (the report says so).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from stickslip.analysis.memory.simulation import MemoryResult, simulate_memory
from stickslip.analysis.memory.stability import (
    SPEED_DECADES,
    SPEED_POINTS,
    MemoryStability,
    critical_loads,
    memory_stability,
)
from stickslip.model.state_friction import MemorySystem

#: The kick of the start-up run: stuck to the drive (slip speed 0), for every law. Rate-and-state
#: friction starts there too: the engine carries the slip speed itself, so the creep of a stuck
#: slider far below the round-off of ``V`` is resolved (:mod:`stickslip.kernel.stiff_system`).
STARTUP_KICK = -1.0
#: The kick of the run from near steady sliding: the contact starts moving at ``-NUDGE V``,
#: against the drive (slip speed ``(1 + NUDGE) V``; :func:`initial_state`).
NUDGE = 0.01

#: The sentence the report gives instead of a tuned foundation.
NO_FOUNDATION = ("the foundation of the paper's procedure (Eqs. 28-30) is tuned for the Coulomb "
                 "law and is not proposed for a friction law with memory; put a candidate in the "
                 "machine file (m_a, k_a, c_a or an [absorber]) and run design again to assess it "
                 "with the machine's own law")


@dataclass(frozen=True)
class MemoryDesign:
    """The design report of a machine with a friction law with memory (module notes).

    Attributes
    ----------
    system : MemorySystem
        The machine (SI).
    stability : MemoryStability
        Steady sliding at the operating speed, with the critical stiffness and speeds.
    critical_loads, unstable_loads : list
        Normal loads (N) where steady sliding at the operating speed changes stability, and the
        load ranges where it is unstable, over the scanned decades.
    startup, nudged : MemoryResult or None
        The runs from the start stuck to the drive and from steady sliding nudged off it
        (None for the quasi-static slider's start-up, which has no velocity to kick).
    """

    system: MemorySystem = field(repr=False)
    stability: MemoryStability = field(repr=False)
    critical_loads: list[float]
    unstable_loads: list[tuple[float, float]]
    startup: MemoryResult | None = field(repr=False)
    nudged: MemoryResult = field(repr=False)

    @property
    def verdict(self) -> str:
        """The start-up's verdict (``stick-slip``, ``steady-sliding``, ...), or the nudged run's
        where the start-up's is undetermined (or there is none)."""
        for run in (self.startup, self.nudged):
            if run is not None and run.verdict.value != "undetermined":
                return run.verdict.value
        return "undetermined"

    @property
    def bistable(self) -> bool:
        """True when the two runs end apart: steady sliding from a nudge, a cycle from stick."""
        if self.startup is None:
            return False
        verdicts = {self.startup.verdict.value, self.nudged.verdict.value}
        return "steady-sliding" in verdicts and bool(
            verdicts & {"stick-slip", "slip-oscillation"})

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready report (SI)."""
        def run(r: MemoryResult | None) -> dict[str, Any] | None:
            if r is None:
                return None
            d = r.to_dict()
            return {key: d[key] for key in ("verdict", "certificate", "status_message",
                                            "period_s", "amplitude_m", "min_slip_speed_m_s",
                                            "stick_ratio", "initial_condition", "t_end_s")}

        w = self.system.load
        spread = 10.0 ** SPEED_DECADES
        return {
            "friction_law": self.system.friction.to_dict()["law"],
            "friction": self.system.friction.describe(),
            "speed_m_per_s": self.stability.speed,
            "load_N": w,
            "verdict": self.verdict,
            "bistable": self.bistable,
            "startup": run(self.startup),
            "nudged": run(self.nudged),
            "stability": self.stability.to_dict(),
            "critical_loads_N": self.critical_loads,
            "unstable_loads_N": [list(r) for r in self.unstable_loads],
            "load_grid_N": [w / spread, w * spread, SPEED_POINTS],
            "foundation": NO_FOUNDATION,
        }

    def summary(self) -> str:
        """A few lines for the terminal."""
        p = self.to_dict()
        lines = [f"friction    {p['friction']}",
                 f"operating   V = {p['speed_m_per_s']:.6g} m/s, N = {p['load_N']:.6g} N"]
        still = "steady" if self.system.quasi_static else "nudged"  # its one run is not kicked
        for key, label in (("startup", "start-up"), ("nudged", still)):
            r = p[key]
            if r is None:
                lines.append(f"{label:11} - (the quasi-static slider has no velocity to kick)")
                continue
            cycle = ("" if r["period_s"] is None else
                     f", period {r['period_s']:.6g} s, amplitude {r['amplitude_m']:.6g} m")
            why = "" if r["verdict"] != "undetermined" else f" ({r['status_message']})"
            lines.append(f"{label:11} {r['verdict']}{cycle}{why}; from {r['initial_condition']}")
        if self.bistable:
            lines.append("            bistable: steady sliding survives small disturbances, a "
                         "start from stick ends in a cycle")
        lines += self.stability.summary().splitlines()
        lo, hi, _ = p["load_grid_N"]
        loads = ", ".join(f"{w:.8g}" for w in self.critical_loads)
        ranges = ", ".join(f"{a:.4g} to {b:.4g}" for a, b in self.unstable_loads)
        loads, ranges = (f"{text} N" if text else "none" for text in (loads, ranges))
        lines.append(f"critical N  {loads} at {p['speed_m_per_s']:.6g} m/s "
                     f"(scan {lo:.3g} to {hi:.3g} N)")
        lines.append(f"unstable N  {ranges}")
        lines.append(f"foundation  {NO_FOUNDATION}")
        return "\n".join(lines)


def memory_design(system: MemorySystem, *, t_max: float | None = None) -> MemoryDesign:
    """Verdicts, critical speeds and loads of a machine with a friction law with memory.

    Parameters
    ----------
    system : MemorySystem
        Structure, load, law and drive speed (SI).
    t_max : float, optional
        Length of each run, s (default
        :func:`~stickslip.analysis.memory.simulation.default_horizon`).

    Returns
    -------
    MemoryDesign
        The runs from stick and from near steady sliding, the linear verdict with the
        critical stiffness and speeds, and the critical loads.
    """
    stability = memory_stability(system)
    spread = 10.0 ** SPEED_DECADES
    loads, unstable = critical_loads(system, stability.speed, system.load / spread,
                                     system.load * spread)
    startup = (None if system.quasi_static
               else simulate_memory(system, t_max=t_max, kick=STARTUP_KICK))
    nudged = simulate_memory(system, t_max=t_max, kick=0.0 if system.quasi_static else NUDGE)
    if not all(math.isfinite(w) for w in loads):
        raise ValueError("a critical load is not finite")
    return MemoryDesign(system, stability, loads, unstable, startup, nudged)
