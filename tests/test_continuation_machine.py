"""``continue --config``: the diagram of the user's own machine, in SI (issue 30, point 3).

A 3-DOF chain with the contact on its middle DOF (``[structure]`` inline, kg, N/m, N s/m),
continued in the belt speed. The source of the reference values is the direct run: at five
points of the continued branch, :func:`stickslip.simulate` from the start-up state of the same
machine at that speed (its certified cycle, converted with ``1/omega_n`` and ``V/omega_n`` of
the contact, ``omega_n = sqrt(K[c, c] / M[c, c])``, Eq. 17, Eqs. 15-16) must give the period
and amplitude the branch reports.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from tests.cli_helpers import run_cli

MACHINE = """mu_s = 0.6
mu_k = 0.4
load = "20 N"
speed = "0.05 m/s"

[structure]
name = "chain3"
mass = [[2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 3.0]]
stiffness = [[300.0, -100.0, 0.0], [-100.0, 150.0, -50.0], [0.0, -50.0, 250.0]]
damping = [[6.0, -2.0, 0.0], [-2.0, 5.0, -1.0], [0.0, -1.0, 8.0]]
contact_dof = 1
"""
#: the contact DOF's own mass and stiffness: omega_n = sqrt(150 / 1) rad/s
OMEGA_N = math.sqrt(150.0 / 1.0)


def _machine_file(tmp: Path) -> Path:
    path = tmp / "machine.toml"
    path.write_text(MACHINE, encoding="utf-8")
    return path


@pytest.mark.slow
def test_machine_branch_matches_direct_runs_at_five_speeds(tmp_path: Path,
                                                           capsys: pytest.CaptureFixture[str]) -> None:
    from stickslip.analysis.simulation import simulate
    from stickslip.analysis.verdict import Verdict
    from stickslip.cli.machine_config import configured_machine

    code, text, err = run_cli(["continue", "--config", str(_machine_file(tmp_path)), "--param", "speed",
                               "--range", "2 cm/s:6 cm/s", "--json"], capsys)
    assert code == 0, err
    payload = json.loads(text)
    assert payload["param"] == "speed" and payload["param_units"] == "m/s"
    assert payload["range"] == pytest.approx([0.02, 0.06], rel=1e-12)
    (branch,) = payload["branches"]
    assert branch["kind"] == "stick-slip"
    speeds = [p["speed"] for p in branch["points"]]
    assert min(speeds) == pytest.approx(0.02, abs=1e-15) and max(speeds) == pytest.approx(0.06, abs=1e-15)
    machine = configured_machine(_machine_file(tmp_path)).machine
    for target in np.linspace(0.02, 0.06, 5):
        point = min(branch["points"], key=lambda p: abs(p["speed"] - target))
        v = point["speed"]
        structure, slider = machine.with_operating_point(speed=v).to_dimensionless()
        run = simulate(structure, slider, record=False)
        assert run.verdict is Verdict.STICK_SLIP
        assert point["period_s"] == pytest.approx(run.period / OMEGA_N, rel=1e-8)
        assert point["amplitude_m"] == pytest.approx(run.amplitude * v / OMEGA_N, rel=1e-8)
        # 3 DOFs: 2 n - 2 = 4 Floquet multipliers of the breakaway map, all inside (stable)
        assert len(point["multipliers"]) == 4 and point["stable"]
        assert max(m["abs"] for m in point["multipliers"]) == pytest.approx(point["multiplier"], rel=1e-12)
        assert point["multiplier"] < 1.0


@pytest.mark.parametrize("args, needle", [
    (["--param", "lam", "--range", "1:2"], "--param 'lam'"),
    (["--param", "speed", "--range", "1 kg:2 kg"], "--range"),
    (["--param", "speed", "--range", "3 cm/s:2 cm/s"], "A < B"),
    (["--param", "mu_k", "--range", "0.3:0.7"], "mu_k = 0.7"),
    (["--param", "speed", "--range", "1:2", "--lam", "3"], "--lam"),
])
def test_machine_bad_input_is_one_line_and_exit_2(args: list[str], needle: str, tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    code, text, err = run_cli(["continue", "--config", str(_machine_file(tmp_path)), *args, "--json"], capsys)
    assert code == 2 and text == "" and len(err.strip().splitlines()) == 1
    assert needle in err


def test_paper_slider_in_load_is_born_at_eq36_in_newtons(tmp_path: Path,
                                                         capsys: pytest.CaptureFixture[str]) -> None:
    # m = 2 kg, k = 8 N/m, c = 0.4 N s/m: zeta = c / (2 sqrt(mk)) = 0.05; lambda =
    # (mu_s - mu_k) W / (V sqrt(mk)), so the branch is born where lambda is Eq. (36)'s
    from stickslip.analysis.theory import critical_lambda_exact

    path = tmp_path / "slider.toml"
    path.write_text("m = 2.0\nk = 8.0\nc = 0.4\nmu_s = 0.5\nmu_k = 0.3\nload = 30.0\nspeed = 1.0\n",
                    encoding="utf-8")
    figure, out = tmp_path / "d.png", tmp_path / "d.nc"
    code, text, err = run_cli(["continue", "--config", str(path), "--param", "load",
                               "--range", "10 N:0.06 kN", "--json", "--plot", str(figure),
                               "--out", str(out)], capsys)
    assert code == 0, err
    payload = json.loads(text)
    assert payload["range"] == [10.0, 60.0] and payload["param_units"] == "N"
    (graze,) = [e for e in payload["events"] if e["type"] == "grazing"]
    w_c = critical_lambda_exact(0.05) * 1.0 * math.sqrt(2.0 * 8.0) / (0.5 - 0.3)
    assert graze["load"] == pytest.approx(w_c, abs=1e-7)
    (branch,) = payload["branches"]
    assert max(p["load"] for p in branch["points"]) == 60.0
    omega_n = math.sqrt(8.0 / 2.0)
    for p in branch["points"]:  # V / omega_n and 1 / omega_n of the slider itself
        assert p["amplitude_m"] == pytest.approx(p["amplitude"] * 1.0 / omega_n, rel=1e-12)
        assert p["period_s"] == pytest.approx(p["period"] / omega_n, rel=1e-12)
    assert figure.stat().st_size > 10_000
    import xarray as xr

    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert ds["load"].attrs["units"] == "N" and ds["period_s"].attrs["units"] == "s"
        np.testing.assert_allclose(ds["amplitude_m"].values, [p["amplitude_m"] for p in branch["points"]],
                                   rtol=1e-12)


def test_si_parameter_is_continued_at_the_scale_of_its_range() -> None:
    """A 2-DOF modal machine in belt speed (mm/s): the branch crosses 1.3-2.5 mm/s within 60
    steps, end to end (continued in SI units, the arclength was all coordinates: it stopped
    at the step bound after a sliver of the range), and its period and amplitude at three
    speeds are those of direct runs started on the branch's breakaway state
    (:func:`stickslip.simulate`, the reference; from start-up this machine slides steadily at
    1.3 mm/s: the cycle coexists with steady sliding)."""
    from stickslip import InitialState, simulate
    from stickslip.analysis.continuation import MachineSystem, continue_cycles
    from stickslip.app.machine_page import MODE_INPUTS, machine_from_files, modes_machine_toml

    raw = {key: default for key, (_, default) in MODE_INPUTS.items()}
    machine, _, _ = machine_from_files({"m.toml": modes_machine_toml(raw).encode()})
    result = continue_cycles(MachineSystem(machine), "speed", (1.3e-3, 2.5e-3), max_steps=60, seeds=4)
    (branch,) = result.branches
    assert branch.stop_reason == "backward: range-end; forward: range-end"
    assert branch.points[0].param == 1.3e-3 and branch.points[-1].param == 2.5e-3
    for point in (branch.points[0], branch.points[len(branch.points) // 2], branch.points[-1]):
        structure, slider = machine.with_operating_point(speed=point.param).to_dimensionless()
        n = structure.n_dof
        run = simulate(structure, slider, record=False,
                       initial=InitialState(point.state[:n], point.state[n:]))
        assert run.cycle_length == 1
        assert point.period == pytest.approx(run.period, rel=1e-7)
        assert point.amplitude == pytest.approx(run.amplitude, rel=1e-6)
