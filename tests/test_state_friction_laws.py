"""Friction laws with memory (issue 33.1): validation, the regularised form, the kernel's derivatives.

Sources: the classic rate-and-state law and its steady state (Dieterich 1979, Ruina 1983:
``mu_ss = mu_ref + (a - b) ln(V/v_ref)``, ``theta_ss = d_c/V``); the regularised form equals it
to ``a/(2 X^2)`` (its series ``asinh X = ln 2X + 1/(4 X^2) + ...``); LuGre's steady state
``F = g(V) + sigma2 V`` (Canudas de Wit et al. 1995, Eq. 5). The kernel's first and second
partial derivatives are checked against central differences of its own values.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from stickslip.kernel import stiff
from stickslip.model.state_friction import (
    LuGreFriction,
    MemorySystem,
    RateStateFriction,
    SpeedSchedule,
)
from stickslip.model.state_friction_input import (
    parse_state_friction,
    speed_schedule_from_config,
    state_friction_from_table,
)

RS = dict(a=0.01, b=0.015, d_c=1e-5, mu_ref=0.6, v_ref=1e-6)
LUGRE = dict(sigma0=1e5, sigma1=math.sqrt(1e5), sigma2=0.4, mu_c=1.0, mu_s=1.5,
             stribeck_velocity=1e-3)


@pytest.mark.parametrize(("change", "needle"), [
    ({"a": 0.0}, "a=0.0 must be positive"),
    ({"a": -0.01}, "a=-0.01 must be positive"),
    ({"d_c": 0.0}, "d_c=0.0 must be positive"),
    ({"b": -1.0}, "b=-1.0 must not be negative"),
    ({"v_ref": 0.0}, "v_ref=0.0 must be positive"),
    ({"evolution": "ageing"}, "evolution='ageing' must be 'aging' or 'slip'"),
    ({"a": 1e-4, "mu_ref": 0.6}, "exceeds 500"),
])
def test_rate_state_refuses_bad_parameters(change: dict[str, object], needle: str) -> None:
    with pytest.raises(ValueError) as info:
        RateStateFriction(**{**RS, **change})  # type: ignore[arg-type]
    assert needle in str(info.value)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize(("change", "needle"), [
    ({"sigma0": 0.0}, "sigma0=0.0 must be positive"),
    ({"sigma0": -1.0}, "sigma0=-1.0 must be positive"),
    ({"sigma1": -1.0}, "sigma1=-1.0 must not be negative"),
    ({"mu_s": 0.5}, "mu_s=0.5 must be at least mu_c=1.0"),
    ({"stribeck_velocity": 0.0}, "stribeck_velocity=0.0 must be positive"),
])
def test_lugre_refuses_bad_parameters(change: dict[str, object], needle: str) -> None:
    with pytest.raises(ValueError) as info:
        LuGreFriction(**{**LUGRE, **change})  # type: ignore[arg-type]
    assert needle in str(info.value)


def test_regularised_law_is_the_classic_law_away_from_zero() -> None:
    # classic: mu = mu_ref + a ln(v/v_ref) + b ln(v_ref theta/d_c) with psi = mu_ref + b ln(v_ref theta/d_c)
    law = RateStateFriction(**RS)
    for v in (1e-9, 1e-6, 1e-3, 1.0):
        for theta in (1e-2, 10.0, 1e4):
            psi = law.mu_ref + law.b * math.log(law.v_ref * theta / law.d_c)
            classic = psi + law.a * math.log(v / law.v_ref)
            assert law.mu(v, psi) == pytest.approx(classic, rel=1e-14, abs=1e-15)
    # odd in v and zero at rest: the regularisation near v = 0
    assert law.mu(0.0, 0.6) == 0.0
    assert law.mu(-1e-6, 0.6) == -law.mu(1e-6, 0.6)


def test_steady_states() -> None:
    law = RateStateFriction(**RS)
    v = 1e-4
    psi = law.steady_state(v, 1.0)
    assert law.theta(psi) == pytest.approx(law.d_c / v, rel=1e-13)
    assert law.steady_mu(v) == pytest.approx(law.mu_ref + (law.a - law.b) * math.log(v / law.v_ref),
                                             rel=1e-13)
    lugre = LuGreFriction(**LUGRE)
    v = 0.1
    g = 1.0 + 0.5 * math.exp(-((v / 1e-3) ** 2))
    assert lugre.steady_state(v, 1.0) == pytest.approx(g / 1e5, rel=1e-15)
    assert lugre.steady_mu(v, 1.0) == pytest.approx(g + 0.4 * v, rel=1e-15)


def _values(law: int, p: np.ndarray, v: float, s: float) -> np.ndarray:
    out = np.empty(stiff.N_LAW)
    stiff.law_values(law, p, v, s, out)
    return out


@pytest.mark.parametrize(("code", "p", "v", "s"), [
    (stiff.LAW_RATE_STATE_AGING, RateStateFriction(**RS).parameters(2.0), 3e-6, 0.61),
    (stiff.LAW_RATE_STATE_AGING, RateStateFriction(**RS).parameters(2.0), 1e-7, 0.62),
    (stiff.LAW_RATE_STATE_SLIP, RateStateFriction(**RS, evolution="slip").parameters(2.0), 3e-6, 0.61),
    (stiff.LAW_RATE_STATE_SLIP, RateStateFriction(**RS, evolution="slip").parameters(2.0), -2e-6, 0.58),
    (stiff.LAW_LUGRE, LuGreFriction(**LUGRE).parameters(1.0), 8e-4, 1.2e-5),
    (stiff.LAW_LUGRE, LuGreFriction(**LUGRE).parameters(1.0), -3e-4, -4e-6),
])
def test_kernel_derivatives_match_differences(code: int, p: np.ndarray, v: float, s: float) -> None:
    """First and second partials of F and G (the exact Jacobian and the variational block)."""
    base = _values(code, p, v, s)
    hv = 1e-6 * max(abs(v), 1e-12)
    hs = 1e-6 * max(abs(s), 1e-9)
    dv = (_values(code, p, v + hv, s) - _values(code, p, v - hv, s)) / (2 * hv)
    ds = (_values(code, p, v, s + hs) - _values(code, p, v, s - hs)) / (2 * hs)
    pairs = [(stiff.L_FV, dv, stiff.L_F), (stiff.L_FS, ds, stiff.L_F), (stiff.L_GV, dv, stiff.L_G),
             (stiff.L_GS, ds, stiff.L_G), (stiff.L_FVV, dv, stiff.L_FV),
             (stiff.L_FVS, ds, stiff.L_FV), (stiff.L_FSS, ds, stiff.L_FS),
             (stiff.L_GVV, dv, stiff.L_GV), (stiff.L_GVS, ds, stiff.L_GV),
             (stiff.L_GSS, ds, stiff.L_GS)]
    for analytic, diff, of in pairs:
        scale = max(abs(base[analytic]), abs(diff[of]), 1e-300)
        assert abs(base[analytic] - diff[of]) <= 1e-5 * scale, (analytic, base[analytic], diff[of])


def test_machine_file_tables_and_units() -> None:
    law = state_friction_from_table({"law": "rate-state", "a": 0.01, "b": 0.015, "d_c": "10 um",
                                     "mu_ref": 0.6, "v_ref": "1 um/s", "evolution": "slip"})
    assert isinstance(law, RateStateFriction)
    assert law.d_c == pytest.approx(1e-5) and law.v_ref == pytest.approx(1e-6)
    assert law.evolution == "slip"
    lugre = state_friction_from_table({"law": "lugre", "sigma0": "100 kN/m", "sigma1": "316 N*s/m",
                                       "sigma2": "0.4 N*s/m", "mu_c": 1.0, "mu_s": 1.5,
                                       "stribeck_velocity": "1 mm/s"})
    assert isinstance(lugre, LuGreFriction)
    assert lugre.sigma0 == pytest.approx(1e5) and lugre.stribeck_velocity == pytest.approx(1e-3)
    for table, needle in [
        ({"law": "rate-state", "a": 0.01, "b": 0.01, "d_c": "0 m", "mu_ref": 0.6, "v_ref": "1 um/s"},
         "d_c=0.0 must be positive"),
        ({"law": "rate-state", "a": 0.01, "b": 0.01, "d_c": "1 kg", "mu_ref": 0.6, "v_ref": 1e-6},
         "wrong unit"),
        ({"law": "rate-state", "a": 0.01}, "needs b, d_c, mu_ref, v_ref"),
        ({"law": "lugre", **{k: v for k, v in LUGRE.items()}, "slope": 1.0}, "unknown keys slope"),
        ({"law": "lugre", **{**LUGRE, "sigma0": "-1 N/m"}}, "sigma0=-1.0 must be positive"),
    ]:
        with pytest.raises(ValueError) as info:
            state_friction_from_table(table, source="[friction]")
        assert needle in str(info.value), str(info.value)
        assert str(info.value).startswith("[friction]")


def test_speed_schedule() -> None:
    sched = speed_schedule_from_config([["0 s", "1 um/s"], ["10 s", "10 um/s"]], source="speed")
    assert sched.times == (0.0, 10.0)
    assert sched.speeds == pytest.approx((1e-6, 1e-5))
    for value, needle in [([["1 s", "1 um/s"]], "starts at 0 s"),
                          ([["0 s", "1 um/s"], ["0 s", "2 um/s"]], "must increase"),
                          ([["0 s", "-1 um/s"]], "must be positive"),
                          ([["0 s"]], "must be a pair"),
                          ([["0 s", "1 kg"]], "wrong unit"),
                          ([["0 s", "0 um/s"], ["1 s", "1 um/s"]], "first and the last"),
                          ([["0 s", "1 um/s"], ["1 s", "0 um/s"]], "first and the last"),
                          ([["0 s", "1 um/s"], ["1 s", "-1 um/s"], ["2 s", "1 um/s"]],
                           "may hold at 0 between two slides")]:
        with pytest.raises(ValueError) as info:
            speed_schedule_from_config(value, source="speed")
        assert needle in str(info.value), str(info.value)


def test_speed_schedule_holds_between_slides() -> None:
    # slide-hold-slide, the healing test of rate-and-state laboratories (Dieterich 1972)
    sched = speed_schedule_from_config([["0 s", "10 um/s"], ["5 s", "0 um/s"],
                                        ["15 s", "10 um/s"]], source="speed")
    assert sched.speeds == pytest.approx((1e-5, 0.0, 1e-5))


def test_dimensionless_command_line_syntax() -> None:
    law = parse_state_friction("rate-state", "a=0.01,b=0.015,dc=0.1,mu_ref=0.6,vref=1,evolution=slip",
                               "rate-state:...")
    assert isinstance(law, RateStateFriction) and law.evolution == "slip" and law.d_c == 0.1
    lugre = parse_state_friction("lugre", "sigma0=1e5,sigma1=316,sigma2=0.4,mu_c=1,mu_s=1.5,vs=0.01",
                                 "lugre:...")
    assert isinstance(lugre, LuGreFriction) and lugre.stribeck_velocity == 0.01
    with pytest.raises(ValueError, match="needs"):
        parse_state_friction("rate-state", "a=0.01", "rate-state:a=0.01")
    with pytest.raises(ValueError, match=r"a=0\.0 must be positive"):
        parse_state_friction("rate-state", "a=0,b=0.015,dc=0.1,mu_ref=0.6,vref=1", "x")


def test_quasi_static_slider_is_rate_state_only() -> None:
    sched = SpeedSchedule.constant(1e-6)
    with pytest.raises(ValueError, match=r"needs law = \"rate-state\""):
        MemorySystem(np.zeros((1, 1)), np.zeros((1, 1)), np.ones((1, 1)), 0, 1.0,
                     LuGreFriction(**LUGRE), sched)
    with pytest.raises(ValueError, match="takes no damping"):
        MemorySystem(np.zeros((1, 1)), np.ones((1, 1)), np.ones((1, 1)), 0, 1.0,
                     RateStateFriction(**RS), sched)
    qs = MemorySystem(np.zeros((1, 1)), np.zeros((1, 1)), np.ones((1, 1)), 0, 1.0,
                      RateStateFriction(**RS), sched)
    assert qs.quasi_static
