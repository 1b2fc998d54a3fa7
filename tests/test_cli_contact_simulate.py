"""``stickslip simulate --config`` with a machine's contact (normal DOF, separation, Jenkins).

Reference values: the event-driven solve_ivp oracle of tests/test_contact_engine.py for the
brake pad's period, and the paper's Eq. (34) for the rigid-contact limit.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from tests.cli_helpers import run_cli

#: examples/brake_pad (Hoffmann et al. 2002 minimal model) inline, at a slow belt.
BRAKE_PAD = """mu_s = 0.5
mu_k = 0.4
load = "1 kN"
speed = "2 cm/s"

[structure]
mass = [[0.1, 0.0], [0.0, 0.1]]
stiffness = [[8e7, -1.5e7], [-1.5e7, 2.5e7]]
damping = [[40.0, 0.0], [0.0, 4.0]]
contact_dof = 0
normal_dof = 1

[contact]
normal_stiffness = "5e7 N/m"
"""


def write(tmp_path: Path, text: str) -> str:
    path = tmp_path / "machine.toml"
    path.write_text(text)
    return str(path)


def one_error(err: str) -> str:
    """The single error line (a first-run compile notice may precede it), no traceback."""
    lines = [line for line in err.splitlines() if line.startswith("stickslip: error:")]
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


def test_brake_pad_stick_slip_with_separation_json(tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    # the period 0.0002497536798011929 s is the event-driven solve_ivp oracle's
    # (tests/test_contact_engine.py, the same machine), to 1e-7
    code, out, err = run_cli(["simulate", "--config", write(tmp_path, BRAKE_PAD), "--json",
                              "--history-times", "0.0630:0.0638:161"], capsys)
    assert code == 0, err
    p = json.loads(out)
    assert p["verdict"] == "stick-slip" and p["separated"] is True
    assert p["period_s"] == pytest.approx(0.0002497536798011929, rel=1e-7)
    assert p["amplitude_m"] > 0.0 and p["event_counts"]["lift-off"] > 0
    history = p["history"]
    assert len(history["t_s"]) == 161 and min(history["normal_force_N"]) == 0.0
    assert "separation" in history["mode"] and "stick" in history["mode"]


@pytest.mark.parametrize(("load", "speed", "start"), [
    ("1 kN", "2 cm/s", "stuck to the belt"),
    # c V = 40 N s/m x 5 m/s = 200 N > mu_s W = 0.5 x 316 N = 158 N: no stick can hold it
    ("316 N", "5 m/s", "in slip forward at once"),
])
def test_the_start_is_said(tmp_path: Path, capsys: pytest.CaptureFixture[str], load: str,
                           speed: str, start: str) -> None:
    text = BRAKE_PAD.replace('load = "1 kN"', f'load = "{load}"').replace(
        'speed = "2 cm/s"', f'speed = "{speed}"')
    code, out, err = run_cli(["simulate", "--config", write(tmp_path, text), "--t-max", "1 ms"],
                             capsys)
    assert code == 0, err
    line = next(x for x in out.splitlines() if x.startswith("start"))
    assert start in line, line
    code, out, err = run_cli(["simulate", "--config", write(tmp_path, text), "--t-max", "1 ms",
                              "--json"], capsys)
    assert json.loads(out)["initial_mode"] == ("stick" if "stuck" in start else "slip forward")


def test_paper_slider_with_a_stiff_damped_jenkins_element(tmp_path: Path,
                                                          capsys: pytest.CaptureFixture[str]) -> None:
    # m = 1 kg, k = 1 N/m, undamped, lambda = (mu_s - mu_k) W / (V sqrt(m k)) = 0.5: a stiff
    # contact with damping ratio 0.3 gives Eq. (34)'s period 2 pi (1 + (lambda - atan lambda)
    # / pi) s back to 1e-3
    text = ('mu_s = 0.3\nmu_k = 0.2\nload = "1 N"\nspeed = "0.2 m/s"\nm = "1 kg"\nk = "1 N/m"\n'
            'c = "0 N*s/m"\n\n[contact]\ntangential_stiffness = "1e4 N/m"\n'
            'tangential_damping = "60 N*s/m"\n')
    code, out, err = run_cli(["simulate", "--config", write(tmp_path, text), "--json"], capsys)
    assert code == 0, err
    p = json.loads(out)
    period = 2.0 * math.pi * (1.0 + (0.5 - math.atan(0.5)) / math.pi)
    assert p["verdict"] == "stick-slip" and p["separated"] is False
    assert p["period_s"] == pytest.approx(period, rel=1e-3)


@pytest.mark.parametrize(("change", "extra", "why"), [
    (('normal_stiffness = "5e7 N/m"', 'normal_stiffness = "-5e7 N/m"'), [],
     "normal_stiffness = -50000000.0 must be positive"),
    (("[contact]", '[friction]\nlaw = "linear"\nslope = "0.1 s/m"\n\n[contact]'), [],
     "takes the Coulomb law (mu_s, mu_k) only"),
    (("[contact]", '[friction]\nlaw = "lugre"\n\n[contact]'), [],
     "runs with the Coulomb law (mu_s, mu_k) only, not with a friction law with memory"),
    (None, ["--plot", "x.png"], "--plot cannot be given with a [contact] machine"),
    (None, ["--initial", "0,0,0,0"], "--initial cannot be given with a [contact] machine"),
    (None, ["--t-max", "1 ms", "--history-times", "0:9:3"], "goes beyond the end of the run"),
])
def test_bad_input_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                               change: tuple[str, str] | None, extra: list[str], why: str) -> None:
    text = BRAKE_PAD.replace(*change) if change else BRAKE_PAD
    code, out, err = run_cli(["simulate", "--config", write(tmp_path, text), *extra], capsys)
    assert code == 2 and out == ""
    assert why in one_error(err)


def test_a_settling_cycle_gets_its_own_period_not_a_multiple(tmp_path: Path,
                                                             capsys: pytest.CaptureFixture[str]) -> None:
    # the brake pad at 1 m/s settles on a slip-and-separation cycle so slowly that its states
    # 8 cycles apart met the 1e-9 repeat tolerance before neighbours did (period reported
    # 8 x 0.243 ms). Reference, independent of the repeat test: the spacing of the run's own
    # last lift-off events, one per cycle.
    text = BRAKE_PAD.replace('speed = "2 cm/s"', 'speed = "1 m/s"')
    code, out, err = run_cli(["simulate", "--config", write(tmp_path, text), "--json"], capsys)
    assert code == 0, err
    p = json.loads(out)
    lift_offs = [e["t_s"] for e in p["events"] if e["kind"] == "lift-off"]
    assert p["verdict"] == "slip-oscillation" and len(lift_offs) >= 3
    assert p["period_s"] == pytest.approx(lift_offs[-1] - lift_offs[-2], rel=1e-6)
