"""Any linear structure with the contact on any DOF (issue 18 points 1, 2 and 6).

References:
* the independent event-driven ``solve_ivp`` simulator of ``tests/oracle.py``, which handles
  the contact DOF natively with index sets (no reordering, no package code);
* exact permutations: reordering DOFs is exact in floating point, so results agree to 1e-12;
* the paper's presets: ``float.hex`` identity with today's ``--dva`` path;
* Nakano's exact 1DOF boundary, paper Eq. (36) (:func:`critical_lambda_exact`).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from stickslip.analysis.simulation import simulate
from stickslip.analysis.theory import critical_lambda_exact
from stickslip.analysis.verdict import Verdict
from stickslip.model.initial import InitialState
from stickslip.model.machine import Machine, machine_from_physical_system, modal_structure
from stickslip.model.parameters import Foundation, Slider
from stickslip.model.physical import PhysicalFoundation, PhysicalSystem
from stickslip.model.structure import Structure, elastic_foundation
from tests.oracle import STICK, oracle_simulate

GAMMA = 2.0


def _stamp(matrix: np.ndarray, a: int, b: int | None, value: float) -> None:
    """Add a spring (or dashpot) ``value`` between DOFs ``a`` and ``b`` (``None``: the ground)."""
    matrix[a, a] += value
    if b is not None:
        matrix[b, b] += value
        matrix[a, b] -= value
        matrix[b, a] -= value


def test_structure(n: int, contact: int, proportional: bool) -> Structure:
    """A grounded chain of ``n`` masses with a cross spring, contact on DOF ``contact``.

    ``proportional``: Rayleigh damping ``0.02 M + 0.03 K``; else discrete dashpots on three
    elements (non-proportional: ``Phi' C Phi`` is not diagonal).
    """
    mass = np.diag(np.linspace(0.8, 1.6, n))
    mass[contact, contact] = 1.0
    stiffness = np.zeros((n, n))
    for i in range(n - 1):
        _stamp(stiffness, i, i + 1, 1.0 + 0.3 * i)
    _stamp(stiffness, 0, None, 1.5)
    _stamp(stiffness, n - 1, None, 2.0)
    _stamp(stiffness, 0, n - 1, 0.4)
    if proportional:
        damping = 0.02 * mass + 0.03 * stiffness
    else:
        damping = np.zeros((n, n))
        _stamp(damping, contact, None, 0.1)
        _stamp(damping, 0, 1, 0.05)
        _stamp(damping, n - 2, n - 1, 0.2)
    return Structure(mass, damping, stiffness, name=f"{n}-DOF test chain", contact_dof=contact)


test_structure.__test__ = False  # type: ignore[attr-defined]

CASES = [(3, 1, True), (3, 1, False), (4, 2, True), (4, 2, False), (6, 3, True), (6, 3, False)]


def _startup(st: Structure, lam: float) -> tuple[np.ndarray, np.ndarray]:
    """Startup state written out: ``q = -gamma lam K^-1 e_c``, ``v = e_c`` (Eqs. 15-16)."""
    e_c = np.eye(st.n_dof)[st.contact_dof]
    return -GAMMA * lam * np.linalg.solve(st.stiffness, e_c), e_c


@pytest.mark.parametrize(("n", "contact", "proportional"), CASES)
def test_stick_slip_agrees_with_the_oracle(n: int, contact: int, proportional: bool) -> None:
    # reference: event-driven solve_ivp oracle (tests/oracle.py), contact DOF native
    st = test_structure(n, contact, proportional)
    lam = 3.0 if n < 6 else 10.0
    run = simulate(st, Slider(lam, gamma=GAMMA))
    assert run.verdict is Verdict.STICK_SLIP
    q0, v0 = _startup(st, lam)
    horizon = 60.0
    oracle = oracle_simulate(st.mass, st.damping, st.stiffness, lam, GAMMA, q0, v0, horizon,
                             contact_dof=contact, max_step=0.05)
    engine_events = run.event_times[run.event_times < horizon - 1.0]
    assert oracle.event_times.size >= engine_events.size >= 3
    np.testing.assert_allclose(oracle.event_times[: engine_events.size], engine_events,
                               rtol=0, atol=1e-8)
    # one certified cycle, from the engine's breakaway state: the oracle comes back to it
    # after exactly one period, and its contact DOF spans twice the amplitude
    t_b = float(run.breakaway_times[-1])
    q_b, v_b, _ = run.state_at([t_b])
    cycle = oracle_simulate(st.mass, st.damping, st.stiffness, lam, GAMMA, q_b[0], v_b[0],
                            run.period, contact_dof=contact, max_step=0.02)
    q_end, v_end = cycle.state_at(run.period)
    scale = max(1.0, float(np.abs(np.concatenate([q_b[0], v_b[0]])).max()))
    assert np.abs(np.concatenate([q_end - q_b[0], v_end - v_b[0]])).max() <= 1e-7 * scale
    t = np.linspace(0.0, run.period, 20001)
    x_c = np.array([cycle.state_at(float(s))[0][contact] for s in t])
    assert 0.5 * (x_c.max() - x_c.min()) == pytest.approx(run.amplitude, rel=1e-6)


@pytest.mark.parametrize(("n", "contact", "proportional"), CASES)
def test_steady_sliding_agrees_with_the_oracle(n: int, contact: int, proportional: bool) -> None:
    # reference: the oracle shows no stick phase after the engine's certificate time and the
    # contact velocity decays (its verdict heuristic agrees)
    st = test_structure(n, contact, proportional)
    lam = 0.3
    run = simulate(st, Slider(lam, gamma=GAMMA))
    assert run.verdict is Verdict.STEADY_SLIDING
    q0, v0 = _startup(st, lam)
    horizon = run.t_certified + 40.0
    oracle = oracle_simulate(st.mass, st.damping, st.stiffness, lam, GAMMA, q0, v0, horizon,
                             contact_dof=contact, max_step=0.05)
    np.testing.assert_allclose(oracle.event_times, run.event_times[run.event_times < horizon],
                               rtol=0, atol=1e-8)
    assert not np.any(oracle.event_modes[oracle.event_times > run.t_certified] == STICK)
    assert oracle.verdict() == "steady-sliding"
    _, v_end = oracle.state_at(horizon)
    assert abs(v_end[contact]) < run.lyapunov_bound < 1.0


def _permuted(st: Structure, order: np.ndarray) -> Structure:
    """The structure with user DOF ``j`` = DOF ``order[j]`` of ``st``."""
    ix = np.ix_(order, order)
    return Structure(st.mass[ix], st.damping[ix], st.stiffness[ix],
                     contact_dof=int(np.flatnonzero(order == st.contact_dof)[0]))


@pytest.mark.parametrize(("n", "contact", "proportional"), CASES)
def test_permuting_the_dofs_changes_nothing(n: int, contact: int, proportional: bool) -> None:
    # reference: a permutation is exact; verdict, period, amplitude, event times to 1e-12
    st = test_structure(n, contact, proportional)
    lam = 3.0 if n < 6 else 10.0
    order = np.random.default_rng(n).permutation(n)
    other = _permuted(st, order)
    a = simulate(st, Slider(lam, gamma=GAMMA))
    b = simulate(other, Slider(lam, gamma=GAMMA))
    assert a.verdict is b.verdict is Verdict.STICK_SLIP
    assert b.period == pytest.approx(a.period, rel=1e-12)
    assert b.amplitude == pytest.approx(a.amplitude, rel=1e-12)
    m = min(a.event_times.size, b.event_times.size, 40)
    np.testing.assert_allclose(b.event_times[:m], a.event_times[:m], rtol=1e-12)
    # per-DOF outputs come back in the user's order
    times = np.linspace(0.0, 30.0, 7)
    qa, va, _ = a.state_at(times)
    qb, vb, _ = b.state_at(times)
    np.testing.assert_allclose(qb, qa[:, order], rtol=1e-11, atol=1e-11)
    np.testing.assert_allclose(vb, va[:, order], rtol=1e-11, atol=1e-11)
    np.testing.assert_allclose(b.initial.position, a.initial.position[order], rtol=1e-12)
    assert b.structure.contact_dof == other.contact_dof
    assert b.to_dict()["contact_dof"] == other.contact_dof


def _hex(result: object) -> list[str]:
    r = result
    return [float(x).hex() for x in (r.period, r.amplitude, r.stick_ratio, r.max_velocity,  # type: ignore[attr-defined]
                                     *r.event_times)]  # type: ignore[attr-defined]


def test_foundation_given_swapped_is_bit_identical() -> None:
    # reference: the preset itself (float.hex); the contact-first twin of the swapped matrices
    # is the preset exactly, so nothing can move
    preset = elastic_foundation(0.05, Foundation(1.2, 0.9, 0.08))
    swapped = _permuted(preset, np.array([1, 0]))
    slider = Slider(2.0, gamma=GAMMA)
    a, b = simulate(preset, slider), simulate(swapped, slider)
    assert _hex(a) == _hex(b)
    assert a.verdict is b.verdict


@pytest.mark.parametrize(("load", "verdict"), [(3.0, Verdict.STEADY_SLIDING), (30.0, Verdict.STICK_SLIP)])
def test_machine_equal_to_the_paper_foundation_is_bit_identical_to_the_dva_path(
        load: float, verdict: Verdict) -> None:
    # reference: today's --dva M,K,ZETA_A path, simulate(elastic_foundation(...)), float.hex.
    # Values are chosen so that the SI scaling is exact: sqrt(m k) = 4 (a power of two),
    # k_a / k = 4 (K = 2 exactly, K**2 = 4), so M = m_a/m, K**2 and the dampers 2 zeta,
    # 2 zeta_a round exactly as the chain's do.
    system = PhysicalSystem(mass=2.0, stiffness=8.0, damping=0.4, mu_s=0.5, mu_k=0.3, load=load, speed=0.25,
                            foundation=PhysicalFoundation(m_a=3.0, k_a=32.0, c_a=0.8))
    machine = machine_from_physical_system(system)
    structure, slider = machine.to_dimensionless()
    found = system.dimensionless_foundation()
    assert found is not None
    dva_path = elastic_foundation(system.zeta, Foundation(found.mass_ratio, found.stiffness_ratio,
                                                          found.damping_ratio))
    for mine, theirs in ((structure.mass, dva_path.mass), (structure.damping, dva_path.damping),
                         (structure.stiffness, dva_path.stiffness)):
        assert [x.hex() for x in mine.ravel()] == [x.hex() for x in theirs.ravel()]
    assert slider.lam.hex() == system.slider().lam.hex()
    a = simulate(structure, slider)
    b = simulate(dva_path, system.slider())
    assert a.verdict is b.verdict is verdict
    assert _hex(a) == _hex(b)


@pytest.mark.parametrize("zeta", [0.05, 0.2])
def test_uncoupled_contact_mode_has_the_1dof_boundary_of_eq_36(zeta: float) -> None:
    # reference: paper Eq. (36), critical_lambda_exact; the contact DOF (in the middle of a
    # 5-DOF structure) has no coupling to the others, so the rest never moves
    n, c = 5, 2
    rest = test_structure(4, 1, False)
    mass, damping, stiffness = (np.zeros((n, n)) for _ in range(3))
    others = [i for i in range(n) if i != c]
    for big, small in ((mass, rest.mass), (damping, rest.damping), (stiffness, rest.stiffness)):
        big[np.ix_(others, others)] = small
    mass[c, c], stiffness[c, c], damping[c, c] = 1.0, 1.0, 2.0 * zeta
    st = Structure(mass, damping, stiffness, contact_dof=c)
    exact = critical_lambda_exact(zeta)
    assert simulate(st, Slider(exact * (1 + 1e-8), gamma=GAMMA)).verdict is Verdict.STICK_SLIP
    assert simulate(st, Slider(exact * (1 - 1e-8), gamma=GAMMA)).verdict is Verdict.STEADY_SLIDING


def test_modal_structure_has_the_modal_receptance_at_the_contact() -> None:
    # reference: H_cc(w) = sum phi_i^2 / (w_i^2 - w^2 + 2 i zeta_i w_i w), the definition of
    # a mass-normalised modal model seen from one point
    f, z, phi = [3.0, 11.0, 25.0], [0.02, 0.05, 0.01], [0.3, -0.8, 0.5]
    mass, damping, stiffness = modal_structure(f, z, phi)
    w_i = 2 * np.pi * np.array(f)
    for w in (1.0, 18.0, 70.0, 160.0):
        dyn = stiffness - w**2 * mass + 1j * w * damping
        h = np.linalg.solve(dyn, np.eye(3)[0])[0]
        expect = sum(p**2 / (wi**2 - w**2 + 2j * zi * wi * w) for p, zi, wi in zip(phi, z, w_i, strict=True))
        assert h == pytest.approx(expect, rel=1e-10)


BAD_MATRICES = [
    ("not square", [[1.0, 0.0]], [[1.0, 0.0]], [[1.0, 0.0]], "square"),
    ("asymmetric", np.eye(2), np.zeros((2, 2)), [[2.0, -1.0], [-1.1, 2.0]], "not symmetric"),
    ("mass not PD", [[1.0, 0.0], [0.0, -1.0]], np.zeros((2, 2)), np.eye(2),
     "mass matrix must be positive definite"),
    ("free mode", np.eye(3), np.zeros((3, 3)), [[1.0, -1.0, 0.0], [-1.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
     "free rigid-body mode .* moves DOFs 0, 1"),
    ("negative stiffness", np.eye(2), np.zeros((2, 2)), [[1.0, 0.0], [0.0, -1.0]],
     "not positive semi-definite"),
    ("nan", np.eye(2), np.zeros((2, 2)), [[1.0, math.nan], [math.nan, 1.0]], "NaN"),
    ("sizes", np.eye(2), np.zeros((3, 3)), np.eye(2), "3x3, expected 2x2"),
    ("damping", np.eye(2), [[-1.0, 0.0], [0.0, 0.0]], np.eye(2),
     "damping matrix must be positive semi-definite"),
]


@pytest.mark.parametrize(("label", "mass", "damping", "stiffness", "message"), BAD_MATRICES,
                         ids=[b[0] for b in BAD_MATRICES])
def test_bad_matrices_are_refused_with_one_line(label: str, mass: object, damping: object,
                                                stiffness: object, message: str) -> None:
    for build in (lambda: Structure(mass, damping, stiffness),  # type: ignore[arg-type]
                  lambda: Machine(mass, damping, stiffness, 0, 0.5, 0.3, 10.0, 0.1)):  # type: ignore[arg-type]
        with pytest.raises(ValueError, match=message) as info:
            build()
        assert "\n" not in str(info.value)


@pytest.mark.parametrize("contact", [-1, 2, 1.0, True, "0"])
def test_contact_dof_outside_the_structure_is_refused(contact: object) -> None:
    with pytest.raises(ValueError, match="contact_dof"):
        Structure(np.eye(2), np.zeros((2, 2)), 2 * np.eye(2), contact_dof=contact)  # type: ignore[arg-type]


def test_machine_scaling_is_the_contact_dofs_own_entries() -> None:
    # reference: module docstring of model/machine.py: m_ref = M[c,c], k_ref = K[c,c]
    st = test_structure(4, 2, False)
    machine = Machine(st.mass * 3.0, st.damping * 5.0, st.stiffness * 7.0, 2, 0.5, 0.3, 20.0, 0.1)
    structure, slider = machine.to_dimensionless()
    k_ref = 7.0 * st.stiffness[2, 2]
    assert machine.reference_mass == 3.0 and machine.reference_stiffness == k_ref
    assert structure.mass[2, 2] == 1.0 and structure.stiffness[2, 2] == 1.0
    assert slider.lam == pytest.approx(0.2 * 20.0 / (0.1 * math.sqrt(3.0 * k_ref)), rel=1e-15)
    assert structure.zeta == pytest.approx(5.0 * st.damping[2, 2] / (2 * math.sqrt(3.0 * k_ref)),
                                           rel=1e-15)
    with_startup = simulate(structure, slider)
    assert with_startup.initial.velocity.tolist() == [0.0, 0.0, 1.0, 0.0]
    assert isinstance(with_startup.initial, InitialState)
