"""Stick-slip cycles whatever the start (issue 13, point 4).

Sources: on the rigid base the breakaway state is unique, so a cycle exists exactly where the
start-up run stick-slips, above the root of Eq. (36); a reported cycle must be reproduced by
:func:`stickslip.simulate` started on it (certified, same period); a stable cycle attracts
nearby breakaway states, at the rate of its largest Floquet multiplier (return map iterated).
The exact Jacobian of the return map (phase flows and saltation matrices) is checked against
central differences of the exact map, the Jacobian the search used before it was exact.
"""

from __future__ import annotations

import functools
import itertools
import json
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

from stickslip import (
    Foundation,
    InitialState,
    Slider,
    Verdict,
    critical_lambda_exact,
    elastic_foundation,
    optimal_foundation_fit,
    rigid_base,
    simulate,
)
from stickslip.analysis.cycles import Cycle, find_cycles
from stickslip.analysis.return_map import ReturnMap, newton_fixed_point
from stickslip.analysis.simulation import EngineOptions
from stickslip.kernel.system import mode_kind_band
from stickslip.model.friction import LinearFriction, StribeckFriction

from .cli_helpers import run_cli


@pytest.mark.parametrize("zeta", [0.05, 0.2])
def test_rigid_base_cycle_exists_exactly_above_eq36(zeta: float) -> None:
    lam_c = critical_lambda_exact(zeta)
    assert find_cycles(rigid_base(zeta), Slider(lam_c * (1 + 1e-4)), seeds=4).cycles
    assert not find_cycles(rigid_base(zeta), Slider(lam_c * (1 - 1e-4)), seeds=4).cycles


def test_foundation_cycle_is_reproduced_and_attracts_nearby_states() -> None:
    structure, slider = elastic_foundation(0.1, optimal_foundation_fit(0.1)), Slider(15.0)
    search = find_cycles(structure, slider, seeds=6, max_period=1)
    assert len(search.cycles) == 1
    cycle = search.cycles[0]
    b = cycle.breakaway_state
    run = simulate(structure, slider, initial=InitialState(b[:2], b[2:]), record=False)
    assert run.verdict is Verdict.STICK_SLIP and run.period == pytest.approx(cycle.period, rel=1e-9)
    # the start-up run lands on the same cycle (README: period 33.9767)
    assert simulate(structure, slider, record=False).period == pytest.approx(cycle.period, rel=1e-8)
    assert cycle.stable
    pmap = ReturnMap(structure, slider, EngineOptions())
    fixed = pmap.reduce(b)
    x = fixed + np.array([1e-3, -1e-3])
    errors = []
    for _ in range(6):
        x = pmap(x, 1)
        errors.append(float(np.max(np.abs(x - fixed))))
    # attracted, at the rate of the Floquet multipliers: one return shrinks the 1e-3 offset by
    # the largest multiplier (the long, damped stick phase makes it tiny here)
    mu = float(max(abs(cycle.multipliers)))
    assert errors[0] <= 10.0 * (mu + 1e-9) * 1e-3
    assert errors[-1] <= errors[0] + 1e-9


def test_cycles_command_json(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(["cycles", "--lam", "3", "--zeta", "0.1", "--seeds", "3", "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    [cycle] = payload["cycles"]
    assert {"period", "amplitude", "stick_ratio", "stable", "multipliers", "breakaway_state"} <= set(cycle)
    # Nakano's breakaway state on the rigid base: xi = lambda - 2 zeta, xi' = 1 (Eq. 20)
    assert cycle["breakaway_state"] == pytest.approx([3.0 - 0.2, 1.0])
    assert cycle["period"] == pytest.approx(simulate(rigid_base(0.1), Slider(3.0)).period, rel=1e-9)
    assert payload["n_runs_unsettled"] == 0  # every run settles on the one cycle
    # no ball on the rigid base (the audit read proof_radius 0 as an empty proof): said why
    assert cycle["multipliers"] == [] and cycle["proof"].startswith("exact: with one DOF")


@pytest.mark.slow
def test_runs_that_settle_on_no_listed_cycle_are_counted(
        tmp_path: Any, capsys: pytest.CaptureFixture[str]) -> None:
    # An independent audit's 3-DOF chain (B3): `cycles` lists two 1-stick-phase cycles and one
    # of 2 (--max-period 2), but start-up settles on a stable cycle of 5 stick phases (the
    # audit's own Newton shooting: period 91.85175832, |multipliers| 0.86499, 0.53887; simulate
    # proves it with --t-max 40000). The output said only "search 25 starts".
    for name, rows in (("M.csv", "1,0,0\n0,0.5,0\n0,0,2\n"),
                       ("K.csv", "3000,-1000,0\n-1000,4000,-3000\n0,-3000,3000\n"),
                       ("C.csv", "6.5,-2,0\n-2,8.25,-6\n0,-6,7\n")):
        (tmp_path / name).write_text(rows)
    machine = tmp_path / "machine.toml"
    machine.write_text('mu_s = 0.5\nmu_k = 0.3\nload = "100.0 N"\nspeed = "0.05 m/s"\n'
                       '[structure]\nname = "B3"\nmass = "M.csv"\nstiffness = "K.csv"\n'
                       'damping = "C.csv"\ncontact_dof = 0\n')
    code, out, err = run_cli(["cycles", "--config", str(machine), "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    assert max(c["stick_phases"] for c in payload["cycles"]) <= 2
    assert payload["n_runs_unsettled"] >= payload["n_seeds"] // 2
    code, out, err = run_cli(["cycles", "--config", str(machine)], capsys)
    assert code == 0 and "on none of these cycles" in out, err


def test_a_cycle_slower_than_the_horizon_is_said_and_found_with_a_longer_one(
        capsys: pytest.CaptureFixture[str]) -> None:
    # a bad-input audit: at lambda = 1e4 the cycle's period (~1.7e4) exceeds the default
    # horizon (5000) and "none found" was printed as if no cycle existed. Oracle: simulate's
    # certified period with a long horizon.
    code, out, err = run_cli(["cycles", "--lam", "1e4", "--zeta", "0.1", "--seeds", "2"], capsys)
    assert code == 0, err
    assert "within the horizon" in out and "raise --t-max" in out
    code, out, err = run_cli(["cycles", "--lam", "1e4", "--zeta", "0.1", "--seeds", "2",
                              "--t-max", "1e5", "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    [cycle] = payload["cycles"]
    expected = simulate(rigid_base(0.1), Slider(1e4), options=EngineOptions(t_max=1e5)).period
    assert cycle["period"] == pytest.approx(expected, rel=1e-9)
    assert payload["t_max"] == 1e5


# --- the exact Jacobian of the return map ------------------------------------------------------

#: central-difference step of the oracle, relative (the step the search used before)
FD_STEP = 1e-6
#: Agreement of the exact Jacobian with central differences: ``max|J - J_fd| <= RTOL max|J_fd|
#: + ATOL``. Truncation error of central differences ~ h^2 |P'''| ~ 1e-12; rounding error ~
#: eps_P / h, with eps_P ~ 1e-14 the error of the map's values (breakaway states of size ~ 10,
#: events located to a few ulps) over 2h = 2e-6: ~ 5e-9 absolute, whatever the size of J.
#: Hence ATOL = 1e-8 and RTOL = 1e-5 (ten times the step). Measured (these cases, at the cycle
#: and off it): <= 2.2e-9 absolute; <= 8e-9 relative where |J| ~ 0.25 (lightly damped
#: foundation), <= 2.5e-6 relative where |J| ~ 9e-4 (optimal foundation: the absolute floor).
RTOL, ATOL = 1e-5, 1e-8

FloatArray = NDArray[np.float64]


def _fd_jacobian(pmap: ReturnMap, b: FloatArray, k: int, rel: float = FD_STEP) -> FloatArray:
    """Central differences of the exact map ``P^k`` (step ``rel * max(1, |b_j|)``): the oracle."""
    jac = np.empty((b.size, b.size))
    for j in range(b.size):
        h = rel * max(1.0, abs(b[j]))
        plus, minus = b.copy(), b.copy()
        plus[j] += h
        minus[j] -= h
        fp, fm = pmap(plus, k), pmap(minus, k)
        assert fp is not None and fm is not None
        jac[:, j] = (fp - fm) / (2.0 * h)
    return jac


@dataclass(frozen=True)
class _StepFriction:
    """A friction law with a JUMP: ``F = gamma lambda + drop`` below ``u = edge``, ``gamma
    lambda`` above (exact, two bands). At its band edge ``f^+ != f^-``, so the saltation
    matrix there is not the identity (no library law is discontinuous)."""

    edge: float = 0.3
    drop: float = 0.5
    exact = True

    def bands(self, lam: float, gamma: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        return (np.array([0.0, self.edge, math.inf]), np.array([gamma * lam + self.drop, gamma * lam]),
                np.zeros(2))

    def value(self, u: Any, lam: float, gamma: float) -> FloatArray:
        uu = np.asarray(u, dtype=np.float64)
        return np.where(uu < self.edge, gamma * lam + self.drop, gamma * lam)

    def slope_at(self, u: float, lam: float, gamma: float) -> float:
        return 0.0

    def describe(self) -> str:
        return f"step at u = {self.edge:g}, drop {self.drop:g}, exact"


#: The paper's 2DOF model (Fig. 1, Eqs. 19-27): the fitted optimal foundation of Eqs. (28)-(30)
#: at zeta = 0.1, whose long damped stick phase makes DP tiny (multipliers ~ 2e-4), and a
#: lightly damped foundation (zeta_a = 0.02) whose motion survives the stick phase (DP ~ 0.3).
_STRUCTURES = {
    "optimal": lambda: elastic_foundation(0.1, optimal_foundation_fit(0.1)),
    "light": lambda: elastic_foundation(0.05, Foundation(1.0, 1.0, 0.02)),
}
_CASES = {
    "optimal-coulomb": ("optimal", lambda: Slider(7.0)),
    "light-coulomb": ("light", lambda: Slider(3.0)),
    # velocity weakening F = gamma lambda - 4 u, floored at u* = 1.5: two bands, edge crossed
    "light-linear": ("light", lambda: Slider(3.0, friction=LinearFriction(2.0))),
    # 11 bands at tolerance 1e-2 (the default 1e-4 gives 72 bands, too many events for the
    # search's event budget between breakaways, RETURN_EVENTS)
    "light-stribeck": ("light", lambda: Slider(3.0, friction=StribeckFriction(0.5, tolerance=1e-2))),
    "optimal-stribeck": ("optimal", lambda: Slider(7.0, friction=StribeckFriction(0.2, tolerance=1e-2))),
    "light-step": ("light", lambda: Slider(3.0, friction=_StepFriction())),  # type: ignore[arg-type]
}


@functools.cache
def _cycle(case: str) -> tuple[ReturnMap, Cycle]:
    """The (unique, period-1) cycle of a case, found by the search, and its return map."""
    structure_name, make_slider = _CASES[case]
    structure, slider = _STRUCTURES[structure_name](), make_slider()
    search = find_cycles(structure, slider, seeds=2, max_period=1)
    assert len(search.cycles) == 1
    return ReturnMap(structure, slider, EngineOptions()), search.cycles[0]


@pytest.mark.parametrize("case", list(_CASES))
def test_exact_jacobian_agrees_with_central_differences(case: str) -> None:
    pmap, cycle = _cycle(case)
    fixed = pmap.reduce(cycle.breakaway_state)
    run = pmap.recorded_run(cycle.breakaway_state, 1)
    assert run is not None
    bands_crossed = {mode_kind_band(int(m))[1] for m in run[0].segment_modes}
    # a law with bands must cross an edge in the cycle, else its saltation is not exercised
    assert (max(bands_crossed) > 0) == (not case.endswith("coulomb"))
    # at the cycle and off it (the map's Jacobian anywhere, not only at its fixed point)
    for b in (fixed, fixed + np.array([0.05, -0.03])):
        evaluated = pmap.linearise(b, 1)
        assert evaluated is not None
        value, jac = evaluated
        np.testing.assert_array_equal(value, pmap(b, 1))  # the same exact map
        oracle = _fd_jacobian(pmap, b, 1)
        assert np.max(np.abs(jac - oracle)) <= RTOL * np.max(np.abs(oracle)) + ATOL, (jac, oracle)


@pytest.mark.parametrize("case", ["optimal-coulomb", "light-coulomb", "light-stribeck", "light-step"])
def test_floquet_multipliers_agree_with_central_differences(case: str) -> None:
    pmap, cycle = _cycle(case)
    oracle = np.linalg.eigvals(_fd_jacobian(pmap, pmap.reduce(cycle.breakaway_state), 1))
    # eigenvalues move by at most cond(V) |dJ| (Bauer-Fike); |dJ| <= RTOL |J| + ATOL (above),
    # and the eigenvector matrices here are well conditioned (cond(V) <= 5.3 measured): 100 x
    # that bound
    tol = 100.0 * (RTOL * float(np.max(np.abs(oracle))) + ATOL)
    assert cycle.multipliers.size == 2
    for mu in cycle.multipliers:
        assert float(np.min(np.abs(oracle - mu))) <= tol, (cycle.multipliers, oracle)
    assert cycle.stable == bool(np.all(np.abs(oracle) < 1.0))


@pytest.mark.parametrize("case", ["light-coulomb", "light-stribeck"])
def test_newton_converges_quadratically_with_the_exact_jacobian(case: str) -> None:
    pmap, cycle = _cycle(case)
    fixed = pmap.reduce(cycle.breakaway_state)
    residuals: list[float] = []
    solution = newton_fixed_point(pmap, fixed + np.array([1e-2, 1e-2]), 1, residuals=residuals)
    assert solution is not None
    np.testing.assert_allclose(solution[0], fixed, rtol=0.0, atol=1e-10)
    # Newton: r_{i+1} <= C r_i^2 while above the rounding floor (~1e-14 of states ~ 10);
    # measured C <= 0.26 here (residuals 1.2e-2, 2.1e-5, 9.6e-11, 3e-15 for Coulomb), so C = 1
    # is a bound with margin. The plain iteration of P would shrink the residual only by the
    # largest multiplier per step (|mu| = 0.12 and 0.20 here, from the test above).
    assert len(residuals) <= 5
    for before, after in itertools.pairwise(residuals):
        if after > 1e-13:
            assert after <= 1.0 * before**2, residuals
    assert residuals[-1] <= 1e-11 * max(1.0, float(np.max(np.abs(solution[0]))))


def test_stribeck_cycle_at_the_default_tolerance() -> None:
    # a default Stribeck interpolant has about 100 bands, so a cycle has hundreds of band
    # events: the return map's event budget scales with the bands (RETURN_EVENTS per band).
    # Rigid base: the breakaway state is unique, so the one cycle is the start-up run's
    # (same period to the cycle tolerance, EngineOptions.cycle_tol = 1e-9)
    structure = rigid_base(0.1)
    slider = Slider(2.0, friction=StribeckFriction(0.2))
    search = find_cycles(structure, slider, seeds=4)
    assert len(search.cycles) == 1
    startup = simulate(structure, slider, record=False)
    assert startup.verdict is Verdict.STICK_SLIP
    assert search.cycles[0].period == pytest.approx(startup.period, rel=1e-8)


def test_an_unproven_fixed_point_is_a_candidate_not_a_cycle_nor_nothing(
        capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    # the light, soft foundation of tests/test_cycle_proof.py (M = 0.0934, K = 0.0378, zeta_a
    # = 0.715, linear law delta = 0.57, lambda = 1.36, zeta = 0.08): a stick-slip cycle of
    # period 884.175043 (tests/friction_oracle.py, DOP853 at rtol 1e-11), here with no proof
    # (the proof's ladder switched off: the equal-time tube proves it on a ball of about 1e-7,
    # tests/test_cycle_proof.py). The search used to say "none found" for a fixed point no
    # proof closes; it lists it as a candidate, not proven, and says why; an existence
    # boundary is then undetermined there, not steady sliding
    from stickslip.analysis import cycle_proof

    monkeypatch.setattr(cycle_proof, "_ball", lambda *args, **kwargs: None)
    structure = elastic_foundation(0.08, Foundation(0.0934, 0.0378, 0.715))
    slider = Slider(1.36, friction=LinearFriction(0.57))
    search = find_cycles(structure, slider, seeds=4)
    assert search.cycles == ()
    [candidate] = search.candidates
    assert candidate.stick_phases == 1
    assert candidate.period == pytest.approx(884.175043, rel=1e-8)
    assert "the tube fails at every radius tried" in candidate.not_proven
    payload = search.to_dict()
    assert payload["n_cycles"] == 0 and payload["candidates"][0]["proof_radius"] is None
    code, out, err = run_cli(["cycles", "--lam", "1.36", "--zeta", "0.08", "--dva",
                              "0.0934,0.0378,0.715", "--friction", "linear:0.57", "--seeds", "4"],
                             capsys)
    assert code == 0, err
    assert "none proven" in out and "candidate 1 period 884.175" in out and "NOT PROVEN" in out


def test_existence_boundary_is_undetermined_where_only_candidates_are_found(
        monkeypatch: pytest.MonkeyPatch) -> None:
    # sweep.boundary's existence criterion: a proven cycle is stick-slip, no fixed point at
    # all is steady sliding, and a candidate alone (no proof either way) is undetermined
    from stickslip.analysis import cycles as cycles_module
    from stickslip.model.dva import DvaSpec
    from stickslip.model.friction import CoulombFriction
    from stickslip.sweep import boundary
    from stickslip.sweep.executors import StructureSet

    structures = StructureSet.resolve(DvaSpec.parse("none"), np.array([0.1]))
    one = Cycle(np.zeros(2), 1, 5.0, 1.0, 0.5, np.zeros(0, dtype=np.complex128), True)
    answers = {1.0: ((one,), ()), 2.0: ((), ()), 3.0: ((), (one,))}

    def fake(structure, slider, **_):  # type: ignore[no-untyped-def]
        found, candidates = answers[slider.lam]
        return cycles_module.CycleSearch(structure, slider, found, 1, 1, candidates=candidates)

    monkeypatch.setattr(cycles_module, "find_cycles", fake)
    codes = boundary._cycle_codes(structures, np.zeros(3, dtype=np.int64), np.array([1.0, 2.0, 3.0]),
                                  2.0, CoulombFriction(), EngineOptions(), 1)
    assert codes.tolist() == [Verdict.STICK_SLIP.code, Verdict.STEADY_SLIDING.code,
                              Verdict.UNDETERMINED.code]
