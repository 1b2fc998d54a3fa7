"""``design`` says true, clean numbers (issue 32, items 1, 2 and 7).

* Inputs whose products overflow a double (``--speed 1e300``) are refused in one line naming
  the value, with a non-zero exit and nothing on stderr but that line (no ``OverflowError``,
  no ``RuntimeWarning``).
* ``gamma`` of decimal coefficients is the decimal ratio (0.3 / (0.5 - 0.3) = 1.5, not
  1.4999999999999998) in the text and the JSON; no ``-0`` anywhere; a given foundation equal
  to the recommended one is printed once.
* Steady sliding whose growth rate is zero to round-off (an undamped slider on a rigid base)
  is neutral, as ``simulate`` says, not "UNSTABLE".
* The stick-slip-optimal foundation of a non-Coulomb machine says that it assumes Coulomb
  friction.
"""

from __future__ import annotations

import json
import re
import warnings

import pytest

from stickslip import PhysicalSystem
from stickslip.analysis.design import coulomb_tuning_note
from stickslip.model.physical import MAX_SI, PhysicalFriction
from tests.cli_helpers import run_cli

BASE = {"--m": "2 kg", "--k": "50 kN/m", "--c": "20 N*s/m", "--mu-s": "0.5", "--mu-k": "0.3",
        "--load": "500 N", "--speed": "5 cm/s"}


def _args(**override: str) -> list[str]:
    flags = {**BASE, **{f"--{k.replace('_', '-')}": v for k, v in override.items()}}
    return ["design", *[x for kv in flags.items() for x in kv], "--no-stick-slip-optimum"]


@pytest.mark.parametrize(("flag", "value", "named"), [
    ("speed", "1e300", "speed V=1e+300"), ("load", "1e300", "load W=1e+300"),
    ("mu_s", "1e300", "mu_s=1e+300"),
    ("m", "1e300", "m=1e+300"), ("k", "1e300", "k=1e+300"), ("c", "1e300", "c=1e+300"),
    ("speed", "1e-300", "speed V=1e-300"),
])
def test_overflowing_input_is_one_line(flag: str, value: str, named: str,
                                       capsys: pytest.CaptureFixture[str]) -> None:
    # before: --speed 1e300 ended in "OverflowError: (34, 'Numerical result out of range')"
    # from the disturbance margin m V^2 (2 kg * (1e300 m/s)^2 = 2e600 J > 1.8e308)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an overflow RuntimeWarning fails the test
        code, out, err = run_cli(_args(**{flag: value}), capsys)
    assert code != 0 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert named in lines[0] and f"{MAX_SI:g}" in lines[0] and "overflow" in lines[0]
    assert "Traceback" not in err and "Warning" not in err


def test_gamma_is_reported_to_the_digits_of_its_inputs(capsys: pytest.CaptureFixture[str]) -> None:
    # reference: gamma = mu_k / (mu_s - mu_k) (after the paper's Eq. 27); 0.3 / 0.2 = 3/2, while
    # in floating point 0.3 / (0.5 - 0.3) = 1.4999999999999998. The engine keeps the float
    # ratio (every SI answer stays what it was, and mu_s - mu_k round-trips with it); the
    # report states it to 15 significant digits.
    system = PhysicalSystem(mass=2.0, stiffness=5e4, damping=20.0, mu_s=0.5, mu_k=0.3, load=500.0,
                            speed=0.05)
    assert system.slider().gamma == 0.3 / (0.5 - 0.3)
    code, out, err = run_cli([*_args(), "--json"], capsys)
    assert code == 0, err
    assert json.loads(out)["gamma"] == 1.5 and "1.4999999999999998" not in out
    code, out, err = run_cli(_args(), capsys)
    assert code == 0, err
    assert "1.4999999999999998" not in out


def test_no_negative_zero_in_the_json(capsys: pytest.CaptureFixture[str]) -> None:
    # a flat (Coulomb) law has the local weakening delta = -slope / 2 = 0, not -0.0
    code, out, err = run_cli([*_args(), "--json"], capsys)
    assert code == 0, err
    assert "-0.0," not in out and "-0.0}" not in out
    assert json.loads(out)["stability"]["rigid"]["delta_local"] == 0.0


def test_given_recommended_foundation_is_printed_once(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli([*_args(), "--json"], capsys)
    rec = json.loads(out)["recommended_foundation"]
    args = _args(m_a=repr(rec["m_a"]), k_a=repr(rec["k_a"]), c_a=repr(rec["c_a"]))
    code, out, err = run_cli(args, capsys)
    assert code == 0, err
    # before: "foundation assessed (...): m_a=3.811 kg, ..." and "recommended foundation
    # (Eqs. 28-30): m_a=3.811 kg, ..." one under the other
    assert len(re.findall(r"m_a=3\.811 kg", out)) == 1, out
    assert "the recommended one (Eqs. 28-30)" in out


def test_undamped_rigid_base_is_neutral_not_unstable(capsys: pytest.CaptureFixture[str]) -> None:
    args = [a for a in _args() if a not in ("--c", "20 N*s/m")]
    code, out, err = run_cli([*args, "--json"], capsys)
    assert code == 0, err
    rigid = json.loads(out)["stability"]["rigid"]
    # reference: an undamped 1-DOF oscillator under Coulomb friction (no slope) has the
    # eigenvalues +-i omega_n: growth rate 0, marginally stable (paper Section 2.3, zeta = 0)
    assert abs(rigid["growth_rate"]) < 1e-9
    assert rigid["neutral"] is True and rigid["stable"] is False
    code, out, err = run_cli(args, capsys)
    line = next(x for x in out.splitlines() if x.strip().startswith("rigid base") and "growth" in x)
    assert "UNSTABLE" not in line and "neutral" in line and "marginally stable" in line


def test_coulomb_tuning_note_only_for_another_law() -> None:
    assert coulomb_tuning_note("coulomb") is None
    note = coulomb_tuning_note("stribeck")
    assert note is not None and note.startswith("assumes Coulomb friction") and "stribeck" in note


@pytest.mark.slow  # 20-40 s: kept out of the default run (under 10 minutes)
def test_stick_slip_optimum_of_a_stribeck_machine_says_it_assumes_coulomb(
        capsys: pytest.CaptureFixture[str]) -> None:
    from stickslip.analysis.design import design_foundation
    from stickslip.cli.design_command import format_report

    # the Stribeck machine of issue 32 item 1 (m 0.538 kg, k 6957 N/m, c 5.746 N s/m, W 10 N,
    # mu_k 0.2, mu_s 0.6, v_s 0.1 m/s, viscous 0.02 s/m), at V = 5 cm/s
    system = PhysicalSystem(mass=0.538, stiffness=6957.0, damping=5.746, mu_s=0.6, mu_k=0.2,
                            load=10.0, speed=0.05,
                            friction=PhysicalFriction("stribeck", stribeck_velocity=0.1, viscous=0.02))
    payload = design_foundation(system, stick_slip_optimum=True).to_dict()
    best = payload["stick_slip_optimal_foundation"]
    assert best["assumption"] == coulomb_tuning_note("stribeck")
    text = format_report(payload)
    row = text.splitlines().index(next(x for x in text.splitlines()
                                       if x.startswith("stick-slip-optimal foundation")))
    assert "assumes Coulomb friction" in text.splitlines()[row + 1]
    # the Coulomb-tuned foundation assessed once with the machine's law, by the same search as
    # the foundation_simulation row (its law is the Stribeck law's description)
    own = best["own_law"]
    assert own["law"] == payload["critical_law"]["foundation_simulation"] != best["friction_law"]
    assert own["speed"] is not None or own["note"]  # a value, or what the search found instead
    assert text.splitlines()[row + 2].startswith("  with the machine's friction law: V_c=")


@pytest.mark.parametrize("bound", ["1e300", "1e-300"])
def test_an_absurd_deflection_bound_is_named(bound: str, capsys: pytest.CaptureFixture[str]) -> None:
    # before: "K=5.477e-152 is below the supported range" -- a foundation ratio the user never gave
    code, out, err = run_cli([*_args(), "--max-foundation-deflection", bound], capsys)
    assert code == 2 and out == ""
    (line,) = err.strip().splitlines()
    assert f"max_foundation_deflection={float(bound)!r}" in line and "mu_k W / k = 0.003 m" in line
