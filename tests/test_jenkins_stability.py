"""Complex-eigenvalue analysis with a Jenkins element (the tangential contact compliance).

Oracles: the contact engine's own slip-forward flow (stickslip.analysis.contact._modes, the
time-domain model: Coulomb law, a separate construction of the same equations), the
finite-difference Jacobian of the nonlinear equations written out here (a friction law with a
slope), and the rigid contact's spectrum as the element stiffens.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import linear_sum_assignment

from stickslip.analysis.contact._modes import SLIP_FORWARD, ContactSystem
from stickslip.analysis.contact.critical_coefficient import critical_friction
from stickslip.analysis.contact.friction_coupling import FrictionCoupledSystem, verdict_of

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _machine(kt: float, ct: float, mc: float | None, slope: float = 0.0) -> FrictionCoupledSystem:
    """3 DOF, tangential 0, normal 1 (positive away from the belt), damped unequally."""
    k = np.array([[4.0e4, -1.0e4, 0.0], [-1.0e4, 3.0e4, -0.5e4], [0.0, -0.5e4, 2.0e4]])
    c = np.diag([2.0, 1.0, 3.0])
    return FrictionCoupledSystem(np.diag([1.0, 0.8, 1.2]), c, k, 0, 1, normal_stiffness=2.0e4,
                                 normal_damping=0.5, load=100.0, slope=slope,
                                 tangential_stiffness=kt, tangential_damping=ct, contact_mass=mc)


def _matched(a: np.ndarray, b: np.ndarray) -> float:
    """Largest distance between the two sets of eigenvalues, matched one to one."""
    assert a.shape == b.shape, (a.shape, b.shape)
    cost = np.abs(a[:, None] - b[None, :])
    rows, cols = linear_sum_assignment(cost)
    return float(cost[rows, cols].max())


@pytest.mark.parametrize("ct, mc", [(30.0, None), (30.0, 0.05), (0.0, 0.05)])
def test_coulomb_jenkins_spectrum_is_the_contact_engines_slip_flow(ct: float, mc: float | None) -> None:
    system = _machine(5.0e4, ct, mc)
    mu = 0.4
    engine = ContactSystem(system.mass, system.damping, system.stiffness, 0, 1, load=100.0,
                           speed=0.1, mu_s=0.6, mu_k=mu, normal_stiffness=2.0e4,
                           normal_damping=0.5, tangential_stiffness=5.0e4,
                           tangential_damping=ct, contact_mass=mc)
    flow = engine.mode(SLIP_FORWARD).flow.a
    reference = np.linalg.eigvals(flow)
    values, bounds = system.eigenvalues(mu)
    print(f"c_t = {ct}, m_c = {mc}: {_matched(values, reference):.3e} apart, "
          f"largest |s| {np.abs(reference).max():.3e}")
    assert _matched(values, reference) <= 1e-9 * np.abs(reference).max()
    assert np.all(np.isfinite(bounds))


def _nonlinear_rhs(system: FrictionCoupledSystem, mu_of, z: np.ndarray, speed: float) -> np.ndarray:
    """The equations of the module docstring, massive point, state (q, q', e, v_p), SI."""
    n, t, nd = system.n_dof, system.tangential_dof, system.normal_dof
    q, v, e, vp = z[:n], z[n:2 * n], z[2 * n], z[2 * n + 1]
    normal = system.load - system.normal_stiffness * q[nd] - system.normal_damping * v[nd]
    e_dot = v[t] - vp
    element = -(system.tangential_stiffness * e + system.tangential_damping * e_dot)
    force = -system.stiffness @ q - system.damping @ v
    force[nd] -= system.normal_stiffness * q[nd] + system.normal_damping * v[nd] - system.load
    force[nd] -= system.load  # the preload and the spring's share W cancel (as in the CEA)
    force[t] += element
    vp_dot = (mu_of(speed - vp) * normal - element) / system.contact_mass
    return np.concatenate([v, np.linalg.solve(system.mass, force), [e_dot], [vp_dot]])


def test_linearisation_with_a_slope_is_the_jacobian_of_the_equations() -> None:
    speed, mu0, slope = 0.5, 0.4, -0.08  # mu(v_r) = mu0 + slope (v_r - V) + (v_r - V)^2
    system = _machine(5.0e4, 30.0, 0.05, slope=slope)

    def mu_of(v_r: float) -> float:
        return mu0 + slope * (v_r - speed) + (v_r - speed) ** 2

    # steady state: q0 from (K0 + mu k_n e_t e_n^T) q0 = mu W e_t, e0 = -mu N0 / k_t, v_p = 0
    n0 = system.normal_force(mu0)
    k = system.contact_stiffness()
    k[0, 1] += mu0 * system.normal_stiffness
    q0 = np.linalg.solve(k, np.array([mu0 * system.load, 0.0, 0.0]))
    z0 = np.concatenate([q0, np.zeros(3), [-mu0 * n0 / 5.0e4], [0.0]])
    assert np.abs(_nonlinear_rhs(system, mu_of, z0, speed)).max() < 1e-9
    jac = np.empty((8, 8))
    for j in range(8):
        h = 1e-7 * max(1.0, abs(z0[j]))
        dz = np.zeros(8)
        dz[j] = h
        jac[:, j] = (_nonlinear_rhs(system, mu_of, z0 + dz, speed)
                     - _nonlinear_rhs(system, mu_of, z0 - dz, speed)) / (2 * h)
    reference = np.linalg.eigvals(jac)
    values, _ = system.eigenvalues(mu0)
    print(f"{_matched(values, reference):.3e} apart of {np.abs(reference).max():.3e}")
    assert _matched(values, reference) <= 1e-5 * np.abs(reference).max()


@pytest.mark.parametrize("mc", [None, 1e-3])
def test_a_stiff_element_tends_to_the_rigid_contact(mc: float | None) -> None:
    # the rigid contact with the point's mass added to the tangential DOF; the gap closes
    # like 1 / k_t (first order in the element's compliance)
    rigid = dataclasses.replace(_machine(5.0e4, 0.0, None, slope=-0.004), tangential_stiffness=None)
    mass = rigid.mass.copy()
    mass[0, 0] += mc or 0.0
    reference, _ = dataclasses.replace(rigid, mass=mass).eigenvalues(0.3)
    gaps = []
    for kt in (1e6, 1e7, 1e8):
        values, _ = dataclasses.replace(rigid, tangential_stiffness=kt, tangential_damping=1.0,
                                        contact_mass=mc).eigenvalues(0.3)
        slow = values[np.abs(values) < 2e3]  # the element's own eigenvalues are fast
        gaps.append(_matched(slow, reference))
    print(f"m_c = {mc}: gaps {gaps} (largest |s| {np.abs(reference).max():.1f})")
    assert gaps[1] < gaps[0] / 8 and gaps[2] < gaps[1] / 8
    assert gaps[2] < 1e-6 * np.abs(reference).max()


def test_undamped_massless_element_follows_the_load_and_keeps_the_rigid_boundary() -> None:
    # c_t = 0, Coulomb: the extension follows N and the structure sees mu N, as rigid
    jenkins = _machine(5.0e4, 0.0, None)
    rigid = dataclasses.replace(jenkins, tangential_stiffness=None)
    for mu in (0.2, 0.5):
        a, _ = jenkins.eigenvalues(mu)
        b, _ = rigid.eigenvalues(mu)
        np.testing.assert_array_equal(a, b)
    found_j = critical_friction(jenkins.undamped(), mu_max=3.0, n_scan=100)
    found_r = critical_friction(rigid.undamped(), mu_max=3.0, n_scan=100)
    assert found_j.mu == found_r.mu


def test_an_element_damper_that_cancels_the_slope_is_never_proven() -> None:
    system = FrictionCoupledSystem(np.eye(1), np.eye(1), np.eye(1), 0, load=2.0, slope=-0.5,
                                   tangential_stiffness=10.0, tangential_damping=1.0)
    values, bounds = system.eigenvalues(0.3)  # c_t + slope N_0 = 1 - 0.5 * 2 = 0
    assert verdict_of(values, bounds) == 0


def test_stability_command_analyses_the_jenkins_example(tmp_path: Path) -> None:
    from typer.testing import CliRunner

    from stickslip.cli.main import app

    result = CliRunner().invoke(app, ["stability", "--config",
                                      str(EXAMPLES / "jenkins_slider" / "machine.toml"), "--json"])
    assert result.exit_code == 0, result.output
    import json

    data = json.loads(result.output)
    # 1 DOF on a massless damped element, Coulomb: the element decouples (k_t de + c_t de' = 0),
    # so the slider's own pair (zeta = 0.1, 1 rad/s) and -k_t / c_t = -5.2705 1/s
    values = [complex(re, im) for re, im in data["eigenvalues"]]
    print(values)
    assert len(values) == 3
    reals = sorted(v.real for v in values)
    assert max(abs(v.imag) for v in values) == pytest.approx(math.sqrt(1 - 0.1**2), rel=1e-9)
    assert reals[0] == pytest.approx(-10.0 / 1.8973666, rel=1e-6)
    assert reals[1] == pytest.approx(-0.1, rel=1e-9) and reals[2] == pytest.approx(-0.1, rel=1e-9)
    assert data["verdict"] == "stable"
    assert data["critical"]["method"].startswith("exact")


@pytest.mark.parametrize("mc", [None, 0.05])
def test_exact_critical_mu_with_element_slope_and_normal_dof(mc: float | None) -> None:
    # f(mu) A(mu) quadratic (f = c_t (1 + a mu) + slope W or 1 + a mu): the roots decide; the
    # oracle is the growth rate of the linearisation (checked above against the equations'
    # Jacobian) on a grid and on both sides of the root
    rng = np.random.default_rng(7)
    exact = crossed = 0
    for _ in range(12):
        k = rng.normal(size=(3, 3))
        system = dataclasses.replace(
            _machine(float(rng.uniform(1e4, 1e5)), float(rng.uniform(1.0, 50.0)), mc,
                     slope=float(rng.uniform(-0.01, 0.01))),
            stiffness=np.diag([4.0e4, 3.0e4, 2.0e4]) + 3e3 * (k + k.T))

        def growth(mu: float, system: FrictionCoupledSystem = system) -> float:
            values, _ = system.eigenvalues(mu)
            return float(values.real.max())

        if growth(0.0) >= 0.0:
            continue
        found = critical_friction(system, mu_max=6.0)
        print(f"m_c = {mc}: critical mu {found.mu} ({found.kind})")
        assert found.method.startswith("exact"), found.method
        exact += 1
        crossed += found.mu is not None
        top = 6.0 if found.mu is None else found.mu
        grid = np.linspace(0.0, 6.0, 601)
        assert all(growth(float(mu)) < 0.0 for mu in grid[grid < top * (1 - 1e-7)])
        if found.mu is not None:
            assert growth(found.mu * (1 - 1e-6)) < 0.0 < growth(found.mu * (1 + 1e-6))
    assert exact >= 4 and crossed >= 2


def test_the_command_and_the_app_search_the_analysis_range() -> None:
    """``stickslip stability``'s default ``--mu-max`` (kept in the command for its start-up
    time) is the analysis's default range, which the app's machine page uses unchanged."""
    from stickslip.analysis.contact.critical_coefficient import MU_MAX
    from stickslip.cli.stability_command import MU_MAX_DEFAULT

    assert MU_MAX_DEFAULT == MU_MAX


@pytest.mark.parametrize("ct, slope", [(0.0, 0.0), (30.0, 0.004)])
def test_a_massive_point_is_one_more_dof_with_a_rigid_contact(ct: float, slope: float) -> None:
    # oracle: the Jenkins state matrix (checked above against the contact engine's flow and
    # the equations' Jacobian); point_as_dof builds the (n + 1)-DOF rigid contact separately
    rng = np.random.default_rng(11)
    for _ in range(6):
        k = rng.normal(size=(3, 3))
        system = dataclasses.replace(
            _machine(float(rng.uniform(1e4, 1e5)), ct, float(rng.uniform(0.01, 0.5)), slope),
            stiffness=np.diag([4.0e4, 3.0e4, 2.0e4]) + 3e3 * (k + k.T))
        rigid = system.point_as_dof()
        assert rigid.n_dof == 4 and rigid.tangential_stiffness is None
        for mu in (0.0, 0.3, 1.1):
            jenkins, _ = system.eigenvalues(mu)
            augmented, _ = rigid.eigenvalues(mu)
            assert _matched(jenkins, augmented) <= 1e-9 * float(np.abs(jenkins).max())
            assert rigid.normal_force(mu) == pytest.approx(system.normal_force(mu), rel=1e-12)


@pytest.mark.slow  # 20-40 s: kept out of the default run (under 10 minutes)
def test_undamped_critical_mu_of_a_massive_point_is_exact() -> None:
    # the undamped spectrum is marginal until two modes coalesce: the oracle is a 4,001-point
    # numpy scan of the Jenkins state matrix's eigenvalues (unstable where a real part exceeds
    # 1e-7 of the largest modulus), which must bracket the exact value, and both sides of it
    rng = np.random.default_rng(5)
    crossed = 0
    for _ in range(10):
        k = rng.normal(size=(3, 3))
        system = dataclasses.replace(
            _machine(float(rng.uniform(1e4, 1e5)), 0.0, float(rng.uniform(0.01, 0.5))),
            stiffness=np.diag([4.0e4, 3.0e4, 2.0e4]) + 3e3 * (k + k.T)).undamped()

        def unstable(mu: float, system: FrictionCoupledSystem = system) -> bool:
            values, _ = system.eigenvalues(mu)
            return bool(values.real.max() > 1e-7 * float(np.abs(values).max()))

        found = critical_friction(system, mu_max=4.0)
        print(f"undamped massive point: critical mu {found.mu} ({found.kind}); {found.method}")
        assert found.method.startswith("exact"), found.method
        grid = np.linspace(0.0, 4.0, 4001)
        flags = [unstable(float(mu)) for mu in grid]
        if found.mu is None:
            assert not any(flags)
            continue
        crossed += 1
        first = flags.index(True)
        assert grid[first - 1] <= found.mu <= grid[first]
        assert not unstable(found.mu * (1 - 1e-6)) and unstable(found.mu * (1 + 1e-4))
    assert crossed >= 3
