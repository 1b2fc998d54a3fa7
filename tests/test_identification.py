"""Identification from a measured stick-slip record (issue 19, DESIGN.md section 11).

Every record here is made by the independent SI simulator of ``tests/record_oracle.py``
(event-driven ``solve_ivp`` written from the rig's equations in physical units; neither the
engine nor the dimensionless mapping), with known parameters, white noise of a stated fraction
of the signal's peak-to-peak range, and where stated a load-cell offset and drift. The claims:
recovered ``mu_s``, ``mu_k`` and ``k`` within 1 % of the truth at 0.5 % noise and 5 % at 2 %
noise, every true value inside three standard errors, and clear messages when the record
cannot support the model.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from stickslip.analysis.identification.record_fit import MeasuredRecord, RecordError, identify
from tests.cli_helpers import run_cli
from tests.record_oracle import coulomb, linear, noisy, simulate_rig, stribeck

M, K, C, MU_S, MU_K, W, V = 1.0, 1.0e4, 5.0, 0.6, 0.4, 100.0, 0.05
KNOWN = {"m": M, "load": W, "speed": V}
EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "rig_record.csv"


def _rig(mu=None, *, t_end=0.93, fs=2000.0, t_start=0.23, **kw):
    return simulate_rig(m=M, k=K, c=C, mu_s=kw.pop("mu_s", MU_S), mu=mu or coulomb(MU_K), load=W, speed=V,
                        t_end=t_end, fs=fs, t_start=t_start, **kw)


def _check(result, truth, rel, n_se=3.0):
    for name, value in truth.items():
        p = result.parameters[name]
        assert p.value is not None, f"{name} undetermined"
        if name in ("k", "mu_s", "mu_k"):
            assert abs(p.value - value) <= rel * abs(value), f"{name} = {p.value} vs {value}"
        assert abs(p.value - value) <= n_se * p.stderr, f"{name} = {p.value} +/- {p.stderr} vs {value}"


@pytest.fixture(scope="module")
def coulomb_fit():
    """0.5 % noise on F and x, offset 1.5 N and drift 2 N/s on F, start in mid-slip."""
    rng = np.random.default_rng(5)
    rig = _rig()
    rec = MeasuredRecord(rig.t, F=noisy(rig.F, 0.005, rng) + 1.5 + 2.0 * rig.t, x=noisy(rig.x, 0.005, rng))
    return identify(rec, KNOWN, law="coulomb")


def test_coulomb_half_percent_noise_offset_drift_midcycle(coulomb_fit):
    _check(coulomb_fit, {"k": K, "c": C, "mu_s": MU_S, "mu_k": MU_K, "force_offset": 1.5, "force_drift": 2.0},
           0.01)
    assert coulomb_fit.cycles_used >= 5
    # residuals at the noise level: the model explains the record (reduced chi-square ~ 1)
    assert 0.8 < coulomb_fit.to_dict()["reduced_chi2"] < 1.25
    # the record starts in mid-slip: the first segment has its own free state (x_0, v_0)
    assert coulomb_fit.segments == coulomb_fit.stick_segments + 1


def test_coulomb_two_percent_noise_force_only():
    rng = np.random.default_rng(6)
    rig = _rig(t_start=0.17)
    result = identify(MeasuredRecord(rig.t, F=noisy(rig.F, 0.02, rng)), KNOWN)
    _check(result, {"k": K, "mu_s": MU_S, "mu_k": MU_K}, 0.05)
    assert result.parameters["force_offset"].free is False  # F alone: offset held at 0


def test_without_a_force_channel_its_zero_is_not_fitted():
    """x and v alone: the force's offset and drift act on no residual (an audit found the
    drift's Jacobian column exactly zero, yet it was a free parameter, reported undetermined,
    correlated to -0.97 with mu_k and counted in the free parameters)."""
    rng = np.random.default_rng(10)
    rig = _rig(t_end=0.73)
    result = identify(MeasuredRecord(rig.t, x=noisy(rig.x, 0.005, rng), v=noisy(rig.v, 0.005, rng)),
                      KNOWN)
    for name in ("force_offset", "force_drift"):
        assert result.parameters[name].free is False and result.parameters[name].value == 0.0
        assert not any(name in pair for pair in result.correlations)
    assert sorted(n for n, p in result.parameters.items() if p.free) == ["c", "k", "mu_k", "mu_s"]
    _check(result, {"k": K, "mu_s": MU_S, "mu_k": MU_K}, 0.01)


@pytest.mark.parametrize("preload", [-0.003, -0.006])
def test_a_start_up_from_a_preloaded_spring_uses_every_stick_phase(preload):
    """A record from the start: the spring compressed by 3 or 6 mm, so the first stick phase
    lasts two or three periods. An audit found the whole record's autocorrelation then peaks
    at two or three periods: 4 stick phases of 12 found, then a refusal ("the stated mass is
    0.0351 times the 28.5 kg the slip phases imply") or "no repeating cycle"."""
    rng = np.random.default_rng(11)
    rig = _rig(t_end=1.4, t_start=0.0, x0=preload)
    assert rig.breakaways.size >= 11  # the oracle's own count of the stick phases that end
    rec = MeasuredRecord(rig.t, F=noisy(rig.F, 0.001, rng), x=noisy(rig.x, 0.001, rng))
    result = identify(rec, KNOWN)
    assert result.cycles_used >= rig.breakaways.size - 1
    _check(result, {"k": K, "c": C, "mu_s": MU_S, "mu_k": MU_K}, 0.01)


def test_uneven_time_steps_are_fitted_with_a_warning():
    """The second half of the record at half the rate (steps of 0.5 ms, then 1 ms): the fit
    runs on the record's own times, and the estimates' even-step reading is said."""
    rng = np.random.default_rng(12)
    rig = _rig(t_end=0.93)
    h = rig.t.size // 2
    keep = np.concatenate([np.arange(h), np.arange(h, rig.t.size, 2)])
    rec = MeasuredRecord(rig.t[keep], F=noisy(rig.F, 0.005, rng)[keep],
                         x=noisy(rig.x, 0.005, rng)[keep])
    result = identify(rec, KNOWN)
    assert any("time steps range from 0.0005 to 0.001 s" in w for w in result.warnings)
    _check(result, {"k": K, "mu_s": MU_S, "mu_k": MU_K}, 0.01)
    even = identify(MeasuredRecord(rig.t, F=rig.F, x=rig.x), KNOWN)
    assert not any("time steps" in w for w in even.warnings)


def test_force_offset_without_displacement_is_undetermined():
    """With F alone a force offset a and a common shift d of mu_s and mu_k are the same
    record: the motion depends on mu_s - mu_k, and the shift moves the kinetic equilibrium
    k x_eq = mu_k W by d W / k, which changes F = k x + c x' by exactly d W -- the same as
    a = d W. The Jacobian has a null direction; mu_s and mu_k must come back null."""
    rng = np.random.default_rng(7)
    rig = _rig(t_end=0.73)
    result = identify(MeasuredRecord(rig.t, F=noisy(rig.F, 0.005, rng)), KNOWN, fit_offset=True)
    assert result.parameters["mu_s"].value is None
    assert result.parameters["mu_k"].value is None
    assert result.parameters["k"].value == pytest.approx(K, rel=0.01)
    assert {"mu_s", "mu_k"} <= set(result.undetermined)
    assert result.to_dict()["parameters"]["mu_s"]["value"] is None


def test_force_offset_of_a_noise_free_force_record_is_undetermined():
    """The same degeneracy without noise (an independent audit): the optimum is sharp along
    every other direction, so the rank test passed, and mu_s and mu_k came back with standard
    errors of 2e-7, each shifted by the offset's -0.97 N / W. The shift is exact whatever the
    noise: the offset and the friction levels are undetermined."""
    rig = _rig(t_end=0.73)
    result = identify(MeasuredRecord(rig.t, F=rig.F), KNOWN, fit_offset=True)
    for name in ("mu_s", "mu_k", "force_offset"):
        assert result.parameters[name].value is None, result.summary()
    assert result.parameters["k"].value == pytest.approx(K, rel=1e-4)


def test_a_mass_far_off_is_named_when_the_fit_fails(tmp_path, capsys):
    """A stated mass 15 times the rig's drove the fit out of the dimensionless range and the
    message named gamma (an independent audit: 25 kg for 1.74); it names the mass now, one
    line, exit 2."""
    path = tmp_path / "rig.csv"
    rig = _rig(t_end=0.73)
    rng = np.random.default_rng(3)
    f, x = noisy(rig.F, 0.005, rng), noisy(rig.x, 0.005, rng)
    path.write_text("t,F,x\n" + "\n".join(f"{a},{b},{c}" for a, b, c in zip(rig.t, f, x, strict=True)))
    code, out, err = run_cli(["identify", str(path), "--mass", "15 kg", "--load", "100 N",
                              "--speed", "5 cm/s"], capsys)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and "check --mass" in err and "15 kg" in err


def test_cycles_not_quite_equal():
    """mu_s changes by up to 0.8 % from one stick phase to the next (mean 0.6): the fit
    (one segment per cycle) recovers the mean within 1 %."""
    rng = np.random.default_rng(8)
    jitter = MU_S * (1.0 + 0.008 * np.array([0.3, -1.0, 0.6, -0.2, 1.0, -0.7, 0.1, -0.1, 0.5, -0.5]))
    rig = _rig(mu_s_per_stick=list(jitter))
    rec = MeasuredRecord(rig.t, F=noisy(rig.F, 0.005, rng), x=noisy(rig.x, 0.005, rng))
    result = identify(rec, KNOWN)
    for name, value in (("k", K), ("mu_s", MU_S), ("mu_k", MU_K)):
        assert result.parameters[name].value == pytest.approx(value, rel=0.01)


def test_too_few_stick_phases_is_refused_clearly():
    rig = _rig(t_end=0.38, t_start=0.23)  # 0.15 s: one breakaway
    with pytest.raises(RecordError, match="stick phase"):
        identify(MeasuredRecord(rig.t, F=rig.F), KNOWN)
    # steady sliding: no stick at all (a ramp that never breaks away)
    t = np.linspace(0.0, 1.0, 2000)
    with pytest.raises(RecordError, match=r"no (oscillation|repeating)|stick phase"):
        identify(MeasuredRecord(t, F=40.0 + 0.1 * np.sin(3.0 * t)), KNOWN)


def test_known_parameter_is_held_fixed(coulomb_fit):
    rng = np.random.default_rng(9)
    rig = _rig(t_end=0.73)
    rec = MeasuredRecord(rig.t, F=noisy(rig.F, 0.005, rng), x=noisy(rig.x, 0.005, rng))
    result = identify(rec, {**KNOWN, "c": C})
    assert result.parameters["c"].free is False and result.parameters["c"].estimate == C
    assert result.parameters["k"].value == pytest.approx(K, rel=0.01)
    with pytest.raises(ValueError, match="not a fitted parameter"):
        identify(rec, {**KNOWN, "zeta": 0.1})


def test_result_exports_and_plot(coulomb_fit, tmp_path):
    d = coulomb_fit.to_dict()
    assert d["law"] == "coulomb"
    assert set(d["parameters"]["k"]) >= {"value", "stderr", "unit"} and d["parameters"]["k"]["unit"] == "N/m"
    json.dumps(d)
    report = coulomb_fit.summary()
    assert "[[Variables]]" in report and "mu_s:" in report and "[[Correlations]]" in report
    ds = coulomb_fit.to_xarray()
    assert ds["F_fitted"].attrs["units"] == "N"
    assert coulomb_fit.to_csv().splitlines()[0].startswith("t [s],F_measured [N]")
    _fig, axes, artists = coulomb_fit.plot()
    assert len(axes) == 3 and artists
    mu, se = coulomb_fit.friction_curve([0.01, 0.1])
    assert mu == pytest.approx([coulomb_fit.parameters["mu_k"].value] * 2)
    assert se[0] == pytest.approx(coulomb_fit.parameters["mu_k"].stderr, rel=1e-3)


def test_record_reader_units_signs_and_columns(tmp_path):
    from stickslip.io.record import parse_columns, read_columns_toml, read_record

    t = np.linspace(0.0, 0.5, 6)
    path = tmp_path / "rec.csv"
    path.write_text("# rig\ntime,disp,load\n" + "\n".join(
        f"{1e3 * a},{1e3 * 0.001 * i},{-0.001 * 40 * i}" for i, a in enumerate(t)) + "\n")
    rec = read_record(path, parse_columns("t=time:ms,x=disp:mm,F=-load:kN"))
    assert rec.t == pytest.approx(t)
    assert rec.x == pytest.approx(0.001 * np.arange(6))
    assert rec.F == pytest.approx(40.0 * np.arange(6))
    spec = tmp_path / "cols.toml"
    spec.write_text('[columns.t]\nname = "time"\nunit = "ms"\n'
                    '[columns.F]\nname = "load"\nunit = "kN"\nsign = -1\n')
    rec2 = read_record(path, read_columns_toml(spec))
    assert rec2.F == pytest.approx(rec.F) and rec2.x is None
    head = tmp_path / "head.csv"
    head.write_text("t [ms],F (kN)\n0,1\n1,2\n2,3\n")
    rec3 = read_record(head)
    assert rec3.t == pytest.approx([0.0, 1e-3, 2e-3]) and rec3.F == pytest.approx([1e3, 2e3, 3e3])
    with pytest.raises(RecordError, match=r"not a .*length.* unit"):
        read_record(path, parse_columns("t=time:ms,x=disp:kg"))
    with pytest.raises(RecordError, match="no column 'nope'"):
        read_record(path, parse_columns("t=time,F=nope"))


def test_cli_json_write_config_and_design(tmp_path, capsys):
    cfg = tmp_path / "machine.toml"
    code, out, err = run_cli(["identify", str(EXAMPLE), "--mass", "1 kg", "--load", "100 N", "--speed",
                              "5 cm/s", "--write-config", str(cfg), "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    assert out.count("\n") == 1
    for key in ("law", "parameters", "residual_rms", "cycles_used", "information_criteria", "correlations"):
        assert key in payload
    p = payload["parameters"]
    # the example's truth (tests/make_identify_example.py), 0.5 % noise: within 1 %
    for name, value in (("k", K), ("mu_s", MU_S), ("mu_k", MU_K)):
        assert p[name]["value"] == pytest.approx(value, rel=0.01)
    code, out, err = run_cli(["design", "--config", str(cfg), "--no-stick-slip-optimum", "--json"], capsys)
    assert code == 0, err
    design = json.loads(out)
    lam = (p["mu_s"]["value"] - p["mu_k"]["value"]) * W / (V * math.sqrt(M * p["k"]["value"]))
    assert design["lambda"] == pytest.approx(lam, rel=1e-9)
    assert design["zeta"] == pytest.approx(p["c"]["value"] / (2 * math.sqrt(M * p["k"]["value"])), rel=1e-9)


@pytest.mark.parametrize("args, needle", [
    (["--mass", "2 m"], "--mass"),
    (["--law", "magic"], "--law"),
    (["--columns", "q=time"], "--columns"),
    (["--bootstrap", "-1"], "--bootstrap"),
    (["--fix", "zeta=3"], "--fix"),
])
def test_cli_bad_input_one_line_exit_2(args, needle, tmp_path, capsys):
    base = {"--mass": "1 kg", "--load": "100 N", "--speed": "0.05 m/s"}
    for flag, value in zip(args[::2], args[1::2], strict=True):
        base[flag] = value
    argv = ["identify", str(EXAMPLE), "--write-config", str(tmp_path / "m.toml")]
    for flag, value in base.items():
        argv += [flag, value]
    code, out, err = run_cli(argv, capsys)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and needle in err and "Traceback" not in err
    assert not (tmp_path / "m.toml").exists()


def test_cli_missing_record_and_too_short(tmp_path, capsys):
    code, _, err = run_cli(["identify", str(tmp_path / "none.csv"), "--mass", "1", "--load", "100",
                            "--speed", "0.05"], capsys)
    assert code == 2 and "does not exist" in err
    short = tmp_path / "short.csv"
    rig = _rig(t_end=0.38)
    short.write_text("t,F\n" + "\n".join(f"{a},{b}" for a, b in zip(rig.t, rig.F, strict=True)))
    code, _, err = run_cli(["identify", str(short), "--mass", "1", "--load", "100", "--speed", "0.05"],
                           capsys)
    assert code == 2 and "stick phase" in err and len(err.strip().splitlines()) == 1


@pytest.mark.slow
@pytest.mark.parametrize("noise, rel", [(0.005, 0.01), (0.02, 0.05)])
def test_stribeck_law(noise, rel):
    """Stribeck curve mu_k 0.35, mu_0 = mu_s 0.6, v_s 2 cm/s, n = 1, no viscous term; the
    exponent and the viscous slope are given as known (a dozen cycles do not separate them
    from mu_k and v_s: the five-parameter fit reports correlations near -1 and large errors)."""
    rng = np.random.default_rng(10)
    rig = _rig(stribeck(0.35, MU_S, 0.02, 1.0, 0.0), t_end=1.23)
    rec = MeasuredRecord(rig.t, F=noisy(rig.F, noise, rng), x=noisy(rig.x, noise, rng))
    result = identify(rec, {**KNOWN, "exponent": 1.0, "viscous": 0.0}, law="stribeck")
    _check(result, {"k": K, "mu_s": MU_S, "mu_k": 0.35, "stribeck_velocity": 0.02}, rel)


@pytest.mark.slow
@pytest.mark.parametrize("noise, rel", [(0.005, 0.01), (0.02, 0.05)])
def test_linear_law(noise, rel):
    rng = np.random.default_rng(11)
    rig = _rig(linear(MU_K, 1.0), t_end=1.23)
    rec = MeasuredRecord(rig.t, F=noisy(rig.F, noise, rng), x=noisy(rig.x, noise, rng))
    result = identify(rec, KNOWN, law="linear")
    _check(result, {"k": K, "mu_s": MU_S, "mu_k": MU_K, "slope": 1.0}, rel)


@pytest.mark.slow
def test_auto_prefers_the_law_of_the_record():
    """A velocity-weakening contact, mu = 0.4 - 1 s/m v_r: ``auto`` ranks the linear law above
    Coulomb by its information criterion, and reports AIC and BIC for the three laws."""
    rng = np.random.default_rng(13)
    rig = _rig(linear(MU_K, 1.0), t_end=0.93)
    rec = MeasuredRecord(rig.t, F=noisy(rig.F, 0.005, rng), x=noisy(rig.x, 0.005, rng))
    result = identify(rec, KNOWN, law="auto")
    assert set(result.criteria) == {"coulomb", "linear", "stribeck"}
    assert result.criteria["linear"]["bic"] < result.criteria["coulomb"]["bic"]
    assert result.law in ("linear", "stribeck")


@pytest.mark.slow
def test_bootstrap_intervals_cover_the_truth():
    rng = np.random.default_rng(12)
    rig = _rig()
    rec = MeasuredRecord(rig.t, F=noisy(rig.F, 0.005, rng), x=noisy(rig.x, 0.005, rng))
    result = identify(rec, KNOWN, bootstrap=20)
    for name, value in (("k", K), ("mu_s", MU_S), ("mu_k", MU_K)):
        lo, hi = result.parameters[name].interval
        assert lo <= result.parameters[name].value <= hi
        assert hi - lo < 0.02 * value


@pytest.mark.parametrize("scale", [1e6, 1e300])
def test_a_force_in_the_wrong_units_is_refused_before_any_fit(scale: float) -> None:
    # a bad-input audit: the example's force times 1e10 ran the fit for 193 s before refusing,
    # and times 1e300 overflowed numpy on its way to "no oscillation". |F| <= mu_s W plus the
    # slip's overshoot for a slider held by a spring; beyond 1000 W it is refused at once.
    rig = _rig()
    with pytest.raises(RecordError, match=r"times the normal load .*check the force's units"):
        identify(MeasuredRecord(rig.t, F=scale * rig.F), KNOWN)


def test_a_bootstrap_reports_its_progress() -> None:
    """``identify --bootstrap 500`` ran 15 s and more without a word (an independent audit):
    each refit is reported, so the command line shows a bar on a terminal."""
    rng = np.random.default_rng(5)
    rig = _rig(t_end=0.73)
    rec = MeasuredRecord(rig.t, F=noisy(rig.F, 0.005, rng), x=noisy(rig.x, 0.005, rng))
    calls: list[tuple[int, int]] = []
    result = identify(rec, KNOWN, bootstrap=3, progress=lambda done, total: calls.append((done, total)))
    assert calls == [(0, 3), (1, 3), (2, 3), (3, 3)]
    assert result.parameters["k"].interval is not None
