"""Identification of each friction law, undetermined parameters, ``auto`` and BLAS threads (issue 19).

Every record is made by the independent SI simulator of ``tests/record_oracle.py``
(event-driven ``solve_ivp`` written from the rig's equations in physical units; neither the
engine nor the dimensionless mapping) with known parameters and white noise of a stated
fraction of each signal's peak-to-peak range. The rig is the one of
``tests/test_identification.py``: 1 kg, k = 10 kN/m, c = 5 N s/m, mu_s = 0.6, W = 100 N,
V = 5 cm/s. The claims are the issue's: every true value inside three standard errors;
``k``, ``mu_s`` and ``mu_k`` within 1 % at 0.5 % noise; what a record cannot determine comes
back as ``None`` by the documented rule (``UNDETERMINED_RULE``).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from threadpoolctl import threadpool_info

from stickslip.analysis.blas_threads import blas_limited as _blas_limited
from stickslip.analysis.identification.record_fit import (
    TABLE_QUANTILES,
    MeasuredRecord,
    identify,
    table_knots,
    visited_knots,
)
from tests.cli_helpers import run_cli
from tests.record_oracle import coulomb, linear, noisy, simulate_rig, stribeck

M, K, C, MU_S, MU_K, W, V = 1.0, 1.0e4, 5.0, 0.6, 0.4, 100.0, 0.05
KNOWN = {"m": M, "load": W, "speed": V}
STRENGTHENING = 0.1  # s/m: mu = mu_k + 0.1 s/m v_r


def _record(mu, *, noise=0.005, seed=21, t_end=0.93, fs=2000.0, channels=("F", "x")):
    rig = simulate_rig(m=M, k=K, c=C, mu_s=MU_S, mu=mu, load=W, speed=V, t_end=t_end, fs=fs, t_start=0.23)
    rng = np.random.default_rng(seed)
    return rig, MeasuredRecord(rig.t, **{n: noisy(getattr(rig, n), noise, rng) for n in channels})


def _within(result, truth, *, rel=None, n_se=3.0):
    """Each true value inside ``n_se`` standard errors; ``k``, ``mu_s``, ``mu_k`` within ``rel``."""
    for name, value in truth.items():
        p = result.parameters[name]
        assert p.value is not None, f"{name} undetermined: {result.summary()}"
        assert abs(p.value - value) <= n_se * p.stderr, f"{name} = {p.value} +/- {p.stderr} vs {value}"
        if rel is not None and name in ("k", "mu_s", "mu_k"):
            assert abs(p.value - value) <= rel * abs(value), f"{name} = {p.value} vs {value}"


# ----------------------------------------------------------------------------- table law: knots
def test_table_knots_are_quantiles_of_the_slip_speeds():
    """Sliding speeds uniform on [0, 0.3] m/s (and stick samples at 0): the knots are 0 and
    the quantiles q of the uniform law, 0.3 q (closed form), to the sampling's resolution."""
    v_r = np.concatenate([np.zeros(500), np.linspace(0.0, 0.3, 3001)[1:]])
    knots = table_knots(v_r, V)
    assert knots[0] == 0.0
    assert knots[1:] == pytest.approx([0.3 * q for q in TABLE_QUANTILES], abs=2e-4)
    with pytest.raises(ValueError, match="no slip phase"):
        table_knots(np.zeros(10), V)


def test_visited_knots_midpoint_rule():
    """Knot i is reached when the largest sliding speed passes (v_{i-1} + v_i) / 2."""
    assert visited_knots((0.0, 0.1, 0.2, 0.4), 0.29) == [True, True, True, False]
    assert visited_knots((0.0, 0.1, 0.2, 0.4), 0.31) == [True, True, True, True]
    assert visited_knots((0.0, 0.1), 0.01) == [True, False]


@pytest.fixture(scope="module")
def strengthening_table_fit():
    """A velocity-strengthening contact, mu = 0.4 + 0.1 s/m v_r (linear law with a negative
    slope), mu_s = 0.6 > mu(0+) = 0.4 so it stick-slips through the static/kinetic drop; a
    table fit with the default knots. The truth is linear in v_r, so a piecewise-linear
    table through any knots represents it exactly: knot i's true value is 0.4 + 0.1 v_i.
    (A stronger strengthening, 0.2 s/m with this rig's damping, sends the slider into a
    slip that barely returns to the belt speed, which the oracle resolves too slowly.)"""
    rig, rec = _record(linear(MU_K, -STRENGTHENING), seed=22)
    return rig, identify(rec, KNOWN, law="table")


def test_table_law_recovers_a_strengthening_curve(strengthening_table_fit):
    rig, result = strengthening_table_fit
    knots = result.table_v
    v_max = float(np.max(V - rig.v))
    assert knots[0] == 0.0 and len(knots) == 1 + len(TABLE_QUANTILES)
    # knots inside the record's sliding speeds (the last one the largest the model reaches)
    assert knots[-1] == pytest.approx(v_max, rel=0.05)
    assert all(result.table_visited)
    truth = {f"table_mu_{i}": MU_K + STRENGTHENING * v for i, v in enumerate(knots)}
    _within(result, {"k": K, "mu_s": MU_S, **truth}, rel=0.01)
    # a standard error per knot; mu_k of a table is its lowest determined knot
    values = [result.parameters[f"table_mu_{i}"].value for i in range(len(knots))]
    assert all(result.parameters[f"table_mu_{i}"].stderr > 0 for i in range(len(knots)))
    assert result.parameters["mu_k"].value == min(values)
    payload = result.to_dict()
    json.dumps(payload)
    assert payload["table_v"] == list(knots) and payload["table_visited"] == [True] * len(knots)


@pytest.mark.slow
def test_table_knots_beyond_the_record_are_undetermined():
    """Knots given by the user at 0, 5, 15 cm/s and 1 and 2 m/s: the record slides at most
    about 0.23 m/s, so the last two knots (midpoints 0.575 and 1.5 m/s not reached) come back
    null, the others within three standard errors of the truth 0.4 + 0.1 v; the machine
    file's table leaves the undetermined knots out (the engine holds the last value)."""
    rig, rec = _record(linear(MU_K, -STRENGTHENING), seed=23)
    assert float(np.max(V - rig.v)) < 0.5 * (0.15 + 1.0)
    speeds = (0.0, 0.05, 0.15, 1.0, 2.0)
    result = identify(rec, KNOWN, law="table", table_speeds=speeds)
    assert result.table_v == speeds
    assert result.table_visited == (True, True, True, False, False)
    assert result.parameters["table_mu_3"].value is None and result.parameters["table_mu_4"].value is None
    assert {"table_mu_3", "table_mu_4"} <= set(result.undetermined)
    _within(result, {f"table_mu_{i}": MU_K + STRENGTHENING * speeds[i] for i in range(3)})
    assert "2 (not reached) m/s" in result.summary()
    rows = result.table_csv().strip().splitlines()
    assert rows[0] == "v,mu" and len(rows) == 4
    assert "table =" in result.to_config()


def test_table_speeds_are_checked():
    _rig, rec = _record(coulomb(MU_K), t_end=0.5)
    with pytest.raises(ValueError, match="increase strictly"):
        identify(rec, KNOWN, law="table", table_speeds=(0.0, 0.1, 0.1))
    with pytest.raises(ValueError, match="table law"):
        identify(rec, KNOWN, law="linear", table_speeds=(0.0, 0.1))


# ----------------------------------------------------------------------------- the rule
def test_undetermined_rule_for_shape_and_table_parameters():
    """UNDETERMINED_RULE's standard-error part, at its thresholds: a Stribeck shape parameter
    is undetermined above half its value; a table value and mu_k above mu_s (not above their
    own value, which may be near zero); k above its value."""
    from stickslip.analysis.identification.result import undetermined

    values = {"k": K, "mu_s": MU_S, "mu_k": MU_K, "c": C}
    for name in ("exponent", "stribeck_velocity"):
        assert undetermined(name, 2.0, 0.99, values, mass=M, speed=V) is False
        assert undetermined(name, 2.0, 1.01, values, mass=M, speed=V) is True
    assert undetermined("table_mu_3", 0.01, 0.05, values, mass=M, speed=V) is False
    assert undetermined("table_mu_3", 0.01, 0.61, values, mass=M, speed=V) is True
    assert undetermined("k", K, 0.9 * K, values, mass=M, speed=V) is False
    assert undetermined("k", K, 1.1 * K, values, mass=M, speed=V) is True
    assert undetermined("force_offset", 0.0, 1e9, values, mass=M, speed=V) is False


# ----------------------------------------------------------------------------- strengthening
@pytest.mark.parametrize("noise, rel", [(0.005, 0.01), (0.02, 0.05)])
def test_linear_strengthening_law(noise, rel):
    """mu = 0.4 + 0.1 s/m v_r (slope -0.1 s/m in the machine file's mu_k - slope v_r),
    mu_s = 0.6: the fit recovers the strengthening, a slope whose sign the record
    determines (the truth inside three standard errors, zero far outside them)."""
    _rig, rec = _record(linear(MU_K, -STRENGTHENING), noise=noise, seed=24, t_end=1.23)
    result = identify(rec, KNOWN, law="linear")
    _within(result, {"k": K, "c": C, "mu_s": MU_S, "mu_k": MU_K, "slope": -STRENGTHENING}, rel=rel)
    slope = result.parameters["slope"]
    assert slope.value < -3.0 * slope.stderr


# ----------------------------------------------------------------------------- Stribeck, 5 parameters
@pytest.mark.slow
def test_stribeck_five_parameters_determined():
    """mu = 0.35 + 0.25 exp(-(v_r / 5 cm/s)^2), no viscous term, all five friction parameters
    free: the record's sliding speeds (up to about 0.33 m/s) bracket v_s, so every one is
    determined and inside three standard errors of the truth; k and mu_s within 1 %. The
    kinetic mu_k trades against the viscous slope (correlation near -1): its standard error
    (about 2 % here) is what 7 cycles at 2 kHz support, and the truth lies within it."""
    _rig, rec = _record(stribeck(0.35, MU_S, 0.05, 2.0, 0.0), seed=10, t_end=1.23)
    result = identify(rec, KNOWN, law="stribeck")
    assert result.undetermined == []
    _within(result, {"k": K, "c": C, "mu_s": MU_S}, rel=0.01)
    _within(result, {"mu_k": 0.35, "stribeck_velocity": 0.05, "exponent": 2.0, "viscous": 0.0})


@pytest.mark.slow
def test_stribeck_exponent_undetermined_when_the_record_misses_v_s():
    """v_s = 3 mm/s while the record slides at up to about 0.3 m/s: the curve has fallen to
    mu_k within the first percent of each slip phase, so few samples see its shape and the
    exponent (and v_s) are undetermined by the rule (relative standard error above 0.5, or an
    optimum on the search limit), reported as null, never as a number; k and mu_s stay
    determined within 1 %."""
    _rig, rec = _record(stribeck(0.35, MU_S, 0.003, 1.0, 0.0), seed=10, t_end=1.23)
    result = identify(rec, KNOWN, law="stribeck")
    assert result.parameters["exponent"].value is None
    assert result.parameters["exponent"].stderr is None
    assert "exponent" in result.undetermined
    assert result.to_dict()["parameters"]["exponent"]["value"] is None
    _within(result, {"k": K, "mu_s": MU_S}, rel=0.01)


@pytest.mark.slow
@pytest.mark.parametrize("noise, rel", [(0.005, 0.01), (0.02, 0.05)])
def test_viscous_stribeck_law(noise, rel):
    """A Stribeck curve with a viscous term, mu = 0.35 + 0.25 exp(-v_r / 2 cm/s) + 0.3 s/m v_r
    (the exponent given as known, 1): the targets hold for k, mu_s and mu_k."""
    _rig, rec = _record(stribeck(0.35, MU_S, 0.02, 1.0, 0.3), noise=noise, seed=10, t_end=1.23)
    result = identify(rec, {**KNOWN, "exponent": 1.0}, law="stribeck")
    _within(result, {"k": K, "c": C, "mu_s": MU_S, "mu_k": 0.35, "stribeck_velocity": 0.02,
                     "viscous": 0.3}, rel=rel)


# ----------------------------------------------------------------------------- auto
@pytest.mark.slow
@pytest.mark.parametrize("law, mu", [
    ("coulomb", coulomb(MU_K)),
    ("linear", linear(MU_K, -STRENGTHENING)),
    ("stribeck", stribeck(0.35, MU_S, 0.02, 1.0, 0.0)),
])
def test_auto_picks_the_law_of_the_record(law, mu):
    """``auto`` fits coulomb, linear and stribeck (exponent 1) and keeps the lowest BIC; on a
    record made with each law it keeps that law, and reports AIC, BIC, chi-square and the
    parameter count of all three."""
    _rig, rec = _record(mu, seed=31)
    result = identify(rec, KNOWN, law="auto")
    assert set(result.criteria) == {"coulomb", "linear", "stribeck"}
    for crit in result.criteria.values():
        assert set(crit) == {"aic", "bic", "chi2", "n_params"}
    bics = {name: c["bic"] for name, c in result.criteria.items()}
    assert result.law == law == min(bics, key=bics.__getitem__), bics
    assert result.to_dict()["information_criteria"][law]["bic"] == bics[law]


# ----------------------------------------------------------------------------- BLAS threads
def _blas_threads():
    return {info["filepath"]: info["num_threads"] for info in threadpool_info() if info["user_api"] == "blas"}


def test_blas_limited_while_any_fit_runs():
    """The limit holds while any fit runs and the process's setting comes back after the
    last one: overlapping fits (entered twice, left once) keep it; ``None`` leaves BLAS as
    it is. (Checked from the main thread: OpenBLAS here ignores a limit set from a worker
    thread, see the docstring of ``blas_limited``.)"""
    np.dot(np.ones((2, 2)), np.ones((2, 2)))  # load BLAS
    before = _blas_threads()
    first, second = _blas_limited(1), _blas_limited(1)
    first.__enter__()
    second.__enter__()
    assert set(_blas_threads().values()) == {1}
    first.__exit__(None, None, None)
    assert set(_blas_threads().values()) == {1}  # the other fit still runs
    second.__exit__(None, None, None)
    assert _blas_threads() == before
    with _blas_limited(None):
        assert _blas_threads() == before


def test_cli_table_speeds_refused_without_table_law(tmp_path, capsys):
    from tests.test_identification import EXAMPLE

    code, out, err = run_cli(["identify", str(EXAMPLE), "--mass", "1 kg", "--load", "100 N", "--speed",
                              "5 cm/s", "--table-speeds", "0, 1 cm/s"], capsys)
    assert code == 2 and out == "" and "--table-speeds" in err and len(err.strip().splitlines()) == 1
    code, out, err = run_cli(["identify", str(EXAMPLE), "--mass", "1 kg", "--load", "100 N", "--speed",
                              "5 cm/s", "--law", "table", "--table-speeds", "0, 2 cm/s, 1 cm/s"], capsys)
    assert code == 2 and out == "" and "increase strictly" in err


@pytest.mark.slow
def test_a_stribeck_fit_of_a_clean_record_converges_to_the_truth():
    """A nearly noise-free record (1e-6 of the range) of an exponential Stribeck rig (c = 10
    N s/m, mu_s 0.6, mu_k 0.35, v_s 1 cm/s, exponent 1, V 3 cm/s, start-up): an audit's
    independent simulator made this record; the fit stopped at its budget of 100 evaluations
    at exponent 0.54 and mu_s 0.68 % off, reported as a result. Now it converges, every true
    value inside three standard errors, and a stop at the budget is said (the next test)."""
    rig = simulate_rig(m=M, k=K, c=10.0, mu_s=0.6, mu=stribeck(0.35, 0.6, 0.01), load=W,
                       speed=0.03, t_end=1.25, fs=2000.0)
    rng = np.random.default_rng(2)
    rec = MeasuredRecord(rig.t, F=noisy(rig.F, 1e-6, rng), x=noisy(rig.x, 1e-6, rng))
    result = identify(rec, {"m": M, "load": W, "speed": 0.03}, law="stribeck")
    assert result.success, result.summary()
    assert not any("did not converge" in w for w in result.warnings)
    p = result.parameters
    assert p["exponent"].value == pytest.approx(1.0, rel=0.05)
    assert p["stribeck_velocity"].value == pytest.approx(0.01, rel=0.05)
    for name, value in (("k", K), ("mu_s", 0.6), ("mu_k", 0.35)):
        assert p[name].value == pytest.approx(value, rel=2e-3)


def test_a_fit_stopped_at_its_budget_is_said_everywhere(monkeypatch, tmp_path):
    """The optimiser's budget cut to 3 evaluations (so that it stops before converging): the
    result's warnings (terminal and JSON) and the machine file it writes say so."""
    from stickslip.analysis.identification import record_fit

    real = record_fit.solve_fit
    monkeypatch.setattr(record_fit, "solve_fit",
                        lambda problem, z0, weights=None, max_nfev=3: real(problem, z0, weights, 3))
    _rig, rec = _record(coulomb(MU_K))
    result = identify(rec, KNOWN)
    assert not result.success
    assert any("did not converge" in w for w in result.warnings)
    assert any("did not converge" in w for w in result.to_dict()["warnings"])
    assert "did not converge" in result.summary()
    assert "# warning: the fit did not converge" in result.to_config()


@pytest.mark.slow
def test_five_parameter_stribeck_fit_ends_below_its_nested_optimum():
    """An independent audit's rig (2 kg, k = 20 kN/m, c = 8 N s/m, W = 150 N, V = 3 cm/s,
    mu = 0.35 + 0.2 exp(-v_r / 2 cm/s), so n = 1 and no viscous term; 0.5 % noise, 5 kHz):
    the five-parameter fit stopped near the exponent's lower limit (n = 0.51 +/- 0.07, mu_s
    ten standard errors high) at a chi-square above that of the fit with n = 1 and no viscous
    term held, a point of the same problem. The full fit now ends at or below the nested
    optimum and the truth lies within three standard errors."""
    rig = simulate_rig(m=2.0, k=2.0e4, c=8.0, mu_s=0.55, mu=stribeck(0.35, 0.55, 0.02, 1.0),
                       load=150.0, speed=0.03, t_end=1.7, fs=5000.0, t_start=0.1)
    rng = np.random.default_rng(101)
    rec = MeasuredRecord(rig.t - rig.t[0], **{n: noisy(getattr(rig, n), 0.005, rng) for n in ("F", "x")})
    known = {"m": 2.0, "load": 150.0, "speed": 0.03}
    full = identify(rec, known, law="stribeck")
    nested = identify(rec, {**known, "exponent": 1.0, "viscous": 0.0}, law="stribeck")
    assert full.chi2 <= nested.chi2 * (1.0 + 1e-9)
    _within(full, {"mu_s": 0.55, "exponent": 1.0, "stribeck_velocity": 0.02, "k": 2.0e4, "c": 8.0})
