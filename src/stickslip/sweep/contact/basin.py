"""Basin stability of a machine with its contact: a verdict of the contact engine per start.

``stickslip basin --config`` for a machine with a ``[contact]``. Each start is steady sliding
(the slip-forward equilibrium, :func:`~stickslip.analysis.contact.cycles.steady_sliding_state`;
the start-up state where it does not exist) with these entries replaced (SI, ground frame,
displacements from where every spring is at its natural length and the contact carries the
preload):

* ``x``: the contact DOF's displacement (m);
* ``v``: the contact DOF's velocity (m/s);
* ``y``: the normal DOF's displacement (m, positive away from the belt), with a normal DOF.

A box names some of these columns (an unnamed one keeps its base value); without one, the
default box (:func:`default_box`): ``x* +- V / omega_ref`` (the engine's length unit),
``v`` from ``-V`` to ``V`` and, with a normal DOF, ``y* +- 0.5 N_0 / k_n`` (half the steady
compression of the contact spring). Each start is run to its verdict by
:func:`~stickslip.analysis.contact.engine.simulate_contact` in a bounded pool of worker
processes; its periodic verdicts are observed (a state repeated to 1e-9), not proven. The
fraction of starts per verdict is an estimate with the binomial standard error
``sqrt(p (1 - p) / n)``.
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

from stickslip.analysis.contact._modes import SLIP_FORWARD, ContactSystem
from stickslip.analysis.contact._pool import ContactOutcome, run_many
from stickslip.analysis.contact.cycles import OBSERVED, steady_sliding_state
from stickslip.analysis.verdict import VERDICTS
from stickslip.model._validate import random_seed

FloatArray = NDArray[np.float64]

#: Most starts of one contact basin (each is a run of the pure-Python engine).
MAX_CONTACT_SAMPLES = 1_000_000


def columns(system: ContactSystem) -> tuple[str, ...]:
    """The box's columns: ``x``, ``v`` and, with a normal DOF, ``y``."""
    return ("x", "v") if system.normal_dof is None else ("x", "v", "y")


def base_state(system: ContactSystem) -> tuple[FloatArray, str]:
    """The state the starts disturb, SI, and its name (steady sliding, else start-up)."""
    found = steady_sliding_state(system)
    return (system.startup_state(), "start-up") if found is None else (found, "steady sliding")


def _index(system: ContactSystem, name: str) -> int:
    return {"x": system.tangential_dof, "v": system.n_dof + system.tangential_dof,
            "y": -1 if system.normal_dof is None else system.normal_dof}[name]


def default_box(system: ContactSystem) -> dict[str, tuple[float, float]]:
    """The default box around the base state (module notes), SI.

    Parameters
    ----------
    system : ContactSystem
        The machine (SI).

    Returns
    -------
    dict
        ``x`` (m), ``v`` (m/s) and with a normal DOF ``y`` (m) to ``(lo, hi)``.
    """
    base, _ = base_state(system)
    length, speed = system.speed / system.omega_ref, system.speed
    x = float(base[system.tangential_dof])
    box = {"x": (x - length, x + length), "v": (-speed, speed)}
    if system.normal_dof is not None:
        y = float(base[system.normal_dof])
        load = max(system.normal_force(base, SLIP_FORWARD), 0.0) or system.load
        half = 0.5 * load / system.normal_stiffness
        box["y"] = (y - half, y + half)
    return box


def sample_contact_box(system: ContactSystem, n: int, box: Mapping[str, tuple[float, float]],
                       seed: int = 0) -> FloatArray:
    """``n`` starts uniform in ``box`` (SI); an unnamed column keeps its base value.

    Parameters
    ----------
    system : ContactSystem
        The machine (SI).
    n : int
        Number of starts (1 to :data:`MAX_CONTACT_SAMPLES`).
    box : mapping
        Column names of :func:`columns` to ``(lo, hi)`` in m or m/s.
    seed : int
        Seed of the sampling.

    Returns
    -------
    ndarray, shape (n, len(columns(system)))
        The starts' columns.
    """
    names = columns(system)
    unknown = sorted(set(box) - set(names))
    if unknown:
        raise ValueError(f"box columns {', '.join(unknown)} are not among {', '.join(names)} (a "
                         "contact machine: x and v of the contact DOF in m and m/s"
                         + (", y of the normal DOF in m)" if "y" in names else ")"))
    if isinstance(n, bool) or int(n) != n or not 1 <= int(n) <= MAX_CONTACT_SAMPLES:
        raise ValueError(f"samples={n!r} must be a whole number from 1 to "
                         f"{MAX_CONTACT_SAMPLES:,} with a contact machine")
    for name, (lo, hi) in box.items():
        if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
            raise ValueError(f"box {name}={lo!r}:{hi!r} must be a finite interval with lo <= hi")
    base, _ = base_state(system)
    starts = np.tile([base[_index(system, c)] for c in names], (int(n), 1))
    rng = np.random.default_rng(random_seed(seed))
    for name, (lo, hi) in box.items():
        starts[:, names.index(name)] = rng.uniform(lo, hi, int(n))
    return starts


def initial_states(system: ContactSystem, starts: FloatArray) -> FloatArray:
    """The full engine states of the starts' columns (the rest from the base state), SI."""
    base, _ = base_state(system)
    names = columns(system)
    starts = np.asarray(starts, dtype=np.float64)
    if starts.ndim != 2 or starts.shape[1] != len(names) or not np.all(np.isfinite(starts)):
        raise ValueError(f"starts need shape (n, {len(names)}) of finite numbers "
                         f"({', '.join(names)}), got {starts.shape}")
    states = np.tile(base, (starts.shape[0], 1))
    for j, name in enumerate(names):
        states[:, _index(system, name)] = starts[:, j]
    return states


@dataclass
class ContactBasin:
    """Verdicts of many starts of one machine with its contact (SI)."""

    system: ContactSystem = field(repr=False)
    starts: FloatArray = field(repr=False)
    outcomes: list[ContactOutcome] = field(repr=False)
    base: str = "steady sliding"
    elapsed: float = 0.0

    @property
    def n(self) -> int:
        """Number of starts."""
        return len(self.outcomes)

    @property
    def fractions(self) -> dict[str, float]:
        """Fraction of starts per verdict."""
        return {v.value: sum(o.verdict == v.value for o in self.outcomes) / max(1, self.n)
                for v in VERDICTS}

    @property
    def standard_errors(self) -> dict[str, float]:
        """Binomial standard error of each fraction."""
        return {k: math.sqrt(p * (1.0 - p) / max(1, self.n)) for k, p in self.fractions.items()}

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (SI)."""
        undetermined: dict[str, int] = {}
        periods: dict[str, list[float]] = {}
        for o in self.outcomes:
            if o.verdict == "undetermined":
                why = o.certificate.split(";")[0]
                undetermined[why] = undetermined.get(why, 0) + 1
            if o.period_s is not None:
                periods.setdefault(o.verdict, []).append(o.period_s)
        return {"n": self.n, "fractions": self.fractions, "standard_errors": self.standard_errors,
                "undetermined": sum(undetermined.values()), "undetermined_by": undetermined,
                "period_range_s": {k: [min(v), max(v)] for k, v in periods.items()},
                "separated": sum(o.separated for o in self.outcomes),
                "elapsed_s": self.elapsed,
                "samples_per_second": self.n / self.elapsed if self.elapsed > 0 else None,
                "columns": list(columns(self.system)), "base": self.base,
                "status": f"periodic verdicts {OBSERVED}",
                "engine": "exact piecewise-affine contact engine, one run per start"}

    def write_labels(self, path: str | Path) -> Path:
        """``labels.csv`` (atomic): the start's columns (m, m/s), verdict, period (s), separated."""
        from stickslip.io.atomic import atomic_write_text

        units = {"x": "x_m", "v": "v_m_s", "y": "y_m"}
        rows = [",".join([*(units[c] for c in columns(self.system)), "verdict", "period_s",
                          "separated"])]
        for start, o in zip(self.starts.tolist(), self.outcomes, strict=True):
            rows.append(",".join([*(repr(float(x)) for x in start), o.verdict,
                                  "" if o.period_s is None else repr(o.period_s),
                                  str(o.separated).lower()]))
        atomic_write_text(path, "\n".join(rows) + "\n")
        return Path(path)


def contact_basin(system: ContactSystem, starts: FloatArray, *, t_max: float | None = None,
                  max_events: int = 100_000, workers: int = 2,
                  progress: Callable[[int, int], None] | None = None) -> ContactBasin:
    """The verdict of every start (see the module notes).

    Parameters
    ----------
    system : ContactSystem
        The machine (SI).
    starts : array_like, shape (n, len(columns(system)))
        ``x`` (m), ``v`` (m/s) and with a normal DOF ``y`` (m) of each start.
    t_max : float, optional
        Horizon of each run, s (default the engine's).
    max_events : int
        Bound on the events of each run.
    workers : int
        Worker processes (1: this process; a pool only when the runs are costly).
    progress : callable, optional
        ``progress(done, total)`` after each run.

    Returns
    -------
    ContactBasin
        The outcome of every start.
    """
    began = time.perf_counter()
    states = initial_states(system, starts)
    _, name = base_state(system)
    outcomes = run_many([(system, z) for z in states], t_max=t_max, max_events=max_events,
                        workers=workers, progress=progress)
    return ContactBasin(system, np.asarray(starts, dtype=np.float64), outcomes, name,
                        time.perf_counter() - began)


__all__ = ["MAX_CONTACT_SAMPLES", "ContactBasin", "columns", "contact_basin", "default_box",
           "initial_states", "sample_contact_box"]
