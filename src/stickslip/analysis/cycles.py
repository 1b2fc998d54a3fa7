"""The stick-slip cycles that exist at a parameter point, whatever the start.

A stick-slip cycle is a fixed point of the breakaway-to-breakaway return map. At a breakaway
the slider moves with the belt (``xi' = 1``) and its stick force has just reached the static
limit, ``S = lambda`` (Eq. 20), so the state is fixed by the foundation's coordinates: for
the rigid base the breakaway state is unique, with a foundation it is ``b = (xi_a, xi_a', ...)``
and ``xi`` follows from ``S = lambda``. The return map ``P(b)``, the next breakaway state, is
evaluated exactly by the engine (exact propagation, graze-proof events; the breakaway time is
an event of the run). Cycles are the solutions of ``P^k(b) = b`` (period ``k`` stick phases),
found by Newton's method from many seeds (the breakaway states of runs from a box of initial
states). The Jacobian of ``P^k`` is exact: the product, along the recorded phases of the run
that evaluates the map, of the phase flows ``expm(A t)`` and the saltation matrices of every
event (entering stick, breakaway, friction-band edges), composed with the projection onto the
breakaway section (:meth:`ReturnMap.linearise` derives it). Its eigenvalues are the cycle's
non-trivial Floquet multipliers (the stick phase removes the slider's own coordinates, so the
rigid-base cycle has none and is stable as soon as it exists). Every reported cycle is then
certified by a run of :func:`stickslip.simulate` started on it (its breakaway state repeats),
which also gives the period, amplitude and stick ratio.

The section has two pieces: breakaways onto slip-I (``S = lambda``) and onto slip-II
(``S = -lambda (1 + 2 gamma)``, possible with a foundation, when the foundation pushes the
stuck slider forward). Each breakaway state reached by a seeding run lies on one of them; the
map ``P^k`` of a piece goes ``k`` breakaways on (of either kind, as the engine counts them)
and must land on the same piece. A cycle whose breakaways go onto both modes is found on
either piece and reported once (the slip-I piece first).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.cycle_proof import prove_existence
from stickslip.analysis.engine_run import EngineOptions, run_engine
from stickslip.analysis.return_map import ReturnMap, newton_fixed_point
from stickslip.analysis.verdict import Verdict
from stickslip.kernel.system import SLIP_I, SLIP_II
from stickslip.model._validate import random_seed
from stickslip.model.initial import InitialState
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure, to_user_order

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Cycle:
    """One stick-slip cycle (dimensionless; times in ``tau``, displacements in ``V/omega_n``).

    Attributes
    ----------
    breakaway_state : ndarray, shape (2 n_dof,)
        The full state at the cycle's breakaway (shifted coordinates).
    breakaway_onto : str
        ``slip-I`` or ``slip-II``: the section of ``breakaway_state`` (the slip mode that
        breakaway goes onto).
    stick_phases : int
        Stick phases per cycle (period-k).
    period, amplitude, stick_ratio : float
        Of the certified cycle (as :func:`stickslip.simulate` reports them).
    multipliers : ndarray of complex
        Floquet multipliers of the return map ``P^k``, largest modulus first (empty for the
        rigid base).
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
    breakaway_onto: str = "slip-I"
    proof_radius: float = float("nan")
    """Radius of a ball about ``breakaway_state``'s foundation coordinates holding exactly one
    fixed point of ``P^k`` and no shorter period (:func:`stickslip.analysis.cycle_proof.prove_existence`);
    every listed cycle has one."""
    orbit: tuple[FloatArray, ...] = field(default=(), repr=False)
    not_proven: str = ""
    """Empty for a cycle; for a candidate (:attr:`CycleSearch.candidates`), why no proof makes
    it one."""

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready, with the keys of ``stickslip cycles --json``."""
        if self.not_proven:
            return {**self._fields(), "proof_radius": None, "not_proven": self.not_proven}
        if self.breakaway_state.size == 2:  # one DOF: no ball, the repeat itself is exact
            return {**self._fields(), "proof_radius": float(self.proof_radius),
                    "proof": "exact: with one DOF every stick phase ends at the same breakaway "
                             "state (Eq. 20), so the return map has no free coordinate"}
        return {**self._fields(), "proof_radius": float(self.proof_radius)}

    def _fields(self) -> dict[str, Any]:
        return {
            "breakaway_onto": self.breakaway_onto,
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
    #: slip oscillations (:mod:`stickslip.analysis.slip_oscillations`), when searched for
    slip_oscillations: tuple[Any, ...] = ()
    #: map evaluations that ended at the horizon ``t_max`` (or an event budget) before their
    #: breakaways: a cycle slower than the horizon is not searched
    n_cut_short: int = 0
    t_max: float = math.nan
    #: fixed points of ``P^k`` that Newton's method found (residual below its tolerance) and a
    #: run from them repeats, but that no existence proof makes cycles. A strongly
    #: stable cycle whose slip phase amplifies deviations enormously before its stick phase
    #: removes them is one (its proof's bound on the Jacobian's variation does not close)
    candidates: tuple[Cycle, ...] = ()
    #: seeding runs still sticking after :data:`SEED_BREAKAWAYS` stick phases whose last
    #: breakaway state is on none of the cycles or candidates: they settle on a cycle of more
    #: than ``max_period`` stick phases, approach one slowly, or wander (an observation)
    n_unsettled: int = 0

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``cycles``, ``candidates`` and ``slip_oscillations`` (lists) and the
        search's size."""
        return {
            "cycles": [c.to_dict() for c in self.cycles],
            "n_cycles": len(self.cycles),
            "candidates": [c.to_dict() for c in self.candidates],
            "slip_oscillations": [c.to_dict() for c in self.slip_oscillations],
            "lambda": self.slider.lam,
            "zeta": self.structure.zeta,
            "gamma": self.slider.gamma,
            "structure": self.structure.name,
            "friction": self.slider.friction.describe(),
            "n_seeds": self.n_seeds,
            "n_map_evaluations": self.n_map_evaluations,
            "n_runs_cut_short": self.n_cut_short,
            "n_runs_unsettled": self.n_unsettled,
            "t_max": self.t_max,
        }


#: Breakaways each seeding run goes on for (its late states seed Newton's method too).
SEED_BREAKAWAYS = 64


def find_cycles(
    structure: Structure,
    slider: Slider,
    *,
    seeds: int = 24,
    box: float = 4.0,
    max_period: int = 2,
    seed: int = 0,
    options: EngineOptions | None = None,
    slip_oscillations: bool = False,
) -> CycleSearch:
    """Every stick-slip cycle found at this parameter point, with its stability.

    Parameters
    ----------
    structure, slider : Structure, Slider
        The system (dimensionless), any friction law.
    seeds : int
        Starts drawn uniformly in ``[-box, box]`` (positions), ``[-box, 1.5]`` (velocities) and
        the startup state; their runs' breakaway states seed Newton's method.
    box : float
        Half-width of the seeding box (units ``V/omega_n`` and ``V``).
    max_period : int
        Longest cycle looked for, in stick phases.
    seed : int
        Random seed of the seeding.
    options : EngineOptions, optional
        Horizon of the seeding runs (the result counts those it cut short).
    slip_oscillations : bool
        Also look for the periodic motions that never stick, stable and unstable
        (:func:`stickslip.analysis.slip_oscillations.find_slip_oscillations`, its own seeds).

    Returns
    -------
    CycleSearch
        The distinct cycles found, each with its period, amplitude and Floquet multipliers.
    """
    if slip_oscillations:
        from stickslip.analysis.slip_oscillations import find_slip_oscillations

        search = find_cycles(structure, slider, seeds=seeds, box=box, max_period=max_period, seed=seed,
                             options=options)
        return replace(search, slip_oscillations=find_slip_oscillations(
            structure, slider, seeds=seeds, seed=seed, options=options))
    if structure.contact_dof != 0:  # search the contact-first twin; states back in user order
        inner, perm = structure.contact_first()
        search = find_cycles(inner, slider, seeds=seeds, box=box, max_period=max_period, seed=seed,
                             options=options)
        return replace(search, structure=structure,
                       cycles=tuple(replace(c, breakaway_state=to_user_order(c.breakaway_state, perm))
                                    for c in search.cycles),
                       candidates=tuple(replace(c, breakaway_state=to_user_order(c.breakaway_state, perm))
                                        for c in search.candidates))
    opts = options or EngineOptions()
    n = structure.n_dof
    pmaps = {d: ReturnMap(structure, slider, opts, d) for d in (SLIP_I, SLIP_II)}
    starts, breakaways, ends = _seed_breakaways(pmaps[SLIP_I], structure, slider, seeds, box,
                                                max_period, seed)
    cycles: list[Cycle] = []
    candidates: list[Cycle] = []
    # the section's two pieces: breakaways onto slip-I first (the paper's), then onto slip-II
    for direction, name in ((SLIP_I, "slip-I"), (SLIP_II, "slip-II")):
        pm = pmaps[direction]
        on_section = [z for z in breakaways if pm.direction_of(z) == direction]
        if n == 1:  # the breakaway state is unique: try it even when no run reached it
            on_section = on_section[:1] or [pm.state(np.zeros(0))]
        for k in range(1, int(max_period) + 1):
            for state in on_section:
                if n == 1:
                    solution: tuple[FloatArray, FloatArray] | None = (np.zeros(0), np.zeros((0, 0)))
                    if pm(np.zeros(0), k) is None:
                        solution = None
                else:
                    solution = newton_fixed_point(pm, pm.reduce(state), k)
                if solution is None:
                    continue
                b, jac = solution
                full = pm.state(b)
                scale = max(1.0, float(np.max(np.abs(full))))
                if any(np.max(np.abs(full - z)) <= 1e-7 * scale
                       for c in (*cycles, *candidates) for z in (c.breakaway_state, *c.orbit)):
                    continue  # a cycle found before, from this or another of its breakaways
                why: list[str] = []
                radius = (0.0 if n == 1 else
                          prove_existence(structure, slider, b, k, opts, direction, why=why))
                certified = run_engine(structure, slider, InitialState(full[:n], full[n:]), opts,
                                       False, False)
                if radius is None:  # Newton's fixed point, not proven a cycle
                    if certified.cycle_length == k and certified.verdict in (
                            Verdict.STICK_SLIP, Verdict.UNDETERMINED):  # the run repeats it
                        candidates.append(_candidate_cycle(pm, full, k, jac, certified, name,
                                                           "; ".join(why) or "no reason given"))
                    continue
                if certified.verdict is not Verdict.STICK_SLIP or certified.cycle_length != k:
                    continue
                if any(c.stick_phases == k and c.breakaway_onto != name
                       and abs(c.period - certified.period) <= 1e-8 * c.period
                       and abs(c.amplitude - certified.amplitude) <= 1e-8 * max(1.0, c.amplitude)
                       for c in cycles):
                    continue  # a cycle with breakaways onto both modes, found on the other piece
                cycles.append(_candidate_cycle(pm, full, k, jac, certified, name, "", radius))
            if n == 1:
                break
    cycles.sort(key=lambda c: (c.stick_phases, c.amplitude))
    candidates.sort(key=lambda c: (c.stick_phases, c.period))
    return CycleSearch(structure, slider, tuple(cycles), len(starts),
                       sum(m.evaluations for m in pmaps.values()),
                       n_cut_short=sum(m.cut_short for m in pmaps.values()), t_max=opts.t_max,
                       candidates=tuple(candidates),
                       n_unsettled=_unsettled(ends, (*cycles, *candidates)))


#: A seeding run's last breakaway state is on a listed cycle when within this of one of its
#: breakaway states (max norm, relative to the state's scale).
SETTLED = 1e-3


def _unsettled(ends: list[FloatArray], found: tuple[Cycle, ...]) -> int:
    """How many seeding runs' last breakaway states are on none of the ``found`` cycles
    (within :data:`SETTLED`): runs that settle on a longer cycle, approach one slowly, or
    wander. An observation of the runs, not a proof."""
    count = 0
    for end in ends:
        scale = max(1.0, float(np.max(np.abs(end))))
        if not any(np.max(np.abs(end - z)) <= SETTLED * scale
                   for c in found for z in (c.breakaway_state, *c.orbit)):
            count += 1
    return count


def _seed_breakaways(pmap: ReturnMap, structure: Structure, slider: Slider, seeds: int, box: float,
                     max_period: int, seed: int
                     ) -> tuple[list[FloatArray], list[FloatArray], list[FloatArray]]:
    """The seeding runs' starts (start-up and random), the breakaway states seeding Newton and
    the last breakaway state of each run that went on for :data:`SEED_BREAKAWAYS`."""
    n = structure.n_dof
    rng = np.random.default_rng(random_seed(seed))
    starts = [np.concatenate([structure.kinetic_equilibrium_offset() * -slider.gamma * slider.lam,
                              np.eye(n)[0]])]
    for _ in range(int(seeds)):
        starts.append(np.concatenate([rng.uniform(-box, box, n), rng.uniform(-box, 1.5, n)]))
    breakaways: list[FloatArray] = []
    early = 2 * int(max_period) + 1
    late: list[FloatArray] = []  # tried after every early state, so those keep their order
    ends: list[FloatArray] = []  # each run's last breakaway state
    for start in starts:
        # the states after a short transient (near unstable cycles the run passes) and, from
        # the same run, after a long one: a cycle the runs approach slowly (multipliers near
        # 1 in modulus) is reached only late (seen: |multipliers| 0.795 on a period-2 cycle)
        found = pmap.next_breakaways(start, max(early, SEED_BREAKAWAYS))
        if not found:
            found = pmap.next_breakaways(start, early)  # fewer breakaways: steady sliding later
        breakaways += found[early - int(max_period):early]
        late += found[early:][-int(max_period):]
        if len(found) >= SEED_BREAKAWAYS:
            ends.append(found[-1])
    return starts, breakaways + late, ends


def _candidate_cycle(pm: ReturnMap, full: FloatArray, k: int, jac: FloatArray, run: Any,
                     name: str, why: str, radius: float = math.nan) -> Cycle:
    """A cycle (``why`` empty, its existence ball's ``radius``) or a fixed point of ``P^k``
    no proof makes a cycle (``why`` says what failed), with what the run from it measured
    (it repeats it: its period, amplitude and stick ratio)."""
    multipliers = (np.asarray(np.linalg.eigvals(jac), dtype=np.complex128) if jac.size
                   else np.zeros(0, dtype=np.complex128))
    multipliers = multipliers[np.argsort(-np.abs(multipliers), kind="stable")]  # largest first
    return Cycle(full, k, float(run.period), float(run.amplitude), float(run.stick_ratio),
                 multipliers, bool(np.all(np.abs(multipliers) < 1.0)), name, radius,
                 orbit=tuple(pm.next_breakaways(full, k)) if full.size > 2 else (),
                 not_proven=f"no ball is proven to hold exactly one fixed point: {why}" if why else "")


def cycle_exists(structure: Structure, slider: Slider, **kwargs: Any) -> bool:
    """True when :func:`find_cycles` finds at least one stick-slip cycle.

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices, contact on DOF 0.
    slider : Slider
        The frictional contact: ``lambda``, ``gamma`` and the friction law.
    **kwargs
        Keywords of :func:`find_cycles`.

    Returns
    -------
    bool
        Whether a stick-slip cycle was found.
    """
    return len(find_cycles(structure, slider, **kwargs).cycles) > 0

