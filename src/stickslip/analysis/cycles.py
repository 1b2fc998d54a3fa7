"""The stick-slip cycles that exist at a parameter point, whatever the start (DESIGN.md section 9).

A stick-slip cycle is a fixed point of the breakaway-to-breakaway return map. At a breakaway
the slider moves with the belt (``xi' = 1``) and its stick force has just reached the static
limit, ``S = lambda`` (Eq. 20), so the state is fixed by the foundation's coordinates: for
the rigid base the breakaway state is unique, with a foundation it is ``b = (xi_a, xi_a', ...)``
and ``xi`` follows from ``S = lambda``. The return map ``P(b)``, the next breakaway state, is
evaluated exactly by the engine (exact propagation, graze-proof events; the breakaway time is
an event of the run). Cycles are the solutions of ``P^k(b) = b`` (period ``k`` stick phases),
found by Newton's method from many seeds (the breakaway states of runs from a box of initial
states). The Jacobian is taken by central differences of the exact map (step ``1e-6`` relative)
rather than by saltation matrices; its eigenvalues are the cycle's non-trivial Floquet
multipliers (the stick phase removes the slider's own coordinates, so the rigid-base cycle has
none and is stable as soon as it exists). Every reported cycle is then certified by a run of
:func:`stickslip.simulate` started on it (its breakaway state repeats), which also gives the
period, amplitude and stick ratio.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.simulation import EngineOptions, simulate
from stickslip.analysis.verdict import Verdict
from stickslip.model.initial import InitialState
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure

FloatArray = NDArray[np.float64]
#: Events allowed between two breakaways of the return map (a cycle has a handful).
RETURN_EVENTS = 400


@dataclass(frozen=True)
class Cycle:
    """One stick-slip cycle (dimensionless; times in ``tau``, displacements in ``V/omega_n``).

    Attributes
    ----------
    breakaway_state : ndarray, shape (2 n_dof,)
        The full state at the cycle's breakaway (shifted coordinates).
    stick_phases : int
        Stick phases per cycle (period-k).
    period, amplitude, stick_ratio : float
        Of the certified cycle (as :func:`stickslip.simulate` reports them).
    multipliers : ndarray of complex
        Floquet multipliers of the return map ``P^k`` (empty for the rigid base).
    stable : bool
        Every multiplier inside the unit circle.
    """

    breakaway_state: FloatArray
    stick_phases: int
    period: float
    amplitude: float
    stick_ratio: float
    multipliers: NDArray[np.complex128] = field(repr=False)
    stable: bool

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready, with the keys of ``stickslip cycles --json``."""
        return {
            "period": self.period,
            "amplitude": self.amplitude,
            "stick_ratio": self.stick_ratio,
            "stick_phases": self.stick_phases,
            "stable": self.stable,
            "multipliers": [{"re": float(m.real), "im": float(m.imag), "abs": float(abs(m))}
                            for m in self.multipliers],
            "breakaway_state": [float(x) for x in self.breakaway_state],
        }


@dataclass(frozen=True)
class CycleSearch:
    """Result of :func:`find_cycles`: every distinct cycle found, and how hard it was looked for."""

    structure: Structure
    slider: Slider
    cycles: tuple[Cycle, ...]
    n_seeds: int
    n_map_evaluations: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``cycles`` (a list) and the search's size."""
        return {
            "cycles": [c.to_dict() for c in self.cycles],
            "n_cycles": len(self.cycles),
            "lambda": self.slider.lam,
            "zeta": self.structure.zeta,
            "gamma": self.slider.gamma,
            "structure": self.structure.name,
            "friction": self.slider.friction.describe(),
            "n_seeds": self.n_seeds,
            "n_map_evaluations": self.n_map_evaluations,
        }


class _ReturnMap:
    """``P(b)``: the next breakaway state after the breakaway state built from ``b``."""

    def __init__(self, structure: Structure, slider: Slider, options: EngineOptions) -> None:
        self.structure, self.slider = structure, slider
        self.options = EngineOptions(t_max=options.t_max, max_events=RETURN_EVENTS)
        self.n = structure.n_dof
        self.evaluations = 0

    def state(self, b: FloatArray) -> FloatArray:
        """Breakaway state from the foundation coordinates ``b``: ``xi' = 1`` and ``S = lambda``."""
        n, st = self.n, self.structure
        q = np.zeros(n)
        v = np.zeros(n)
        v[0] = 1.0
        q[1:], v[1:] = b[: n - 1], b[n - 1:]
        # S = K_0j q_j + C_0j v_j (the stick force of Eq. 20 with xi'' = 0) equals lambda
        rest = st.stiffness[0, 1:] @ q[1:] + st.damping[0, :] @ v
        q[0] = (self.slider.lam - rest) / st.stiffness[0, 0]
        return np.concatenate([q, v])

    def reduce(self, state: FloatArray) -> FloatArray:
        """The foundation coordinates of a full state."""
        n = self.n
        return np.concatenate([state[1:n], state[n + 1:]])

    def next_breakaways(self, state: FloatArray, count: int) -> list[FloatArray]:
        """The full states of the next ``count`` breakaways after starting at ``state``.

        Empty when there are fewer: in particular when steady sliding is certified, after which
        the slider never sticks again. A run that certifies its cycle early is continued (up
        to the event budget) to reach ``count`` breakaways.
        """
        n = self.n
        initial = InitialState(state[:n], state[n:])
        for run_on in (False, True):
            self.evaluations += 1
            result = simulate(self.structure, self.slider, initial=initial, options=self.options,
                              run_to_t_max=run_on)
            # the start is itself a breakaway: the engine may register it at t = 0 or within
            # rounding of it (its stick force equals lambda only to rounding); it is not "next"
            times = [t for t in result.breakaway_times if t > 1e-9][:count]
            if len(times) >= count or result.verdict is not Verdict.STICK_SLIP:
                break
        if len(times) < count:
            return []
        q, v, _ = result.state_at(np.array(times))
        return [np.concatenate([q[i], v[i]]) for i in range(len(times))]

    def __call__(self, b: FloatArray, k: int) -> FloatArray | None:
        states = self.next_breakaways(self.state(b), k)
        return None if not states else self.reduce(states[-1])


def _jacobian(pmap: _ReturnMap, b: FloatArray, k: int) -> FloatArray | None:
    m = b.size
    jac = np.empty((m, m))
    for j in range(m):
        h = 1e-6 * max(1.0, abs(b[j]))
        plus, minus = b.copy(), b.copy()
        plus[j] += h
        minus[j] -= h
        fp, fm = pmap(plus, k), pmap(minus, k)
        if fp is None or fm is None:
            return None
        jac[:, j] = (fp - fm) / (2.0 * h)
    return jac


def _newton(pmap: _ReturnMap, b0: FloatArray, k: int, tol: float = 1e-11,
            max_iter: int = 30) -> tuple[FloatArray, FloatArray] | None:
    b = b0.copy()
    for _ in range(max_iter):
        pb = pmap(b, k)
        jac = _jacobian(pmap, b, k)
        if pb is None or jac is None:
            return None
        residual = pb - b
        if np.max(np.abs(residual)) <= tol * max(1.0, float(np.max(np.abs(b)))):
            return b, jac
        try:
            step = np.linalg.solve(jac - np.eye(b.size), -residual)
        except np.linalg.LinAlgError:
            return None
        b = b + step
        if not np.all(np.isfinite(b)):
            return None
    return None


def find_cycles(
    structure: Structure,
    slider: Slider,
    *,
    seeds: int = 24,
    box: float = 4.0,
    max_period: int = 2,
    seed: int = 0,
    options: EngineOptions | None = None,
) -> CycleSearch:
    """Every stick-slip cycle found at this parameter point, with its stability.

    Parameters
    ----------
    structure, slider : Structure, Slider
        The system (dimensionless), any friction law.
    seeds : int
        Initial states drawn uniformly in ``[-box, box]`` for every position and
        ``[-box, 1.5]`` for every velocity (shifted coordinates), plus the startup state; the
        breakaway states their runs reach seed Newton's method.
    box : float
        Half-width of the seeding box (units ``V/omega_n`` and ``V``).
    max_period : int
        Longest cycle looked for, in stick phases.
    seed : int
        Random seed of the seeding.
    options : EngineOptions, optional
        Horizon of the seeding runs.
    """
    opts = options or EngineOptions()
    n = structure.n_dof
    if np.any(structure.mass != np.diag(np.diag(structure.mass))):
        raise ValueError("the cycle search needs a diagonal mass matrix (the paper's structures)")
    pmap = _ReturnMap(structure, slider, opts)
    rng = np.random.default_rng(seed)
    starts = [np.concatenate([structure.kinetic_equilibrium_offset() * -slider.gamma * slider.lam,
                              np.eye(n)[0]])]
    for _ in range(int(seeds)):
        starts.append(np.concatenate([rng.uniform(-box, box, n), rng.uniform(-box, 1.5, n)]))
    breakaways: list[FloatArray] = []
    for start in starts:
        found = pmap.next_breakaways(start, 2 * max_period + 1)
        breakaways += found[-max_period:] if found else []
    cycles: list[Cycle] = []
    for k in range(1, int(max_period) + 1):
        for state in breakaways:
            if n == 1:
                solution: tuple[FloatArray, FloatArray] | None = (np.zeros(0), np.zeros((0, 0)))
                if pmap(np.zeros(0), k) is None:
                    solution = None
            else:
                solution = _newton(pmap, pmap.reduce(state), k)
            if solution is None:
                continue
            b, jac = solution
            full = pmap.state(b)
            scale = max(1.0, float(np.max(np.abs(full))))
            if any(np.max(np.abs(full - c.breakaway_state)) <= 1e-7 * scale for c in cycles):
                continue
            certified = simulate(structure, slider, initial=InitialState(full[:n], full[n:]),
                                 options=opts, record=False)
            if certified.verdict is not Verdict.STICK_SLIP or certified.cycle_k != k:
                continue
            multipliers = (np.asarray(np.linalg.eigvals(jac), dtype=np.complex128) if jac.size
                           else np.zeros(0, dtype=np.complex128))
            stable = bool(np.all(np.abs(multipliers) < 1.0))
            cycles.append(Cycle(full, k, certified.period, certified.amplitude, certified.stick_ratio,
                                multipliers, stable))
        if n == 1:
            break
    cycles.sort(key=lambda c: (c.stick_phases, c.amplitude))
    return CycleSearch(structure, slider, tuple(cycles), len(starts), pmap.evaluations)


def cycle_exists(structure: Structure, slider: Slider, **kwargs: Any) -> bool:
    """True when :func:`find_cycles` finds at least one stick-slip cycle."""
    return len(find_cycles(structure, slider, **kwargs).cycles) > 0

