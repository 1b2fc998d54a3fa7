"""Basin stability of a machine with friction with memory: a verdict for each disturbed start.

Each start is steady sliding at the drive speed with the contact DOF moved to ``x`` (m, from
where the springs are relaxed) and given the velocity ``v`` (m/s, ground frame); the other DOFs
and the state variable keep their steady values. Each is run by
:func:`~stickslip.analysis.memory.simulation.simulate_memory` (the smooth stiff engine, its
verdict: steady sliding linearly stable and reached, or a periodic orbit proven by shooting),
one after the other. The fraction of starts per verdict is an estimate with the binomial
standard error ``sqrt(p (1 - p) / n)``.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.memory.friction import steady_state
from stickslip.analysis.memory.simulation import simulate_memory
from stickslip.analysis.verdict import VERDICTS, Verdict
from stickslip.model._validate import random_seed
from stickslip.model.state_friction import MemorySystem

FloatArray = NDArray[np.float64]

#: The columns of a start: the contact DOF's position (m) and velocity (m/s).
COLUMNS = ("x", "v")
#: Most starts of one memory-law basin (each is a stiff run of up to a second or more).
MAX_MEMORY_SAMPLES = 100_000


@dataclass
class MemoryBasin:
    """Verdicts of many starts of one machine with friction with memory (SI)."""

    system: MemorySystem = field(repr=False)
    states: FloatArray = field(repr=False)
    verdict: NDArray[np.int8] = field(repr=False)
    reasons: list[str] = field(repr=False)
    elapsed: float = 0.0

    @property
    def n(self) -> int:
        """Number of starts."""
        return int(self.verdict.size)

    @property
    def fractions(self) -> dict[str, float]:
        """Fraction of starts per verdict."""
        return {v.value: float(np.count_nonzero(self.verdict == v.code)) / max(1, self.n)
                for v in VERDICTS}

    @property
    def standard_errors(self) -> dict[str, float]:
        """Binomial standard error of each fraction."""
        return {k: math.sqrt(p * (1.0 - p) / max(1, self.n)) for k, p in self.fractions.items()}

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (SI)."""
        undetermined: dict[str, int] = {}
        for code, why in zip(self.verdict.tolist(), self.reasons, strict=True):
            if code == Verdict.UNDETERMINED.code:
                undetermined[why] = undetermined.get(why, 0) + 1
        return {"n": self.n, "fractions": self.fractions, "standard_errors": self.standard_errors,
                "undetermined": int(np.count_nonzero(self.verdict == Verdict.UNDETERMINED.code)),
                "undetermined_by": undetermined, "elapsed_s": self.elapsed,
                "samples_per_second": self.n / self.elapsed if self.elapsed > 0 else None,
                "engine": "smooth stiff engine (friction with memory), one run per start",
                "columns": list(COLUMNS), "friction": self.system.friction.to_dict(),
                "machine": self.system.to_dict()}

    def write_labels(self, path: str | Path) -> Path:
        """``labels.csv``: ``x_m, v_m_s, verdict`` per start."""
        from stickslip.io.atomic import atomic_write_text

        rows = ["x_m,v_m_s,verdict"]
        rows += [f"{x!r},{v!r},{VERDICTS[int(c)].value}"
                 for (x, v), c in zip(self.states.tolist(), self.verdict.tolist(), strict=True)]
        atomic_write_text(path, "\n".join(rows) + "\n")
        return Path(path)


def sample_memory_box(system: MemorySystem, n: int, box: Mapping[str, tuple[float, float]],
                      seed: int = 0) -> FloatArray:
    """``n`` starts ``(x, v)`` uniform in ``box`` (SI); an unnamed column keeps its steady value.

    Parameters
    ----------
    system : MemorySystem
        The machine (SI).
    n : int
        Number of starts (1 to :data:`MAX_MEMORY_SAMPLES`).
    box : mapping
        ``x`` (m) and/or ``v`` (m/s) to ``(lo, hi)``.
    seed : int
        Seed of the sampling.

    Returns
    -------
    ndarray, shape (n, 2)
        The starts.
    """
    unknown = sorted(set(box) - set(COLUMNS))
    if unknown:
        raise ValueError(f"box columns {', '.join(unknown)} are not among x, v (friction with "
                         "memory: the contact DOF's position in m and velocity in m/s)")
    if isinstance(n, bool) or int(n) != n or not 1 <= int(n) <= MAX_MEMORY_SAMPLES:
        raise ValueError(f"samples={n!r} must be a whole number from 1 to {MAX_MEMORY_SAMPLES:,} "
                         "with friction with memory (each start is a stiff run)")
    for name, (lo, hi) in box.items():
        if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
            raise ValueError(f"box {name}={lo!r}:{hi!r} must be a finite interval with lo <= hi")
    y = steady_state(system, system.schedule.first)
    states = np.tile([y[system.contact_dof], 0.0], (int(n), 1))
    rng = np.random.default_rng(random_seed(seed))
    for name, (lo, hi) in box.items():
        states[:, COLUMNS.index(name)] = rng.uniform(lo, hi, int(n))
    return states


def memory_basin(system: MemorySystem, states: FloatArray, *, t_max: float | None = None,
                 progress: Callable[[int, int], None] | None = None) -> MemoryBasin:
    """The verdict of every start ``(x, v)`` (see the module notes).

    Parameters
    ----------
    system : MemorySystem
        The machine (SI; one drive speed, with the slider's mass).
    states : array_like, shape (n, 2)
        Starts: the contact DOF's position (m) and velocity (m/s).
    t_max : float, optional
        Horizon of each run, s (default that of :func:`simulate_memory`).
    progress : callable, optional
        ``progress(done, total)`` after each start.

    Returns
    -------
    MemoryBasin
        Verdicts and the reasons of the undetermined ones.
    """
    if system.quasi_static:
        raise ValueError("the quasi-static slider (m = 0) has no velocity of its own: a basin "
                         "needs the slider's mass")
    if len(system.schedule.speeds) > 1:
        raise ValueError("speed is a schedule: a basin needs one drive speed")
    starts = np.asarray(states, dtype=np.float64)
    if starts.ndim != 2 or starts.shape[1] != 2 or not np.all(np.isfinite(starts)):
        raise ValueError(f"starts need shape (n, 2) of finite numbers (x in m, v in m/s), got "
                         f"{starts.shape}")
    began = time.perf_counter()
    base = steady_state(system, system.schedule.first)
    n_dof, c = system.n_dof, system.contact_dof
    codes = np.empty(starts.shape[0], dtype=np.int8)
    reasons: list[str] = []
    for i, (x, v) in enumerate(starts.tolist()):
        y = base.copy()
        y[c], y[n_dof + c] = x, v
        run = simulate_memory(system, t_max=t_max, initial=y)
        codes[i] = run.verdict.code
        reasons.append("" if run.verdict is not Verdict.UNDETERMINED else run.reason)
        if progress is not None:
            progress(i + 1, starts.shape[0])
    return MemoryBasin(system, starts, codes, reasons, time.perf_counter() - began)


__all__ = ["COLUMNS", "MemoryBasin", "memory_basin", "sample_memory_box"]
