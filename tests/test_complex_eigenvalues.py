"""Complex-eigenvalue analysis of steady sliding with normal-load coupling (issue 34, item 2).

References:
- the undamped flutter boundary of the minimal model of Hoffmann et al. (2002), Mech. Res.
  Commun. 29, 197-205: the zero of the discriminant of its 2x2 quadratic eigenproblem, derived
  in stickslip.analysis.contact.squeal_minimal_model and docs/brake_squeal.md (re-derived here from the
  characteristic polynomial, not taken from the library);
- with damping, the Routh-Hurwitz condition of the characteristic quartic (Hurwitz 1895),
  computed here from the polynomial's coefficients;
- the destabilising effect of damping: Hoffmann and Gaul (2003), ZAMM 83, 524-534 (unequal
  modal damping lowers the flutter boundary, damping proportional to the mass raises it);
- the signs of the linearisation: a central finite-difference Jacobian of the nonlinear
  equations of motion written out in this file.
"""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from stickslip.analysis.contact.critical_coefficient import critical_friction
from stickslip.analysis.contact.eigenvalue_maps import operating_ranges, root_locus, stability_map
from stickslip.analysis.contact.eigenvalues import complex_eigenvalue_analysis
from stickslip.analysis.contact.friction_coupling import FrictionCoupledSystem, friction_at, verdict_of
from stickslip.analysis.contact.squeal_minimal_model import hoffmann_critical_mu, hoffmann_stiffness
from stickslip.model.contact import Contact
from stickslip.model.machine import Machine
from stickslip.model.physical import PhysicalFriction

ROOT = Path(__file__).resolve().parents[1]
#: (m [kg], k1, k2, k3 [N/m], alpha [deg], k_n [N/m]): the docs' brake pad and variations of
#: every parameter (detuned, stiffer contact, a steeper spring, another mass).
HOFFMANN_SETS = [
    (0.1, 6.5e7, 1.0e7, 3.0e7, 135.0, 5.0e7),
    (0.1, 6.0e7, 1.0e7, 3.0e7, 135.0, 5.0e7),
    (1.0, 1.0, 1.0, 1.0, 135.0, 1.0),
    (2.5, 4.0e5, 9.0e5, 6.0e5, 120.0, 2.0e6),
    (0.02, 3.0e6, 1.0e6, 2.0e6, 150.0, 4.0e6),
]


def _closed_form_from_polynomial(m: float, k: np.ndarray, kn: float) -> float:
    """Undamped flutter: det(K(mu) - m lam I) = m^2 lam^2 - b lam + c(mu); the discriminant
    b^2 - 4 m^2 c(mu) is affine in mu, its zero is the coalescence (Hoffmann et al. 2002)."""
    k11, k12, k22 = k[0, 0], k[0, 1], k[1, 1] + kn
    b = m * (k11 + k22)

    def disc(mu: float) -> float:
        return b * b - 4 * m * m * (k11 * k22 - k12 * (k12 + mu * kn))

    return -disc(0.0) / (disc(1.0) - disc(0.0))


def _system(m: float, k: np.ndarray, kn: float, c: np.ndarray | None = None) -> FrictionCoupledSystem:
    return FrictionCoupledSystem(m * np.eye(2), np.zeros((2, 2)) if c is None else c, k, 0, 1,
                                 normal_stiffness=kn, load=1000.0)


@pytest.mark.parametrize("params", HOFFMANN_SETS)
def test_undamped_critical_mu_is_the_closed_form_of_hoffmann_2002(params: tuple[float, ...]) -> None:
    m, k1, k2, k3, alpha, kn = params
    k = hoffmann_stiffness(k1, k2, k3, math.radians(alpha))
    reference = _closed_form_from_polynomial(m, k, kn)
    assert hoffmann_critical_mu(m, k, kn) == pytest.approx(reference, rel=1e-13)
    found = critical_friction(_system(m, k, kn), mu_max=max(2.0, 1.5 * reference), n_scan=100)
    digits = -math.log10(max(abs(found.mu - reference) / reference, 1e-17))
    print(f"found {found.mu:.16g} | reference {reference:.16g} | matching digits {digits:.1f}")
    assert found.kind == "flutter" and found.modes == (1, 2)
    assert digits >= 11
    # the bracket's upper end is proven unstable: the undamped boundary lies below it
    assert found.bracket is not None and reference <= found.bracket[1] * (1 + 1e-13)
    # and the value reported lies in the bracket reported (its lower end is not proven stable:
    # at the coalescence the eigenvalues' bounds are wide, so the bisection may stop a rounding
    # above the exact value)
    assert found.bracket[0] <= found.mu <= found.bracket[1]


def test_no_flutter_when_the_inclined_spring_leans_the_other_way() -> None:
    # k12 > 0: the coupling of a belt moving in +x stiffens; the closed form says inf
    k = hoffmann_stiffness(6.5e7, 1.0e7, 3.0e7, math.radians(45.0))
    assert hoffmann_critical_mu(0.1, k, 5e7) == math.inf
    assert critical_friction(_system(0.1, k, 5e7), mu_max=3.0).mu is None


def _routh_hurwitz_critical_mu(m: float, k: np.ndarray, kn: float, c1: float, c2: float) -> float:
    """det(M s^2 + C s + K(mu)) = a0 s^4 + a1 s^3 + a2 s^2 + a3 s + a4, only a4 depends on mu
    (affinely); stable iff every a_i > 0 and a1 a2 a3 - a0 a3^2 - a1^2 a4 > 0 (Hurwitz)."""
    k11, k12, k22 = k[0, 0], k[0, 1], k[1, 1] + kn
    a0, a1 = m * m, m * (c1 + c2)
    a2 = m * (k11 + k22) + c1 * c2
    a3 = c1 * k22 + c2 * k11
    a4_at_zero, a4_per_mu = k11 * k22 - k12 * k12, -k12 * kn
    a4_critical = (a1 * a2 * a3 - a0 * a3 * a3) / (a1 * a1)
    return (a4_critical - a4_at_zero) / a4_per_mu


@pytest.mark.parametrize("c1, c2", [(20.0, 20.0), (40.0, 4.0), (4.0, 40.0), (40.0, 0.0), (200.0, 50.0)])
def test_damped_critical_mu_is_the_routh_hurwitz_boundary(c1: float, c2: float) -> None:
    m, kn = 0.1, 5e7
    k = hoffmann_stiffness(6.5e7, 1.0e7, 3.0e7, math.radians(135.0))
    reference = _routh_hurwitz_critical_mu(m, k, kn, c1, c2)
    found = critical_friction(_system(m, k, kn, np.diag([c1, c2])), n_scan=100)
    assert found.mu is not None and found.bracket is not None
    print(f"c = ({c1}, {c2}): found {found.mu:.14g} | Routh-Hurwitz {reference:.14g}")
    assert found.mu == pytest.approx(reference, rel=1e-9)
    assert found.bracket[0] <= reference * (1 + 1e-9) and reference <= found.bracket[1] * (1 + 1e-9)


def test_unequal_damping_destabilises_and_mass_proportional_damping_stabilises() -> None:
    # Hoffmann and Gaul (2003): the damped boundary lies below the undamped one when the two
    # modes are damped unequally, above it for damping proportional to the mass
    m, kn = 0.1, 5e7
    k = hoffmann_stiffness(6.5e7, 1.0e7, 3.0e7, math.radians(135.0))
    undamped = hoffmann_critical_mu(m, k, kn)
    for c in (np.diag([40.0, 4.0]), np.diag([4.0, 40.0]), np.diag([1.0, 0.0])):
        damped = critical_friction(_system(m, k, kn, c)).mu
        assert damped is not None and damped < undamped - 1e-3, (np.diag(c), damped, undamped)
    for alpha in (10.0, 100.0, 1000.0):  # C = alpha M
        damped = critical_friction(_system(m, k, kn, alpha * m * np.eye(2))).mu
        assert damped is not None and damped > undamped, (alpha, damped, undamped)
        assert damped == pytest.approx(_routh_hurwitz_critical_mu(m, k, kn, alpha * m, alpha * m),
                                       rel=1e-9)


def test_linearisation_is_the_jacobian_of_the_equations_of_motion() -> None:
    # 3 DOF: tangential 2, normal 0, a linear friction law mu(v_r) = mu0 + s (v_r - V)
    rng = np.random.default_rng(4)
    a = rng.normal(size=(3, 3))
    k = a @ a.T + 3 * np.eye(3)
    b = rng.normal(size=(3, 3))
    c = 0.1 * (b @ b.T)
    mass = np.diag([1.0, 2.0, 0.5])
    kn, cn, w, v, mu0, s = 4.0, 0.3, 2.0, 1.5, 0.35, -0.07
    t, n = 2, 0

    def accel(q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        normal = w - kn * q[n] - cn * qd[n]
        force = -c @ qd - k @ q
        force[n] += normal - w  # the contact force N away from the belt, the preload W towards it
        force[t] += (mu0 + s * ((v - qd[t]) - v)) * normal
        return np.linalg.solve(mass, force)

    system = FrictionCoupledSystem(mass, c, k, t, n, normal_stiffness=kn, normal_damping=cn,
                                   load=w, slope=s)
    m_, c_mu, k_mu = system.matrices(mu0)
    q0 = np.linalg.solve(k_mu, mu0 * w * np.eye(3)[t])
    assert np.allclose(accel(q0, np.zeros(3)), 0.0, atol=1e-12)
    assert system.normal_force(mu0) == pytest.approx(w - kn * q0[n], rel=1e-12)
    h = 1e-6
    jac_q = np.column_stack([(accel(q0 + h * e, np.zeros(3)) - accel(q0 - h * e, np.zeros(3))) / (2 * h)
                             for e in np.eye(3)])
    jac_v = np.column_stack([(accel(q0, h * e) - accel(q0, -h * e)) / (2 * h) for e in np.eye(3)])
    assert np.allclose(jac_q, -np.linalg.solve(m_, k_mu), atol=1e-7)
    assert np.allclose(jac_v, -np.linalg.solve(m_, c_mu), atol=1e-7)
    assert k_mu[t, n] == pytest.approx(k[t, n] + mu0 * kn)  # the +mu k_n coupling entry


def test_eigenvalues_are_the_roots_of_the_characteristic_polynomial() -> None:
    m, kn = 0.1, 5e7
    k = hoffmann_stiffness(6.5e7, 1.0e7, 3.0e7, math.radians(135.0))
    system = _system(m, k, kn, np.diag([40.0, 4.0]))
    for mu in (0.0, 0.2, 0.4):
        _, c, kk = system.matrices(mu)
        poly = np.polynomial.polynomial.polymul([kk[0, 0], c[0, 0], m], [kk[1, 1], c[1, 1], m])
        poly[0] -= kk[0, 1] * kk[1, 0]
        roots = np.sort_complex(np.roots(poly[::-1]))
        values, bounds = system.eigenvalues(mu)
        assert np.allclose(np.sort_complex(values), roots, rtol=1e-9)
        assert np.all(bounds < 1e-6 * np.abs(values))


def test_undamped_spectrum_is_marginal_below_and_unstable_above_the_coalescence() -> None:
    m, kn = 0.1, 5e7
    k = hoffmann_stiffness(6.5e7, 1.0e7, 3.0e7, math.radians(135.0))
    system = _system(m, k, kn)
    mu_c = hoffmann_critical_mu(m, k, kn)
    assert verdict_of(*system.eigenvalues(0.9 * mu_c)) == 0
    assert verdict_of(*system.eigenvalues(1.001 * mu_c)) == 1
    damped = _system(m, k, kn, np.diag([20.0, 20.0]))
    assert verdict_of(*damped.eigenvalues(0.9 * mu_c)) == -1


def _brake_pad(friction: PhysicalFriction | None = None, c: tuple[float, float] = (40.0, 4.0),
               mu_k: float = 0.4) -> tuple[Machine, Contact]:
    k = hoffmann_stiffness(6.5e7, 1.0e7, 3.0e7, math.radians(135.0))
    machine = Machine(0.1 * np.eye(2), np.diag(c), k, 0, 0.5, mu_k, 1000.0, 5.0,
                      friction or PhysicalFriction())
    return machine, Contact(normal_dof=1, normal_stiffness=5e7)


def test_machine_analysis_gives_both_boundaries_and_the_verdict() -> None:
    machine, contact = _brake_pad()
    result = complex_eigenvalue_analysis(machine, contact)
    assert result.mu == 0.4 and result.slope == 0.0
    assert result.verdict == "unstable" and not result.stable
    assert result.critical_undamped.mu == pytest.approx(
        hoffmann_critical_mu(0.1, machine.stiffness, 5e7), rel=1e-11)
    assert result.critical.mu == pytest.approx(
        _routh_hurwitz_critical_mu(0.1, machine.stiffness, 5e7, 40.0, 4.0), rel=1e-9)
    payload = result.to_dict()
    assert len(payload["eigenvalues"]) == 4 and all(len(p) == 2 for p in payload["eigenvalues"])
    stable = complex_eigenvalue_analysis(*_brake_pad(mu_k=0.25))
    assert stable.verdict == "stable" and stable.stable
    # the frequencies at mu = 0: the structure with the contact spring (closed form of a 2x2)
    k0 = machine.stiffness + np.diag([0.0, 5e7])
    assert np.allclose(result.natural_frequencies_hz,
                       np.sqrt(np.linalg.eigvalsh(k0 / 0.1)) / (2 * math.pi), rtol=1e-12)


def test_velocity_weakening_law_is_negative_damping_on_the_tangential_dof() -> None:
    # linear law mu = mu_k - sigma v_r: slope -sigma, the damper -sigma N_0 on DOF t (the
    # engine's "-2 delta" slip damper of stickslip.model.friction.LinearFriction in SI). With
    # k12 = 0 the matrices are block triangular (only K[t, n] = mu k_n couples, one way) and
    # N_0 = W: the tangential block is m s^2 + (c - sigma W) s + k, unstable iff sigma W > c
    # (c = 40 N s/m, W = 1000 N: sigma = 0.04 s/m is the boundary)
    k = np.diag([1e6, 1e6])
    for sigma, unstable in ((0.03, False), (0.05, True)):
        machine = Machine(np.eye(2), np.diag([40.0, 40.0]), k, 0, 0.5, 0.4, 1000.0, 1.0,
                          PhysicalFriction("linear", slope=sigma))
        mu, slope = friction_at(machine)
        assert mu == pytest.approx(0.4 - sigma * 1.0) and slope == pytest.approx(-sigma)
        result = complex_eigenvalue_analysis(machine, Contact(normal_dof=1, normal_stiffness=1e6))
        assert result.normal_force == pytest.approx(1000.0)
        assert result.verdict == ("unstable" if unstable else "stable")


def test_stribeck_slope_is_the_laws_derivative_and_speed_enters_only_through_it() -> None:
    law = PhysicalFriction("stribeck", mu_0=0.5, stribeck_velocity=2.0, exponent=1.0)
    machine, contact = _brake_pad(law)
    mu, slope = friction_at(machine)
    # mu(v) = mu_k + (mu_0 - mu_k) exp(-v / v_s) at v = 5 m/s; its derivative
    assert mu == pytest.approx(0.4 + 0.1 * math.exp(-2.5), rel=1e-12)
    assert slope == pytest.approx(-0.1 / 2.0 * math.exp(-2.5), rel=1e-9)
    coulomb = complex_eigenvalue_analysis(*_brake_pad())
    ranges = operating_ranges(_brake_pad(c=(400.0, 400.0), mu_k=0.25)[0], contact, points=9)
    assert not ranges.unstable_speeds() and not ranges.unstable_loads()
    assert coulomb.slope == 0.0
    systems = [_brake_pad(law)[0].with_operating_point(speed=v) for v in (0.5, 5.0)]
    grid = stability_map([complex_eigenvalue_analysis(s, contact, n_scan=20).system for s in systems],
                         [0.5, 5.0], [0.0, 0.29], "speed [m/s]")
    # a falling Stribeck curve is steeper at low speed: more negative damping there
    assert grid.growth[0, 0] > grid.growth[1, 0]


def test_root_locus_marks_both_boundaries() -> None:
    machine, contact = _brake_pad()
    result = complex_eigenvalue_analysis(machine, contact, n_scan=100)
    locus = root_locus(result.system, np.linspace(0.0, 0.5, 51))
    assert locus.eigenvalues.shape == (51, 4)
    assert locus.critical_mu_undamped == pytest.approx(result.critical_undamped.mu, rel=1e-9)
    # below the damped boundary no branch grows, at 0.5 one does
    assert np.all(locus.eigenvalues[locus.mu < 0.29].real < 0.0)
    assert np.any(locus.eigenvalues[-1].real > 0.0)


def test_contact_refuses_bad_values_in_one_line() -> None:
    cases = [
        (dict(normal_dof=1), "needs [contact] normal_stiffness"),
        (dict(normal_stiffness=1e6), "go together"),
        (dict(normal_dof=1, normal_stiffness=-1.0), "must be positive"),
        (dict(normal_dof=1, normal_stiffness=0.0), "must be positive"),
        (dict(normal_dof=1, normal_stiffness=1.0, normal_damping=-2.0), "must not be negative"),
        (dict(normal_dof=-1, normal_stiffness=1.0), "whole number"),
        (dict(tangential_damping=1.0),
         "tangential_damping needs tangential_stiffness (the spring of the Jenkins element it"),
        (dict(tangential_stiffness=1e6, mass=0.0), "must be positive"),
    ]
    for kwargs, why in cases:
        with pytest.raises(ValueError) as info:
            Contact(**kwargs)  # type: ignore[arg-type]
        assert why in str(info.value) and "\n" not in str(info.value), (kwargs, info.value)
    contact = Contact(normal_dof=1, normal_stiffness=1.0)
    with pytest.raises(ValueError, match="is the contact_dof"):
        contact.check_dofs(2, 1)
    with pytest.raises(ValueError, match="beyond the 2 DOF"):
        Contact(normal_dof=2, normal_stiffness=1.0).check_dofs(2, 0)



def test_steady_sliding_past_self_locking_is_refused_as_a_wedge() -> None:
    # K[n, t] > 0: past the divergence point (det K_eff < 0) the steady state's normal force
    # N_0 = W - k_n q_0[n], q_0 = K_eff^-1 (mu W e_t), written out here for the 2x2, is negative.
    # Written out, N_0 = W / (1 + a mu) with a = k_n (K_0^-1)[n, t], K_0 = K + k_n e_n e_n^T:
    # here K_0 = [[1e6, 0.9e6], [0.9e6, 2e6]], (K_0^-1)[1, 0] = -0.9e6 / (2e12 - 0.81e12), so
    # the self-locking coefficient is -1/a = 1.19e12 / 0.9e12 = 1.3222..., where det K_eff = 0
    # and N_0 grows without bound; beyond it the friction wedges the slider into the belt (an
    # audit found it called lift-off, while the engine shows it stuck with a growing N)
    k = np.array([[1.0e6, 0.9e6], [0.9e6, 1.0e6]])
    kn, w, mu = 1.0e6, 1000.0, 2.0
    k_eff = k + np.array([[0.0, mu * kn], [0.0, kn]])
    n0 = w - kn * np.linalg.solve(k_eff, [mu * w, 0.0])[1]
    assert n0 < 0.0
    machine = Machine(np.eye(2), np.zeros((2, 2)), k, 0, 2.5, mu, w, 1.0)
    contact = Contact(normal_dof=1, normal_stiffness=kn)
    system = FrictionCoupledSystem(machine.mass, machine.damping, k, 0, 1, normal_stiffness=kn,
                                   load=w)
    assert system.normal_force(mu) == pytest.approx(n0, rel=1e-12)
    lock = 1.19e12 / 0.9e12
    assert system.self_locking_mu() == pytest.approx(lock, rel=1e-12)
    assert np.linalg.det(k + np.array([[0.0, lock * kn], [0.0, kn]])) == pytest.approx(0.0, abs=1e-3)
    assert system.normal_force(lock * (1.0 - 1e-9)) > 1e8 * w
    with pytest.raises(ValueError, match=(r"no steady sliding: mu = 2 is past the self-locking "
                                          r"coefficient 1\.32222.*N = -.*wedges the slider")):
        complex_eigenvalue_analysis(machine, contact)
    away = FrictionCoupledSystem(machine.mass, machine.damping, np.array([[1e6, -0.9e6],
                                                                           [-0.9e6, 1e6]]),
                                 0, 1, normal_stiffness=kn, load=w)
    assert away.self_locking_mu() is None  # K[n, t] < 0: a > 0, N_0 = W / (1 + a mu) > 0


@pytest.mark.slow
def test_brake_squeal_worked_example_prints_the_numbers_the_page_quotes(tmp_path: Path) -> None:
    # docs/brake_squeal.md quotes these lines of docs/brake_squeal_example.py
    proc = subprocess.run([sys.executable, str(ROOT / "docs" / "brake_squeal_example.py"), "--out",
                           str(tmp_path)], capture_output=True, text=True, check=True, timeout=600)
    out = proc.stdout
    assert "critical mu 0.30291579; undamped 0.30833333 (closed form 0.30833333)" in out
    assert "ratio 0: critical mu 0.3, 0.3, 0.3" in out
    assert "ratio 1: critical mu 0.30833," in out and ", 0.56667 at c" in out
    assert "ratio 0.1: critical mu 0.30275," in out and ", 0.32791 at c" in out
    assert "ratio 10: critical mu 0.30276," in out and "nan at c" in out
    assert "Stribeck, V = 0.1 m/s: slope -0.09048 s/m, critical mu 0.0" in out
    for name in ("locus", "damping", "map"):
        assert (tmp_path / f"brake_squeal_{name}.png").read_bytes()[:4] == b"\x89PNG"


def test_figures_follow_the_plotting_contract() -> None:
    # stickslip.plot.figure: data first, ax=None or given axes, TypeError on unknown keywords,
    # a PlotResult back, no pyplot figure left behind
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure

    from stickslip.plot.figure import PlotResult
    from stickslip.plot.stability import root_locus_plot, stability_map_plot

    machine, contact = _brake_pad()
    result = complex_eigenvalue_analysis(machine, contact, n_scan=50)
    locus = root_locus(result.system, np.linspace(0.0, 0.4, 21))
    grid = stability_map([result.system], [5.0], np.linspace(0.0, 0.4, 5), "speed [m/s]")
    fig = Figure()
    axes = list(fig.subplots(2, 1))
    drawn = root_locus_plot(locus, ax=axes)
    assert isinstance(drawn, PlotResult) and drawn.figure is fig and drawn.axes == axes
    assert len(axes[0].get_lines()) >= 2 and axes[1].get_xlabel() == "friction coefficient mu"
    assert isinstance(grid.plot(), PlotResult) and isinstance(locus.plot(), PlotResult)
    with pytest.raises(TypeError):
        root_locus_plot(locus, colour="red")  # type: ignore[call-arg]
    with pytest.raises(TypeError):
        stability_map_plot(grid, colour="red")  # type: ignore[call-arg]
    assert plt.get_fignums() == []
    # the map: growth of the one row equals the largest real part at each mu
    for j, mu in enumerate(grid.mu):
        assert grid.growth[0, j] == float(np.max(result.system.eigenvalues(float(mu))[0].real))


def test_without_a_normal_dof_the_undamped_spectrum_does_not_depend_on_mu(tmp_path: Path) -> None:
    # the friction force is mu W, a constant, so no mu couples the modes (it was scanned at 401
    # values, and the text printed "damping ratio -0" and "normal_dof None"): oracle, numpy's
    # eigenvalues at several mu
    k = np.array([[3.0e4, -1.0e4], [-1.0e4, 2.0e4]])
    system = FrictionCoupledSystem(np.diag([1.0, 2.0]), np.zeros((2, 2)), k, 0, None, load=100.0)
    spectra = [np.sort_complex(system.eigenvalues(mu)[0]) for mu in (0.0, 0.4, 1.7)]
    assert all(np.allclose(s, spectra[0], rtol=1e-12) for s in spectra)
    found = critical_friction(system)
    assert found.mu is None and found.method.startswith("exact")
    path = tmp_path / "m.toml"
    path.write_text('m = "2 kg"\nk = "50 kN/m"\nmu_s = 0.5\nmu_k = 0.3\nload = "500 N"\n'
                    'speed = "5 cm/s"\n', encoding="utf-8")
    from typer.testing import CliRunner

    from stickslip.cli.main import app

    result = CliRunner().invoke(app, ["stability", "--config", str(path)])
    assert result.exit_code == 0, result.output
    out = result.output
    assert "normal_dof none" in out and " -0 " not in out and "-0-" not in out
    assert "exact: without a normal DOF" in out
