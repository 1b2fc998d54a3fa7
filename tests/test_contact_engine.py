"""The exact contact engine (normal DOF, separation, Jenkins element) against independent answers.

Sources of the reference values:
- Eqs. (34)-(36) of the paper (``/work/shared/paper``; ``stickslip.analysis.theory``): the
  undamped 1 DOF stick-slip period and amplitude, and the exact damped boundary.
- scipy's ``expm`` of the augmented matrix, unbalanced, for the exact flow.
- An event-driven ``scipy.integrate.solve_ivp`` (DOP853, rtol 1e-11) written here from the
  equations in the docstring of ``stickslip.analysis.contact.engine``, sharing no code with it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
import scipy.linalg
from scipy.integrate import solve_ivp

from stickslip.analysis.contact._events import AffineFlow, Found, first_event
from stickslip.analysis.contact._modes import SEPARATED
from stickslip.analysis.contact.engine import ContactSystem, simulate_contact
from stickslip.analysis.theory import critical_lambda_exact
from stickslip.analysis.verdict import Verdict

MU_S, MU_K = 0.3, 0.2  # gamma = mu_k / (mu_s - mu_k) = 2, the paper's value


def slider(lam: float, zeta: float, **contact: float) -> ContactSystem:
    """The paper's 1 DOF slider (m = k = W = 1) at ``lambda`` and ``zeta``, with a contact."""
    speed = (MU_S - MU_K) / lam
    return ContactSystem(np.eye(1), np.array([[2.0 * zeta]]), np.eye(1), 0, None, 1.0, speed,
                         MU_S, MU_K, **contact)  # type: ignore[arg-type]


def test_the_exact_flow_is_the_exponential_of_the_augmented_matrix() -> None:
    # a 2 DOF mode with metres and m/s of very different sizes: the balanced exponential
    # must equal scipy's plain one, and a 1 DOF oscillator its closed form
    rng = np.random.default_rng(34)
    a = np.block([[np.zeros((2, 2)), np.eye(2)], [-np.diag([8e8, 2.5e8]), -np.diag([400.0, 4.0])]])
    c = np.array([0.0, 0.0, 1e4, -3e3])
    flow = AffineFlow(a, c)
    z0 = rng.normal(size=4) * np.array([1e-6, 1e-6, 1e-2, 1e-2])
    aug = np.zeros((5, 5))
    aug[:4, :4], aug[:4, 4] = a, c
    for t in (1e-6, 3.7e-5, 2e-4):
        plain = scipy.linalg.expm(aug * t)
        expected = plain[:4, :4] @ z0 + plain[:4, 4]
        assert np.allclose(flow.at(z0, t), expected, rtol=1e-10, atol=1e-12 * np.abs(expected).max())
    w = 3.0
    osc = AffineFlow(np.array([[0.0, 1.0], [-w * w, 0.0]]), np.array([0.0, 2.0]))
    for t in (0.1, 1.0, 7.5):
        x = 2.0 / w**2 + (1.0 - 2.0 / w**2) * math.cos(w * t) + 0.5 / w * math.sin(w * t)
        assert osc.at(np.array([1.0, 0.5]), t)[0] == pytest.approx(x, rel=1e-13)


@pytest.mark.parametrize("lam", [0.5, 3.0])
def test_undamped_slider_gives_the_papers_period_and_amplitude(lam: float) -> None:
    # Eqs. (34) and (35): f_ss / f_n = 1 / (1 + (lambda - atan lambda) / pi), A / A_n =
    # sqrt(1 + lambda^2), A_n = V / omega_n; m = k = 1 so omega_n = 1
    run = simulate_contact(slider(lam, 0.0))
    assert run.verdict is Verdict.STICK_SLIP and not run.separated
    period = 2.0 * math.pi * (1.0 + (lam - math.atan(lam)) / math.pi)
    speed = (MU_S - MU_K) / lam
    print(f"period {run.period_s!r} | Eq. 34 {period!r}; amplitude {run.amplitude_m / speed!r} "
          f"| Eq. 35 {math.sqrt(1 + lam * lam)!r}")
    assert run.period_s == pytest.approx(period, rel=1e-12)
    assert run.amplitude_m / speed == pytest.approx(math.sqrt(1.0 + lam * lam), rel=1e-12)


@pytest.mark.parametrize("zeta", [0.05, 0.1])
def test_rigid_contact_boundary_is_eq36(zeta: float) -> None:
    # the exact boundary of the paper's Eq. (36) (critical_lambda_exact)
    lam_c = critical_lambda_exact(zeta)
    assert simulate_contact(slider(0.98 * lam_c, zeta)).verdict is Verdict.STEADY_SLIDING
    assert simulate_contact(slider(1.02 * lam_c, zeta)).verdict is Verdict.STICK_SLIP


def test_stiff_damped_jenkins_element_gives_the_rigid_contact_back() -> None:
    # contact damping ratio 0.3: c_t = 2 * 0.3 * sqrt(k_t m); as k_t / k grows the verdicts
    # either side of Eq. (36) and the period of the rigid contact come back
    zeta, lam_c = 0.1, critical_lambda_exact(0.1)
    rigid = simulate_contact(slider(1.5 * lam_c, zeta))
    errors = []
    for ratio in (1e2, 1e3, 1e4):
        contact = {"tangential_stiffness": ratio, "tangential_damping": 0.6 * math.sqrt(ratio)}
        run = simulate_contact(slider(1.5 * lam_c, zeta, **contact))
        assert run.verdict is Verdict.STICK_SLIP
        errors.append(abs(run.period_s - rigid.period_s) / rigid.period_s)
    assert errors[0] > errors[1] > errors[2] and errors[2] < 1e-3, errors
    contact = {"tangential_stiffness": 1e4, "tangential_damping": 60.0}
    assert simulate_contact(slider(0.97 * lam_c, zeta, **contact)).verdict is Verdict.STEADY_SLIDING
    assert simulate_contact(slider(1.03 * lam_c, zeta, **contact)).verdict is Verdict.STICK_SLIP


def test_a_massive_contact_point_and_an_undamped_element_run() -> None:
    # the same element with a contact mass (a DOF of its own), and without damping (the
    # extension slaved to -s mu_k N / k_t in slip): both still stick-slip well above Eq. (36)
    lam = 3.0 * critical_lambda_exact(0.1)
    heavy = simulate_contact(slider(lam, 0.1, tangential_stiffness=100.0, tangential_damping=6.0,
                                    contact_mass=0.01))
    bare = simulate_contact(slider(lam, 0.1, tangential_stiffness=100.0))
    assert heavy.verdict is Verdict.STICK_SLIP and bare.verdict is Verdict.STICK_SLIP


# --- the independent oracle: rigid contact, normal DOF, lift-off (c_n = 0) -----------------

def terminal(fun: Any, kind: str) -> Any:
    """A solve_ivp event: terminal, crossing zero downwards, named ``kind``."""
    fun.terminal, fun.direction, fun.kind = True, -1.0, kind
    return fun


def event_driven(rhs: Callable[[str], Any], events: Callable[[str], list[Any]],
                 after: Callable[[str, np.ndarray], tuple[str, np.ndarray]], y: np.ndarray,
                 t_end: float, atol: Any, mode: str = "stick") -> list[tuple[str, float, np.ndarray]]:
    """Run mode by mode with solve_ivp (DOP853, rtol 1e-11) from ``mode``: ``(kind, t, state)``."""
    t, out = 0.0, []
    while t < t_end:
        sol = solve_ivp(rhs(mode), (t, t_end), y, method="DOP853", rtol=1e-11, atol=atol,
                        events=events(mode))
        if sol.status != 1:
            break
        hit = next(i for i, te in enumerate(sol.t_events) if te.size)
        kind = events(mode)[hit].kind
        t, y = float(sol.t_events[hit][0]), sol.y_events[hit][0].copy()
        out.append((kind, t, y.copy()))
        mode, y = after(kind, y)
    return out


def oracle(system: ContactSystem, t_end: float) -> list[tuple[str, float, np.ndarray]]:
    """Events ``(kind, t, state)`` of an event-driven solve_ivp run (diagonal mass, c_n = 0)."""
    m = np.diag(system.mass)
    k, c, t_dof, n_dof = system.stiffness, system.damping, system.tangential_dof, system.normal_dof
    assert n_dof is not None and system.normal_damping == 0.0
    kn, load, speed = system.normal_stiffness, system.load, system.speed

    def forces(y: np.ndarray, mode: str) -> tuple[np.ndarray, float]:
        q, v = y[:2], y[2:]
        f = -k @ q - c @ v
        normal = load - kn * q[n_dof] if mode != "sep" else 0.0
        f[n_dof] += -kn * q[n_dof] if mode != "sep" else -load
        if mode in ("slip+", "slip-"):
            f[t_dof] += (1.0 if mode == "slip+" else -1.0) * system.mu_k * normal
        return f, normal

    def rhs(mode: str) -> Callable[[float, np.ndarray], np.ndarray]:
        def f(_t: float, y: np.ndarray) -> np.ndarray:
            force, _ = forces(y, mode)
            acc = force / m
            if mode == "stick":
                acc[t_dof] = 0.0
            return np.concatenate([y[2:], acc])
        return f

    def events(mode: str) -> list[Any]:
        ev = terminal
        stick_force = lambda y: -forces(y, "stick")[0][t_dof]  # noqa: E731
        normal = lambda y: forces(y, mode)[1]  # noqa: E731
        if mode == "stick":
            return [ev(lambda _t, y: system.mu_s * normal(y) - stick_force(y), "break+"),
                    ev(lambda _t, y: system.mu_s * normal(y) + stick_force(y), "break-"),
                    ev(lambda _t, y: normal(y), "lift-off")]
        if mode == "sep":
            return [ev(lambda _t, y: kn * y[n_dof] - load, "re-contact")]
        sign = 1.0 if mode == "slip+" else -1.0
        return [ev(lambda _t, y: sign * (speed - y[2 + t_dof]), "re-stick"),
                ev(lambda _t, y: normal(y), "lift-off")]

    def contact_mode(y: np.ndarray) -> str:
        v_r = speed - y[2 + t_dof]
        if abs(v_r) > 1e-9 * speed:
            return "slip+" if v_r > 0 else "slip-"
        y = y.copy()
        y[2 + t_dof] = speed
        force, normal = forces(y, "stick")
        if abs(force[t_dof]) <= system.mu_s * normal:
            return "stick"
        return "slip+" if -force[t_dof] > 0 else "slip-"

    def after(kind: str, y: np.ndarray) -> tuple[str, np.ndarray]:
        mode = {"break+": "slip+", "break-": "slip-", "lift-off": "sep"}.get(kind) or contact_mode(y)
        if mode == "stick":
            y[2 + t_dof] = speed
        return mode, y

    # the start-up state sticks unless the damper's force at the belt speed already exceeds
    # the static limit (c V > mu_s W: a fast belt), then it slips from the start
    mode, y0 = after("start", system.startup_state())
    return event_driven(rhs, events, after, y0, t_end, 1e-12 * system.state_scale[:4], mode)


def two_dof(k12: float, kn: float, speed: float) -> ContactSystem:
    """A point mass with tangential and normal springs, coupled by k12, pressed through k_n."""
    return ContactSystem(np.eye(2), 0.05 * np.eye(2), np.array([[1.0, k12], [k12, 1.0]]), 0, 1,
                         1.0, speed, 0.8, 0.4, normal_stiffness=kn)


def brake_pad(speed: float, mu_s: float, mu_k: float) -> ContactSystem:
    """examples/brake_pad (Hoffmann et al. 2002 minimal model) at another speed and friction."""
    return ContactSystem(0.1 * np.eye(2), np.diag([40.0, 4.0]),
                         np.array([[8e7, -1.5e7], [-1.5e7, 2.5e7]]), 0, 1, 1000.0, speed,
                         mu_s, mu_k, normal_stiffness=5e7)


@pytest.mark.parametrize(("system", "lifts"), [(brake_pad(0.02, 0.5, 0.4), True),
                                               (two_dof(-0.4, 1.0, 0.05), False)],
                         ids=["brake pad, lift-off", "2 DOF, no lift-off"])
@pytest.mark.slow  # 10 s: out of the default run (kept under ten minutes)
def test_engine_agrees_with_an_event_driven_solve_ivp_oracle(system: ContactSystem,
                                                              lifts: bool) -> None:
    run = simulate_contact(system)
    assert run.verdict is Verdict.STICK_SLIP and run.separated is lifts
    ref = oracle(system, run.t_end * (1.0 + 1e-9))
    breaks = [(t, y) for kind, t, y in ref if kind == "break+"]
    period = breaks[-1][0] - breaks[-2][0]
    scale = system.state_scale[:4]
    assert np.max(np.abs(breaks[-1][1] - breaks[-2][1]) / scale) < 1e-6  # the oracle repeats too
    print(f"period: engine {run.period_s!r} | solve_ivp {period!r}")
    assert run.period_s == pytest.approx(period, rel=1e-7)
    names = {"break+": "breakaway forward", "break-": "breakaway backward", "re-stick": "belt speed"}
    assert [names.get(kind, kind) for kind, _, _ in ref] == [e.kind for e in run.events]


def test_steady_sliding_after_lift_offs_agrees_with_the_oracle() -> None:
    # below the flutter point (mu_k = 0.25 < 0.3083) the start-up lifts off a few times and
    # then slides steadily: the oracle sees the same events and none after the engine's bound
    system = brake_pad(1.0, 0.3, 0.25)
    run = simulate_contact(system)
    assert run.verdict is Verdict.STEADY_SLIDING and run.separated
    ref = oracle(system, 3.0 * run.t_end)
    assert len(ref) == len(run.events)
    assert all(e.t == pytest.approx(t, rel=1e-9) for e, (_, t, _) in zip(run.events, ref, strict=True))


def damped_contact_pad() -> ContactSystem:
    """The slow brake pad with a contact damper of 20 N s/m (lift-off by the damper)."""
    return ContactSystem(0.1 * np.eye(2), np.diag([40.0, 4.0]),
                         np.array([[8e7, -1.5e7], [-1.5e7, 2.5e7]]), 0, 1, 1000.0, 0.02,
                         0.5, 0.4, normal_stiffness=5e7, normal_damping=20.0)


def test_a_contact_damper_separates_without_pulling() -> None:
    # the damper lifts the pad off while the spring is still compressed; the contact then
    # comes back by the damper or by the spring, and never pulls (N >= 0 throughout)
    run = simulate_contact(damped_contact_pad(), t_max=0.03)
    kinds = {e.kind for e in run.events}
    assert run.separated and {"re-contact by the damper", "spring released"} <= kinds
    forces = run.history(np.linspace(0.0, run.t_end, 4001))["normal_force_N"]
    assert min(forces) >= 0.0


@pytest.mark.slow
def test_a_contact_damper_pad_settles_on_stick_slip_with_separation() -> None:
    run = simulate_contact(damped_contact_pad(), t_max=0.5)  # 1.4 % closer a period: slow
    assert run.separated and run.verdict is Verdict.STICK_SLIP


def test_bad_input_to_the_engine() -> None:
    with pytest.raises(ValueError, match="mu_s > mu_k"):
        ContactSystem(np.eye(1), np.zeros((1, 1)), np.eye(1), 0, None, 1.0, 1.0, 0.2, 0.3)
    with pytest.raises(ValueError, match="t_max"):
        simulate_contact(slider(1.0, 0.1), t_max=-1.0)
    # a bad-input audit: k_t = 1e30 N/m on a 1 N/m slider gave a "period" of 1.6e-13 s
    with pytest.raises(ValueError, match=r"tangential_stiffness = 1e\+30 N/m is beyond 1e\+12 times"):
        ContactSystem(np.eye(1), np.zeros((1, 1)), np.eye(1), 0, None, 1.0, 1.0, 0.3, 0.2,
                      tangential_stiffness=1e30, tangential_damping=1.0)


@pytest.mark.parametrize("depth", [1e-10, 0.0])
def test_a_root_between_samples_is_not_skipped(depth: float) -> None:
    # x = cos(t - 1) rises to its maximum 1 at t = 1; g = 1 - depth - x is negative only on
    # |t - 1| < acos(1 - depth) (2.8e-5 s wide for depth 1e-10, a touch for depth 0), far
    # inside one sample interval (||A|| h = 0.25): the bound on g'' must still find it
    flow = AffineFlow(np.array([[0.0, 1.0], [-1.0, 0.0]]), np.zeros(2))
    z0 = np.array([math.cos(-1.0), -math.sin(-1.0)])
    found = first_event(flow, z0, np.array([[-1.0, 0.0]]), np.array([1.0 - depth]), 3.0,
                        max_samples=10_000)
    assert isinstance(found, Found)
    expected = 1.0 - math.acos(1.0 - depth)
    # a touch is located to sqrt(eps) (1 - cos(t - 1) is rounding there), a crossing far better
    assert found.dt == pytest.approx(expected, abs=1e-9 if depth else 1e-7)


def jenkins_oracle(lam: float, zeta: float, kt: float, ct: float, t_end: float
                   ) -> list[tuple[str, float]]:
    """Events of the 1 DOF slider (m = k = W = 1) on a massless Jenkins element, by solve_ivp.

    State ``(x, v, e)``: in stick the point moves with the belt (``e' = v - V``) and the belt
    force is ``F = -(k_t e + c_t e')``; in slip ``F = s mu_k`` and ``k_t e + c_t e' = -F``;
    the point's velocity is ``v - e'``.
    """
    speed = (MU_S - MU_K) / lam

    def e_rate(y: np.ndarray, mode: str) -> float:
        if mode == "stick":
            return y[1] - speed
        return (-(1.0 if mode == "slip+" else -1.0) * MU_K - kt * y[2]) / ct

    def belt(y: np.ndarray, mode: str) -> float:
        return -(kt * y[2] + ct * e_rate(y, mode))

    def rhs(mode: str) -> Callable[[float, np.ndarray], np.ndarray]:
        return lambda _t, y: np.array([y[1], -y[0] - 2.0 * zeta * y[1] + belt(y, mode),
                                       e_rate(y, mode)])

    def events(mode: str) -> list[Any]:
        ev = terminal
        if mode == "stick":
            return [ev(lambda _t, y: MU_S - belt(y, "stick"), "break+"),
                    ev(lambda _t, y: MU_S + belt(y, "stick"), "break-")]
        sign = 1.0 if mode == "slip+" else -1.0
        return [ev(lambda _t, y: sign * (speed - (y[1] - e_rate(y, mode))), "belt speed")]

    def after(kind: str, y: np.ndarray) -> tuple[str, np.ndarray]:
        # massless: at the belt speed the stick force equals the slip force, inside the cone
        return {"break+": "slip+", "break-": "slip-"}.get(kind, "stick"), y

    run = event_driven(rhs, events, after, np.array([0.0, speed, 0.0]), t_end, 1e-13 * speed)
    return [(kind, t) for kind, t, _ in run]


@pytest.mark.parametrize(("lam", "verdict"), [(1.50, Verdict.STEADY_SLIDING),
                                              (1.62, Verdict.STICK_SLIP)])
def test_jenkins_element_agrees_with_a_solve_ivp_oracle(lam: float, verdict: Verdict) -> None:
    # k_t / k = 10, contact damping ratio 0.3, zeta = 0.1: either side of the measured
    # boundary lambda_c = 1.5568 (docs/brake_squeal.md), the oracle's events and period
    kt, ct = 10.0, 0.6 * math.sqrt(10.0)
    run = simulate_contact(slider(lam, 0.1, tangential_stiffness=kt, tangential_damping=ct))
    assert run.verdict is verdict
    ref = jenkins_oracle(lam, 0.1, kt, ct, run.t_end * (1.0 + 1e-9))
    names = {"break+": "breakaway forward", "break-": "breakaway backward"}
    assert [names.get(kind, kind) for kind, _ in ref] == [e.kind for e in run.events]
    assert all(e.t == pytest.approx(t, rel=1e-8) for e, (_, t) in zip(run.events, ref, strict=True))
    if verdict is Verdict.STICK_SLIP:
        breaks = [t for kind, t in ref if kind == "break+"]
        assert run.period_s == pytest.approx(breaks[-1] - breaks[-2], rel=1e-8)


@pytest.mark.parametrize("speed", [100.0, 1.0e4])
def test_a_fast_pad_without_a_contact_damper_lifts_off_and_comes_back(speed: float) -> None:
    # found by a bad-input audit: at 100 m/s the located lift-off left a compression above the
    # force tolerance, no re-contact was watched and the run ended in an IndexError; at 1e4 m/s
    # a lift-off and a re-contact 1.3e-18 s apart were reported as a period. Oracle: the
    # event-driven solve_ivp integration above, over the first events.
    system = brake_pad(speed, 0.5, 0.4)
    separated = system.mode(SEPARATED)
    z = system.enter(SEPARATED, np.zeros(system.n_state))
    assert [k for _, k in separated.rows] == ["re-contact"]
    assert separated.surfaces(z)[2] == ["re-contact"]  # compressed at rest: watched all the same
    run = simulate_contact(system)
    assert run.separated
    assert run.period_s is None or run.period_s > 1e-9 * run.t_end
    first = run.events[:12]
    ref = oracle(system, first[-1].t * (1.0 + 1e-9))
    print(f"{speed} m/s: {[(e.kind, e.t) for e in first]} | solve_ivp {[(k, t) for k, t, _ in ref]}")
    names = {"break+": "breakaway forward", "break-": "breakaway backward", "re-stick": "belt speed"}
    assert [names.get(k, k) for k, _, _ in ref][:len(first)] == [e.kind for e in first]
    assert all(e.t == pytest.approx(t, rel=1e-8) for e, (_, t, _) in zip(first, ref, strict=False))


#: A pad past self-locking (an audit's machine: springs 1e6 N/m, a contact spring 5e7 N/m at
#: 70 degrees, k_n = 5e7 N/m, mu_k = 0.6 above the self-locking coefficient 0.4897)
WEDGE_K = np.array([[6848888.922025552, 16069690.242163485],
                    [16069690.242163485, 45151111.07797444]])


def wedged_pad() -> ContactSystem:
    return ContactSystem(0.1 * np.eye(2), np.diag([40.0, 4.0]), WEDGE_K, 0, 1, 1000.0, 5.0, 0.8,
                         0.6, normal_stiffness=5e7)


def test_a_run_out_of_samples_reports_the_time_it_reached() -> None:
    # the wedged pad sticks for good after its second event; a run that spends its sample
    # budget in that stick phase reached the sampled time, not the phase's start (an audit:
    # t = 0.000115 s printed for a run that had got beyond 100 s). Doubling the budget doubles
    # the time reached, to within one chunk of samples
    runs = [simulate_contact(wedged_pad(), t_max=1e300, max_samples=n) for n in (5_000, 10_000)]
    for run, n in zip(runs, (5_000, 10_000), strict=True):
        assert run.verdict is Verdict.UNDETERMINED and len(run.events) == 2
        assert run.samples <= n and f"sample budget of {n} exhausted at t = " in run.certificate
        assert run.t_end > 100.0 * run.events[-1].t
    assert runs[1].t_end == pytest.approx(2.0 * runs[0].t_end, rel=0.05)


def test_simulate_of_a_wedged_pad_says_why_it_has_no_verdict(
        tmp_path: Any, capsys: pytest.CaptureFixture[str]) -> None:
    # N_0 = W / (1 + a mu) with a = k_n (K_0^-1)[n, t] (docs/brake_squeal.md): -1/a, computed
    # here with numpy, is where steady sliding self-locks
    from tests.cli_helpers import run_cli

    k0 = WEDGE_K + np.diag([0.0, 5e7])
    lock = -1.0 / (5e7 * np.linalg.inv(k0)[1, 0])
    assert 0.48 < lock < 0.6
    for name, matrix in (("M", 0.1 * np.eye(2)), ("C", np.diag([40.0, 4.0])), ("K", WEDGE_K)):
        np.savetxt(tmp_path / f"{name}.csv", matrix, delimiter=",")
    (tmp_path / "machine.toml").write_text(
        'mu_s = 0.8\nmu_k = 0.6\nload = "1 kN"\nspeed = "5 m/s"\n[structure]\nmass = "M.csv"\n'
        'stiffness = "K.csv"\ndamping = "C.csv"\ncontact_dof = 0\nnormal_dof = 1\n[contact]\n'
        'normal_stiffness = "5e7 N/m"\n')
    code, out, err = run_cli(["simulate", "--config", str(tmp_path / "machine.toml"), "--t-max",
                              "0.01 s"], capsys)
    assert code == 0, err
    assert "verdict     undetermined" in out
    assert f"is at or past the self-locking coefficient {lock:.6g}" in out
    code, _, err = run_cli(["stability", "--config", str(tmp_path / "machine.toml")], capsys)
    assert code == 2 and f"past the self-locking coefficient {lock:.6g}" in err
    assert "wedges the slider into the belt" in err and "lifts" not in err
