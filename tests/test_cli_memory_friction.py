"""``stickslip simulate --config`` with friction with memory (issue 33, the scripted contract).

The contract: ``[friction] law = "rate-state" | "lugre"`` with units; ``[system] m = "0 kg"``
(the quasi-static slider) and a speed schedule; ``--json`` gives ``verdict``, ``period_s``,
``amplitude_m``; ``--t-max "40 s"``; ``--history-times A:B:N`` adds ``history`` with ``t_s``,
``x_m``, ``v_m_s``, ``mu`` and ``state``; runs start from steady sliding at the first speed and
``--initial-kick F`` starts the contact at ``-F V``. Bad input: one line, exit 2.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from stickslip.cli.main import run
from tests.memory_machines import LUGRE

QUASI_STATIC = """
[system]
m = "0 kg"
k = "1e5 N/m"
load = "1 kN"
speed = [["0 s", "1 um/s"], ["10 s", "10 um/s"]]

[friction]
law = "rate-state"
a = 0.01
b = 0.008
d_c = "10 um"
mu_ref = 0.6
v_ref = "1 um/s"
evolution = "aging"
"""


def _run(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    try:
        run(args)
        code = 0
    except SystemExit as exc:
        code = int(exc.code or 0)
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def _file(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "machine.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_lugre_stick_slip_contract(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _file(tmp_path, LUGRE)
    code, out, err = _run(["simulate", "--config", str(path), "--t-max", "40 s", "--initial-kick",
                           "-1", "--history-times", "0:40:81", "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    assert payload["verdict"] == "stick-slip"
    assert payload["period_s"] == pytest.approx(6.3627, rel=1e-3)  # tests/test_memory_verdicts.py
    assert payload["amplitude_m"] > 0.1
    history = payload["history"]
    assert set(history) >= {"t_s", "x_m", "v_m_s", "mu", "state"}
    assert len(history["t_s"]) == 81 and history["t_s"][-1] == 40.0
    # the kick: slip speed 0 (the contact moves with the belt), position of steady sliding
    assert history["v_m_s"][0] == pytest.approx(0.1)
    assert history["x_m"][0] == pytest.approx((1.0 + 0.4 * 0.1) / 2.0)
    # friction stays between the Coulomb level and the static one (plus the viscous part)
    assert max(history["mu"]) < 1.5 + 0.4 * 0.2 and min(history["mu"]) > 0.0


def test_runs_start_from_steady_sliding(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _file(tmp_path, LUGRE)
    code, out, err = _run(["simulate", "--config", str(path), "--t-max", "5 s", "--history-times",
                           "0:5:6", "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    # steady sliding at 0.1 m/s is stable for these parameters (the paper's cycle needs a start
    # off it): the run stays there
    assert payload["verdict"] == "steady-sliding"
    assert payload["period_s"] is None and payload["amplitude_m"] is None
    for v in payload["history"]["v_m_s"]:
        assert abs(v) < 1e-12


def test_quasi_static_velocity_step(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _file(tmp_path, QUASI_STATIC)
    code, out, err = _run(["simulate", "--config", str(path), "--t-max", "60 s", "--history-times",
                           "0:60:601", "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    assert payload["machine"]["quasi_static"] is True
    history = payload["history"]
    mu = history["mu"]
    t = history["t_s"]
    # steady sliding at 1 um/s before the step: mu_ss = mu_ref + (a - b) ln(V/v_ref) = 0.6
    assert mu[0] == pytest.approx(0.6, abs=1e-12)
    # the state theta = d_c / V = 10 s before the step
    assert history["state"][0] == pytest.approx(10.0, rel=1e-9)
    # after the step the friction rises (direct effect a > 0) then relaxes towards
    # mu_ss(10 um/s) = 0.6 + (a - b) ln 10 (textbook features of a velocity step)
    peak = max(mu)
    final = mu[-1]
    mu_ss = 0.6 + (0.01 - 0.008) * math.log(10.0)
    assert peak > final > 0.6
    assert final == pytest.approx(mu_ss, abs=2e-4)
    assert t[mu.index(peak)] > 10.0
    # 50 s after the step is 5 elastic loading times N a / (k V): not yet steady to 1e-4
    assert payload["verdict"] == "undetermined"
    code, out, err = _run(["simulate", "--config", str(path), "--t-max", "400 s", "--json"], capsys)
    assert code == 0, err
    assert json.loads(out)["verdict"] == "steady-sliding"


@pytest.mark.parametrize(("text", "args", "needle"), [
    (LUGRE.replace('sigma0 = "1e5 N/m"', 'sigma0 = "-1 N/m"'), [], "sigma0=-1.0 must be positive"),
    (QUASI_STATIC.replace('d_c = "10 um"', 'd_c = "0 um"'), [], "d_c=0.0 must be positive"),
    (QUASI_STATIC.replace("a = 0.01", "a = 0"), [], "a=0.0 must be positive"),
    (QUASI_STATIC.replace('"10 s", "10 um/s"', '"10 s", "10 kg"'), [], "wrong unit"),
    (LUGRE.replace('m = "1 kg"', 'm = "0 kg"'), [], "needs law = \"rate-state\""),
    (LUGRE, ["--t-max", "40 kg"], "--t-max"),
    (LUGRE, ["--history-times", "0:40"], "--history-times"),
    (QUASI_STATIC, ["--t-max", "40"], "no natural time"),
    (QUASI_STATIC, ["--initial-kick", "0.5"], "needs the slider's mass"),
    (LUGRE, ["--initial-kick", "nan"], "--initial-kick nan must be a number from -1000 to 1000"),
    (LUGRE, ["--initial-kick", "1e300"], "must be a number from -1000 to 1000"),
    (QUASI_STATIC.replace('["10 s", "10 um/s"]', '["10 s", "0 um/s"]'), [],
     "the first and the last speed of a schedule must be positive"),
    (LUGRE.replace("[system]", "[system]\nmu_k = 0.3"), [], "belong to the curve laws"),
])
def test_bad_input_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str], text: str,
                               args: list[str], needle: str) -> None:
    path = _file(tmp_path, text)
    code, out, err = _run(["simulate", "--config", str(path), *args, "--json"], capsys)
    assert code == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert needle in lines[0], lines[0]


def test_other_commands_say_where_memory_laws_run(tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    # tune tunes an absorber for the curve laws only (design takes the memory laws)
    text = LUGRE.replace('[system]\nm = "1 kg"\nk = "2 N/m"\n', "").replace(
        "[friction]", "[structure]\nmass = [[1.0]]\nstiffness = [[2.0]]\ncontact_dof = 0\n\n"
        "[absorber]\nmass = \"0.1 kg\"\nattach_dof = 0\n\n[friction]")
    path = _file(tmp_path, text)
    code, out, err = _run(["tune", "--config", str(path), "--json"], capsys)
    assert code == 2 and out == ""
    assert "simulate --config" in err and "`design`" in err
    assert len(err.strip().splitlines()) == 1


def test_old_options_refused_next_to_memory_laws(tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = _run(["simulate", "--lam", "1", "--zeta", "0.1", "--initial-kick", "0.5",
                         "--json"], capsys)
    assert code == 2 and "friction law with memory" in err


def test_dimensionless_friction_option(capsys: pytest.CaptureFixture[str]) -> None:
    # the Canudas de Wit example in the slider's units: m = k = V = 1 needs the time scale
    # sqrt(m/k) = 1/sqrt(2) s, length V/omega_n = 0.1/sqrt(2) m, force V sqrt(m k) = 0.1 sqrt(2) N:
    # load 1 N -> lambda = 1/(0.1 sqrt 2); sigma0 1e5 N/m -> 5e4 (in k); sigma1, sigma2 in sqrt(m k)
    root2 = math.sqrt(2.0)
    text = (f"lugre:sigma0=5e4,sigma1={math.sqrt(1e5) / root2},sigma2={0.4 / root2},mu_c=1,"
            "mu_s=1.5,vs=0.01")
    code, out, err = _run(["simulate", "--lam", str(1.0 / (0.1 * root2)), "--zeta", "0",
                           "--friction", text, "--initial-kick", "-1", "--t-max", "80", "--json"],
                          capsys)
    assert code == 0, err
    payload = json.loads(out)
    assert payload["verdict"] == "stick-slip"
    # the SI period 6.3627 s (test_lugre_stick_slip_contract) in tau = omega_n t
    assert payload["period"] == pytest.approx(6.3627198 * root2, rel=1e-5)
    code, _, err = _run(["map", "--lam", "1", "--zeta", "0.1", "--friction",
                         "rate-state:a=0.01,b=0.015,dc=1,mu_ref=0.6,vref=1", "--out", "x.nc"], capsys)
    assert code == 2 and "it runs on simulate with --friction, and on every --config command" in err
    # the law's name alone gets its parameters named (an independent audit: it was told to
    # use simulate, on simulate)
    code, _, err = _run(["simulate", "--lam", "3", "--zeta", "0.1", "--friction", "lugre"], capsys)
    assert code == 2 and err.count("\n") == 1
    assert "friction law 'lugre' needs its parameters, e.g. lugre:sigma0=" in err


STRUCTURE = """
load = "10 N"
speed = "1 mm/s"

[structure]
mass = [[1.0, 0.0], [0.0, 2.0]]
stiffness = [[2e4, -2e4], [-2e4, 6e4]]
damping = [[0.0, 0.0], [0.0, 5.0]]
contact_dof = 0

[friction]
law = "rate-state"
a = 0.01
b = 0.015
d_c = "10 um"
mu_ref = 0.6
v_ref = "1 um/s"
"""


def test_structure_with_rate_state(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # a 2-DOF structure whose contact spring (2e4 N/m) is stiffer than Rice & Ruina's k_c of
    # the slider alone, N (b - a)/d_c (1 + m V^2/(N a d_c)) = 5000 * 2 = 10000 N/m: steady
    # sliding is stable; kicked, the run returns to it within the default horizon
    path = _file(tmp_path, STRUCTURE)
    code, out, err = _run(["simulate", "--config", str(path), "--initial-kick", "0.5", "--json"],
                          capsys)
    assert code == 0, err
    payload = json.loads(out)
    assert payload["machine"]["n_dof"] == 2
    assert payload["steady_sliding"]["stable"] is True
    assert payload["verdict"] == "steady-sliding"


def test_json_gives_the_hopf_stiffness(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # Rice & Ruina (1983): k_c = N (b - a)/d_c (1 + m V^2/(N a d_c)) = 10 * 0.005/1e-5 * 2 = 1e4 N/m
    text = STRUCTURE.replace("[structure]\nmass = [[1.0, 0.0], [0.0, 2.0]]\n"
                             "stiffness = [[2e4, -2e4], [-2e4, 6e4]]\n"
                             "damping = [[0.0, 0.0], [0.0, 5.0]]\ncontact_dof = 0\n",
                             'm = "1 kg"\nk = "8000 N/m"\n')
    path = _file(tmp_path, text)
    code, out, err = _run(["simulate", "--config", str(path), "--t-max", "0.5 s", "--json"], capsys)
    assert code == 0, err
    steady = json.loads(out)["steady_sliding"]
    assert steady["stable"] is False
    assert steady["rice_ruina_critical_stiffness_N_m"] == pytest.approx(1e4, rel=1e-12)
    assert steady["critical_stiffness_N_m"] == pytest.approx(1e4, rel=1e-10)
    # b < a (velocity strengthening): the closed form is negative, no stiffness destabilises
    path.write_text(text.replace("b = 0.015", "b = 0.005"), encoding="utf-8")
    code, out, err = _run(["simulate", "--config", str(path), "--t-max", "0.5 s", "--json"], capsys)
    assert code == 0, err
    assert json.loads(out)["steady_sliding"]["rice_ruina_critical_stiffness_N_m"] is None


def test_a_run_that_stays_at_unstable_steady_sliding_says_to_kick_it(
        capsys: pytest.CaptureFixture[str]) -> None:
    # the shipped example (below Rice and Ruina's k_c, so steady sliding is unstable: the
    # eigenvalues, tests/test_memory_stability.py) started on steady sliding stays there; an
    # independent audit found it told to "increase t_max", which never helps: it needs a kick
    path = Path(__file__).resolve().parents[1] / "examples" / "friction_memory" / "rate_state.toml"
    code, out, err = _run(["simulate", "--config", str(path), "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    assert payload["verdict"] == "undetermined"
    assert "unstable equilibrium" in payload["status_message"]
    assert "--initial-kick" in payload["status_message"] and "t_max" not in payload["status_message"]
    code, out, err = _run(["simulate", "--config", str(path), "--initial-kick", "0.5", "--json"], capsys)
    assert code == 0, err
    assert json.loads(out)["verdict"] in ("stick-slip", "slip-oscillation")


def test_history_times_beyond_the_run_are_said(capsys: pytest.CaptureFixture[str]) -> None:
    # a bad-input audit: the rate-and-state example's run stops at its verdict (17.9 s) and the
    # history at 20 s came back null without a word
    example = Path(__file__).resolve().parent.parent / "examples" / "friction_memory" / "rate_state.toml"
    code, out, err = _run(["simulate", "--config", str(example), "--initial-kick", "0.5",
                           "--history-times", "0:20:5", "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    beyond = [t for t, x in zip(payload["history"]["t_s"], payload["history"]["x_m"], strict=True)
              if x is None]
    assert beyond and min(beyond) > payload["t_end_s"]
    [line] = err.strip().splitlines()
    assert line.startswith("stickslip: warning:") and f"{len(beyond)} of its 5 times" in line


@pytest.mark.parametrize("horizon", ["60 s", "100 s"])
def test_a_history_sample_at_t_max_is_inside_the_run(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                                     horizon: str) -> None:
    # an independent audit: --t-max "60 s" went through tau and back (60 / sqrt(m/k) * sqrt(m/k)
    # = 59.99999999999999 s for the LuGre slider, m = 1 kg, k = 2 N/m), so the run ended an ulp
    # short of 60 s and the history at 60 s was null, with a warning
    path = _file(tmp_path, LUGRE)
    end = horizon.split()[0]
    code, out, err = _run(["simulate", "--config", str(path), "--t-max", horizon, "--initial-kick",
                           "-1", "--history-times", f"0:{end}:5", "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    assert payload["t_end_s"] == float(end)
    assert all(x is not None for x in payload["history"]["x_m"])
    assert "beyond" not in err


def test_a_zero_load_number_names_lam(capsys: pytest.CaptureFixture[str]) -> None:
    # an independent audit: --lam 0 said "load=0.0 must be positive", a name the command line
    # does not have
    code, out, err = _run(["simulate", "--lam", "0", "--zeta", "0", "--friction",
                           "rate-state:a=0.01,b=0.015,dc=0.01,mu_ref=0.6,vref=1"], capsys)
    assert code == 2 and out == ""
    [line] = err.strip().splitlines()
    assert "--lam 0.0 must be positive" in line
