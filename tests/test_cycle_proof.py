"""A stick-slip certificate is a proof of the minimal cycle (analysis.cycle_proof).

References: the period of the slideway example's cycle (20.94 ms, one stick phase) is the
stable cycle that ``stickslip cycles --config`` finds (Newton on the exact return map),
independent of the run's repeat test that reported 41.87 ms before; for random machines the
reference is the same :func:`find_cycles` search, and the proven ball is checked by direct
engine runs started on its boundary.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np
import pytest

from stickslip import simulate
from stickslip.analysis.cycle_proof import divisors
from stickslip.analysis.cycles import find_cycles
from stickslip.analysis.engine_run import EngineOptions, run_engine
from stickslip.analysis.return_map import ReturnMap
from stickslip.analysis.verdict import RunStatus, Verdict
from stickslip.io.machine_file import machine_from_file, read_machine_file
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure

SLIDEWAY = Path(__file__).resolve().parent.parent / "examples" / "slideway" / "machine.toml"


def random_machine(rng: np.random.Generator) -> tuple[Structure, Slider]:
    """A grounded chain of 3-10 masses with the contact on any DOF, proportional or not damped.

    Normalised on the contact DOF (``m = k = 1`` there), damping ratio 2-10 % on it.
    """
    n = int(rng.integers(3, 11))
    mass = np.diag(rng.uniform(0.3, 3.0, n))
    stiffness = np.diag(rng.uniform(0.3, 3.0, n))
    springs = rng.uniform(0.3, 3.0, n - 1)
    for i in range(n - 1):
        stiffness[i:i + 2, i:i + 2] += springs[i] * np.array([[1.0, -1.0], [-1.0, 1.0]])
    contact = int(rng.integers(0, n))
    mass, stiffness = mass / mass[contact, contact], stiffness / stiffness[contact, contact]
    if rng.uniform() < 0.5:  # proportional (Rayleigh)
        damping = rng.uniform(0.0, 0.05) * mass + rng.uniform(0.01, 0.08) * stiffness
    else:
        a = rng.normal(size=(n, n)) * 0.05
        damping = a @ a.T + 0.02 * np.eye(n)
    damping *= 2.0 * rng.uniform(0.02, 0.1) / damping[contact, contact]
    return (Structure(mass, damping, stiffness, name=f"chain{n}", contact_dof=contact),
            Slider(float(rng.uniform(0.5, 5.0)), gamma=float(rng.uniform(0.5, 2.0))))


def test_divisors() -> None:
    assert divisors(1) == [1]
    assert divisors(6) == [1, 2, 3, 6]
    assert divisors(7) == [1, 7]


def test_slideway_period_is_the_minimal_cycle() -> None:
    """The project's own example: the run saw a 2-stick-phase repeat; the cycle has one."""
    machine, _ = machine_from_file(read_machine_file(SLIDEWAY),
                                   {"mu_s": 0.15, "mu_k": 0.10, "load": 2600.0, "speed": 0.5e-3})
    structure, slider = machine.to_dimensionless()
    run = simulate(structure, slider)
    assert run.verdict is Verdict.STICK_SLIP
    assert run.cycle_length == 1
    assert run.cycle_proof is not None and run.cycle_proof.stick_phases == 1
    seconds = run.period * machine.reference_system().time_scale
    assert seconds == pytest.approx(20.94e-3, abs=0.01e-3)  # cycles --config: 20.94 ms
    search = find_cycles(structure, slider, seeds=4, max_period=1)
    stable = [c for c in search.cycles if c.stable]
    assert stable and min(abs(c.period - run.period) for c in stable) <= 1e-7 * run.period
    assert "proven" in run.certificate and run.to_dict()["cycle_proof"]["stick_phases"] == 1


def test_a_proof_beyond_its_work_bound_is_declined_not_guessed(monkeypatch: pytest.MonkeyPatch
                                                                  ) -> None:
    # the slideway's cycle (proven above) with _phase_flow.MAX_PHASE_WORK below its phases'
    # work, as a 301-DOF frame's 3.8e11 multiply-adds per slip phase are: the run must not
    # claim the cycle, it says undetermined with the candidate it could not prove
    from stickslip.analysis import _phase_flow

    machine, _ = machine_from_file(read_machine_file(SLIDEWAY),
                                   {"mu_s": 0.15, "mu_k": 0.10, "load": 2600.0, "speed": 0.5e-3})
    structure, slider = machine.to_dimensionless()
    monkeypatch.setattr(_phase_flow, "MAX_PHASE_WORK", 1e3)
    run = simulate(structure, slider)
    assert run.verdict is Verdict.UNDETERMINED
    assert run.cycle_proof is None and "candidate, not proven" in run.certificate
    assert "period 1: its phases are beyond the work a proof may take" in run.certificate


def _light_foundation():  # type: ignore[no-untyped-def]
    """A light, soft foundation (M = 0.0934, K = 0.0378, zeta_a = 0.715) under the linear law
    delta = 0.57, lambda = 1.36, zeta = 0.08: a stick-slip cycle of period 884.175043
    (tests/friction_oracle.py: DOP853 at rtol 1e-11, the spacing of the last stick onsets over
    tau = 9000)."""
    from stickslip.model.friction import LinearFriction
    from stickslip.model.parameters import Foundation
    from stickslip.model.structure import elastic_foundation

    return (elastic_foundation(0.08, Foundation(0.0934, 0.0378, 0.715)),
            Slider(1.36, friction=LinearFriction(0.57)))


def test_the_light_foundation_cycle_is_proven_at_equal_times() -> None:
    # its long slip phase grows deviations so much that the band-by-band tube never proves a
    # contraction (the cycle was an unproven candidate); the equal-time tube across the law's
    # edge (the floor at zero) does, on a small ball that direct runs from its boundary confirm
    structure, slider = _light_foundation()
    run = simulate(structure, slider, options=EngineOptions(t_max=20000))
    assert run.verdict is Verdict.STICK_SLIP and run.cycle_proof.stick_phases == 1
    assert run.period == pytest.approx(884.175043, rel=1e-8)
    _check_ball(structure, slider, run, np.random.default_rng(2))


def test_an_unproven_candidate_says_why(monkeypatch: pytest.MonkeyPatch) -> None:
    # the light foundation's cycle with no ball proven at any radius (the proof's ladder
    # switched off: a cycle beyond the tube's reach): the run must not claim the cycle, and
    # must say which step failed
    from stickslip.analysis import cycle_proof

    monkeypatch.setattr(cycle_proof, "_ball", lambda *args, **kwargs: None)
    structure, slider = _light_foundation()
    run = simulate(structure, slider, options=EngineOptions(t_max=20000))
    assert run.verdict is Verdict.UNDETERMINED and run.status is RunStatus.UNPROVEN_CYCLE
    assert run.period == pytest.approx(884.175043, rel=1e-8)
    assert ("period-1 candidate, not proven; period 1: the deviation bound of its phases (the "
            "tube) fails at every radius tried" in run.certificate)


def test_the_soft_foundation_cycle_is_proven_in_energy_coordinates() -> None:
    # the soft foundation (M = 1.17013, K = 0.109102, zeta_a = 0.69939, linear law delta =
    # 0.8, lambda = 3, zeta = 0.1): period 427.8636273 (an independent Newton shooting on
    # solve_ivp, an audit), multipliers of modulus 1.3e-6 and 8e-9. Bounded in the engine's
    # coordinates its slip phase grew deviations by about e^57 and no proof held; in the
    # structure's energy coordinates (where the passive flow does not grow) the ball is proven,
    # and direct runs from its boundary stay in it
    from stickslip.model.friction import LinearFriction
    from stickslip.model.parameters import Foundation
    from stickslip.model.structure import elastic_foundation

    structure = elastic_foundation(0.1, Foundation(1.17013, 0.109102, 0.69939))
    slider = Slider(3.0, friction=LinearFriction(0.8))
    run = simulate(structure, slider, options=EngineOptions(t_max=20000))
    assert run.verdict is Verdict.STICK_SLIP and run.cycle_proof.stick_phases == 1
    assert run.period == pytest.approx(427.8636273, rel=1e-9)
    _check_ball(structure, slider, run, np.random.default_rng(5))


def _check_ball(structure: Structure, slider: Slider, run, rng: np.random.Generator,
                points: int = 2, returns: int = 6) -> None:
    """Direct runs from ``points`` states on the proven ball's boundary stay in it and contract
    by ``theta`` over ``returns`` returns of the exact map."""
    proof = run.cycle_proof
    inner, _ = structure.contact_first()
    onto = 0 if proof.breakaway_onto == "slip-I" else 1
    pmap = ReturnMap(inner, slider, EngineOptions(), onto)
    b_hat = pmap.reduce(proof.fixed_point)
    chol = proof.norm_matrix
    rho = proof.radius / np.linalg.norm(np.linalg.inv(chol), 2)
    floor = 1e-12 * max(1.0, float(np.max(np.abs(proof.fixed_point))))
    for _ in range(points):
        u = rng.normal(size=b_hat.size)
        b = b_hat + np.linalg.solve(chol, u / np.linalg.norm(u)) * rho
        bound = rho
        for _ in range(returns):
            b_next = pmap(b, proof.stick_phases)
            assert b_next is not None  # the ball's states reach the section again
            dist = float(np.linalg.norm(chol @ (b_next - b_hat)))
            bound = proof.contraction * bound + proof.residual * np.linalg.norm(chol, 2)
            assert dist <= bound + floor * np.linalg.norm(chol, 2)
            b = b_next


@pytest.mark.parametrize("seed", range(3))
def test_random_machines_period_is_a_stable_cycle(seed: int) -> None:
    _random_machines(seed, 4)


@pytest.mark.slow
def test_two_hundred_random_machines() -> None:
    """Issue 29's acceptance set: 200 machines of 3-10 DOF (20 seeds x 10)."""
    for seed in range(100, 120):
        _random_machines(seed, 10)


@pytest.mark.parametrize("seed", range(2))
def test_random_machines_with_weakening_laws_prove_balls_that_hold(seed: int) -> None:
    _random_weakening_machines(seed, 4)


@pytest.mark.slow
def test_forty_random_machines_with_weakening_laws() -> None:
    for seed in range(200, 210):
        _random_weakening_machines(seed, 4)


def _random_weakening_machines(seed: int, count: int) -> None:
    """The chains of :func:`random_machine` under a Stribeck law (v_s/V 0.1-0.5), a linear
    law (delta 0.2-0.8) or a decreasing six-point table, in turn: every proven cycle's ball
    holds under direct runs from its boundary (_check_ball: the package's own exact map, six
    iterations, by ``theta``), and the run's state lies in it (an undetermined run claims
    nothing to check). The laws' band edges exercise both tubes of the proof."""
    from stickslip.model.friction import LinearFriction, StribeckFriction, TableFriction

    rng = np.random.default_rng(seed)
    for k in range(count):
        structure, slider = random_machine(rng)
        if k % 3 == 2:
            u = np.sort(rng.uniform(0.0, 2.0, 6))
            u[0] = 0.0
            law = TableFriction(tuple(u), tuple(np.sort(rng.uniform(-0.4, 1.0, 6))[::-1]))
        else:
            law = (StribeckFriction(float(rng.uniform(0.1, 0.5))) if k % 3
                   else LinearFriction(float(rng.uniform(0.2, 0.8))))
        slider = Slider(slider.lam, gamma=slider.gamma, friction=law)
        run = simulate(structure, slider, record=False)
        if run.verdict is Verdict.STICK_SLIP:
            proof = run.cycle_proof
            assert proof is not None and proof.contraction < 1.0
            assert proof.distance <= proof.radius
            _check_ball(structure, slider, run, rng)


def _random_machines(seed: int, count: int) -> None:
    rng = np.random.default_rng(seed)
    for _ in range(count):
        structure, slider = random_machine(rng)
        run = simulate(structure, slider, record=False)
        if run.status is RunStatus.UNPROVEN_CYCLE:
            pytest.fail(f"seed {seed}: {structure.name} unproven: {run.certificate}")
        if run.verdict is not Verdict.STICK_SLIP:
            continue
        proof = run.cycle_proof
        assert proof is not None and proof.contraction < 1.0
        assert proof.distance <= proof.radius
        search = find_cycles(structure, slider, seeds=4, max_period=max(2, run.cycle_length))
        same = [c for c in search.cycles if c.stable and c.stick_phases == run.cycle_length
                and abs(c.period - run.period) <= 1e-7 * run.period]
        assert same, (seed, structure.name, run.period,
                      [(c.period, c.stick_phases, c.stable) for c in search.cycles])
        _check_ball(structure, slider, run, rng)


def test_one_dof_needs_no_proof() -> None:
    """The rigid base: the breakaway state is unique, the first repeat is the cycle (Eq. 20)."""
    from stickslip import rigid_base

    run = simulate(rigid_base(0.1), Slider(3.0))
    assert run.verdict is Verdict.STICK_SLIP and run.cycle_length == 1
    assert run.cycle_proof is None


def test_operating_map_cells_report_the_proven_cycle() -> None:
    """``map --config``'s cells: the period of simulate's proven cycle (at 0.4 mm/s and 2000 N
    the run's repeat test sees two stick phases, the proof one). At 0.7333 mm/s, this test's
    point before, the only ball that contracts has radius 1.0e-11 and (1 - theta) rho =
    4.6e-13, below the engine's rounding allowance for one map evaluation (1.6e-12): no proof."""
    from stickslip.sweep.grid import Axis
    from stickslip.sweep.operating_map import operating_map

    machine_file = read_machine_file(SLIDEWAY)
    machine, _ = machine_from_file(machine_file, {"mu_s": 0.15, "mu_k": 0.10, "load": 2000.0,
                                                   "speed": 0.7333e-3})
    speeds, loads = [0.2e-3, 0.4e-3], [2000.0]
    result = operating_map(machine, Axis("speed", np.array(speeds), "list"),
                           Axis("load", np.array(loads), "list"))
    for i, speed in enumerate(speeds):
        point = machine.with_operating_point(speed=speed, load=loads[0])
        structure, slider = point.to_dimensionless()
        run = simulate(structure, slider, record=False)
        assert run.verdict is Verdict.STICK_SLIP and run.cycle_length == 1
        seconds = run.period * point.reference_system().time_scale
        assert result.period_s[i, 0] == seconds
    point = machine.with_operating_point(speed=0.4e-3, load=2000.0)
    structure, slider = point.to_dimensionless()
    observed = run_engine(structure.contact_first()[0], slider, None, EngineOptions(), False, False)
    assert observed.cycle_length == 2  # the repeat the proof corrects


def test_a_ball_must_hold_the_maps_rounding(monkeypatch: pytest.MonkeyPatch) -> None:
    # an independent audit (extended-precision integration of a 44-DOF machine): one map
    # evaluation was off by 5.2e-12, and a ball of radius 1.4e-11 was claimed whose residual
    # condition the exact map violates. The proof adds _cycle_tube.rounding_allowance to the
    # computed residual; with 10,000 times the allowance no ball of the slideway holds it
    from stickslip.analysis import _cycle_tube

    machine, _ = machine_from_file(read_machine_file(SLIDEWAY),
                                   {"mu_s": 0.15, "mu_k": 0.10, "load": 2600.0, "speed": 0.5e-3})
    structure, slider = machine.to_dimensionless()
    assert simulate(structure, slider).verdict is Verdict.STICK_SLIP
    monkeypatch.setattr(_cycle_tube, "STEP_ROUNDING", 20000.0)  # 10,000x: the tube still contracts
    run = simulate(structure, slider)
    assert run.verdict is Verdict.UNDETERMINED
    assert "too small to prove anything in double precision" in run.certificate


def test_end_drift_bounds_the_nominal_continuation() -> None:
    # _cycle_tube.end_drift bounds |g*(t* + u) - g*(t*)| for 0 <= u <= T along z' = A z + c;
    # reference: the exact continuation n . int_0^u expm(A s) ds f* (an augmented matrix
    # exponential), sampled finely on [0, T]
    import scipy.linalg

    from stickslip.analysis._cycle_tube import end_drift

    rng = np.random.default_rng(7)
    for case in range(40):
        a = rng.normal(size=(4, 4))
        f_star = rng.normal(size=4)
        nv = rng.normal(size=4)
        if case % 2:  # a surface nearly parallel to the flow: the tight case
            nv -= (nv @ f_star) / (f_star @ f_star) * f_star * (1.0 - 1e-3)
        t_dev = float(rng.uniform(1e-3, 0.5)) / float(np.linalg.norm(a))
        aug = np.zeros((5, 5))
        aug[:4, :4], aug[:4, 4] = a, f_star
        exact = max(abs(float(nv @ scipy.linalg.expm(aug * u)[:4, 4]))
                    for u in np.linspace(0.0, t_dev, 201))
        norm_a = float(np.linalg.norm(a))  # Frobenius: a bound of the 2-norm, as the tube uses
        f_norm = float(np.linalg.norm(f_star))
        bound = end_drift(nv, a, f_star, f_norm, norm_a, t_dev)
        assert exact <= bound * (1 + 1e-12)
        if case % 2:
            old = float(np.linalg.norm(nv)) * f_norm * np.exp(norm_a * t_dev) * t_dev
            assert bound < 0.6 * old


@pytest.mark.parametrize("factored", [False, True])
def test_sampled_flow_is_the_exact_affine_flow(factored: bool, monkeypatch: pytest.MonkeyPatch
                                               ) -> None:
    # _phase_flow.sampled_flow: states z(s) at the sample times, and M(s) >= ||expm(A s)||_2:
    # the Frobenius norm of the formed propagators, or (beyond DENSE_WORK, as structures of
    # 20 DOF and more take) the product of the 2-norm bounds of the factors E(K h)^k E(h)^j,
    # the refined times by Taylor series from the nearer end; reference: scipy's expm of the
    # augmented matrix at each time, independently
    import scipy.linalg

    from stickslip.analysis import _phase_flow

    rng = np.random.default_rng(11)
    a = rng.normal(size=(6, 6)) * 0.4
    c, z0 = rng.normal(size=6), rng.normal(size=6)
    if factored:
        monkeypatch.setattr(_phase_flow, "DENSE_WORK", 0.0)
    times, zs, m_norm, _ = _phase_flow.sampled_flow(a, c, z0, 12.0, float(np.linalg.norm(a)))
    assert times.size > 100
    aug = np.zeros((7, 7))
    aug[:6, :6], aug[:6, 6] = a, c
    rows = list(range(0, times.size, 7))
    if factored:  # and every refined time next to the end (from the last grid state)
        rows += list(range(times.size - 45, times.size))
    ratios = []
    for j in rows:
        exact = scipy.linalg.expm(aug * times[j])
        assert zs[j] == pytest.approx(exact[:6, :6] @ z0 + exact[:6, 6], rel=1e-11, abs=1e-11)
        two_norm = np.linalg.norm(exact[:6, :6], 2)
        assert m_norm[j] >= two_norm * (1.0 - 1e-12)
        if not factored:
            assert m_norm[j] == pytest.approx(np.linalg.norm(exact[:6, :6]), rel=1e-11)
        ratios.append(m_norm[j] / two_norm)
    if factored:  # an upper bound, not a wild one: within the factors' non-normality
        assert max(ratios) < 3.0 and min(ratios) < 1.01


def test_two_norm_bounds_bound_the_singular_values() -> None:
    # _phase_flow.two_norm_bounds: the largest singular value (numpy's SVD) from above, within
    # its rounding allowance (4 m eps ||X||_F^2 under the square root)
    from stickslip.analysis import _phase_flow

    rng = np.random.default_rng(5)
    x = rng.normal(size=(30, 40, 40)) * np.logspace(-3, 3, 30)[:, None, None]
    x[3] = np.diag(np.arange(1.0, 41.0))  # exactly 40
    bounds = _phase_flow.two_norm_bounds(x)
    exact = np.linalg.norm(x, 2, axis=(1, 2))
    assert np.all(bounds >= exact)
    assert np.all(bounds <= exact * (1.0 + 1e-10))
    assert bounds[3] == pytest.approx(40.0, rel=1e-12)


@pytest.mark.slow  # 16 s: out of the default run (kept under ten minutes)
def test_profile_cycle_ball_prints_the_ladder() -> None:
    # benchmarks/profile_cycle_ball.py (bench_basin's foundation case): the proven radius holds
    # with theta < 1 (the proof's own acceptance), the larger radii name the failing phase
    import subprocess
    import sys

    script = Path(__file__).resolve().parent.parent / "benchmarks" / "profile_cycle_ball.py"
    done = subprocess.run([sys.executable, str(script), "--radii", "8", "--states", "12"],
                          capture_output=True, text=True, check=True, timeout=600)
    lines = done.stdout.splitlines()
    assert lines[0].startswith("stick-slip: proven:")
    held = [line for line in lines if "tube holds" in line and "(contracts)" in line]
    failed = [line for line in lines if "tube fails in phase" in line]
    assert held and failed
    radius = float(lines[0].split("a ball of radius ")[1].split()[0])
    held_radii = [float(line.split("r = ")[1].split(":")[0]) for line in held]
    assert any(abs(r - radius) <= 0.01 * radius for r in held_radii)  # describe() rounds to 3 digits
    # what a larger ball would buy: a larger ball is entered no later, and never before the
    # first breakaway
    stops = [float(line.split("stops after ")[1].split()[0]) for line in lines
             if line.startswith("ball radius")]
    assert len(stops) == 6 and stops[-1] >= 1.0
    assert all(a >= b for a, b in itertools.pairwise(stops))


@pytest.mark.slow  # 11 s: out of the default run (kept under ten minutes)
def test_a_sixty_dof_cycle_is_proven_with_factored_propagators(monkeypatch: pytest.MonkeyPatch
                                                               ) -> None:
    # tests/machines.grounded_chain_machine(60): its phases are beyond _phase_flow.DENSE_WORK,
    # so the proof bounds ||expm(A s)|| by products of factored 2-norms. The proof must hold
    # (a contraction ball holding the run's state) and the ball must be what it claims: direct
    # runs from its boundary contract by theta (_check_ball)
    from stickslip.analysis import _phase_flow

    from .machines import grounded_chain_machine

    machine = grounded_chain_machine(60)
    structure, slider = machine.structure(), machine.slider()
    factored = []
    bounds = _phase_flow.two_norm_bounds
    monkeypatch.setattr(_phase_flow, "two_norm_bounds", lambda x: factored.append(x.shape) or bounds(x))
    run = simulate(structure, slider)
    assert factored and all(shape[1:] == (120, 120) for shape in factored)  # the factored path
    assert run.verdict is Verdict.STICK_SLIP and run.cycle_length == 1
    proof = run.cycle_proof
    assert proof is not None and proof.contraction < 1.0 and proof.distance <= proof.radius
    _check_ball(structure, slider, run, np.random.default_rng(3))


def test_profile_fine_table_proof_names_the_parts_it_times() -> None:
    # benchmarks/profile_fine_table_proof.py (bench_friction.py's Stribeck case, here at the
    # default tolerance 1e-4): the proof is most of a stick-slip run, and every part it times
    # is found in the profile (a renamed function would print 0 calls), each within the whole
    import subprocess
    import sys

    script = Path(__file__).resolve().parent.parent / "benchmarks" / "profile_fine_table_proof.py"
    done = subprocess.run([sys.executable, str(script), "--tolerance", "1e-4"],
                          capture_output=True, text=True, check=True, timeout=600)
    lines = done.stdout.splitlines()
    assert "verdict stick-slip" in lines[0] and "proven:" in lines[1]
    shares = {line[:36].strip(): (int(line[36:].split()[0]), float(line.split()[-2]))
              for line in lines[2:]}
    assert len(shares) == 6
    proof_calls, proof_share = shares["proof of the cycle (all)"]
    assert proof_calls == 1 and proof_share > 50.0
    for part in ("candidate: sampled phases", "norms of the products", "tube bounds (ladder)"):
        calls, share = shares[part]
        assert calls >= 1 and 0.0 < share < proof_share
    assert shares["engine runs (the run and the proof)"][0] >= 1


def test_a_contraction_factor_never_prints_as_one() -> None:
    # an audit found certificates reading "contracts (theta 1)" for theta = 0.99962 (three
    # significant digits round it up): a contraction must read below 1
    from stickslip.analysis.cycle_proof import _fraction

    assert _fraction(0.99962) == "0.99962"
    assert _fraction(0.9999999) == "0.999999"
    assert _fraction(0.946) == "0.946"
    assert float(_fraction(0.99987)) < 1.0
