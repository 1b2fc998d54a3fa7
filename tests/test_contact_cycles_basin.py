"""``cycles``, ``basin`` and ``continue`` with ``--config`` for a machine with its contact.

The machine: the paper's 1 DOF slider (m = k = W = 1, zeta = 0.1, mu_s = 0.3, mu_k = 0.2,
lambda = 0.1 / V) on a massless Jenkins element with k_t / k = 10 and contact damping ratio
0.3 (c_t = 0.6 sqrt(10) N s/m), the element of docs/brake_squeal.md (boundary lambda_c =
1.5568). Sources of the reference values, named at each assertion:

- the event-driven solve_ivp oracle of tests/test_contact_engine.py (``jenkins_oracle``,
  DOP853, rtol 1e-11, sharing no code with the engine);
- ``stickslip simulate --config`` on the same file;
- direct runs of :func:`~stickslip.analysis.contact.engine.simulate_contact` from states
  built here from the equations (steady sliding: ``x* = mu_k W / k``, ``e* = -mu_k W / k_t``);
- the contraction of a run's own breakaway states onto the cycle (for the multipliers).
"""

from __future__ import annotations

import csv
import json
import math
import multiprocessing
from pathlib import Path

import numpy as np
import pytest

from stickslip.analysis.contact._pool import run_many
from stickslip.analysis.contact.continuation import continue_contact
from stickslip.analysis.contact.engine import ContactSystem, simulate_contact
from tests.cli_helpers import run_cli
from tests.test_cli_contact_simulate import one_error
from tests.test_contact_engine import jenkins_oracle

KT, CT = 10.0, 0.6 * math.sqrt(10.0)
MU_S, MU_K = 0.3, 0.2


def slider_text(speed: float) -> str:
    return (f'mu_s = {MU_S}\nmu_k = {MU_K}\nload = "1 N"\nspeed = "{speed!r} m/s"\nm = "1 kg"\n'
            f'k = "1 N/m"\nc = "0.2 N*s/m"\n\n[contact]\ntangential_stiffness = "{KT!r} N/m"\n'
            f'tangential_damping = "{CT!r} N*s/m"\n')


def slider(speed: float) -> ContactSystem:
    """The same machine built directly (not through the machine file)."""
    return ContactSystem(np.eye(1), np.array([[0.2]]), np.eye(1), 0, None, 1.0, speed, MU_S, MU_K,
                         tangential_stiffness=KT, tangential_damping=CT)


def write(tmp_path: Path, text: str) -> str:
    path = tmp_path / "machine.toml"
    path.write_text(text)
    return str(path)


def test_cycles_period_is_that_of_simulate_and_of_the_solve_ivp_oracle(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    config = write(tmp_path, slider_text(0.05))  # lambda = 2 > 1.5568: stick-slip from start-up
    code, out, err = run_cli(["cycles", "--config", config, "--json"], capsys)
    assert code == 0, err
    p = json.loads(out)
    assert p["n_starts"] == 8 and p["n_cycles"] == 1 and "observed, not proven" in p["status"]
    cycle = p["cycles"][0]
    assert cycle["kind"] == "stick-slip" and "start-up" in cycle["starts"]
    assert cycle["stick_phases_per_period"] == 1 and cycle["separated"] is False
    assert cycle["events_per_period"] == {"belt speed": 1, "breakaway forward": 1}
    assert p["steady_sliding_starts"]  # coexisting steady sliding: kicked starts reach it
    code, out, err = run_cli(["simulate", "--config", config, "--json"], capsys)
    assert code == 0, err
    simulated = json.loads(out)
    # source 1: simulate --config on the same file (the same engine from start-up)
    assert cycle["period_s"] == pytest.approx(simulated["period_s"], rel=1e-12)
    assert cycle["amplitude_m"] == pytest.approx(simulated["amplitude_m"], rel=1e-9)
    # source 2: the independent event-driven solve_ivp of tests/test_contact_engine.py
    ref = jenkins_oracle(2.0, 0.1, KT, CT, simulated["t_end_s"] * (1.0 + 1e-9))
    breaks = [t for kind, t in ref if kind == "break+"]
    print(f"period: cycles {cycle['period_s']!r} | oracle {breaks[-1] - breaks[-2]!r}")
    assert cycle["period_s"] == pytest.approx(breaks[-1] - breaks[-2], rel=1e-8)


def test_cycles_of_a_contact_take_t_max(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # its certificate says "increase t_max", so --t-max must be taken (an audit found it
    # refused): a horizon of 1 s is shorter than one period of the stick-slip cycle (7.48 s,
    # simulate --config on this file; the start-up run repeats at t = 66 s), so every start
    # ends undetermined at it
    config = write(tmp_path, slider_text(0.05))
    code, out, err = run_cli(["cycles", "--config", config, "--json", "--t-max", "1 s"], capsys)
    assert code == 0, err
    p = json.loads(out)
    assert p["n_cycles"] == 0 and len(p["undetermined_starts"]) == 8, p
    assert all("time horizon" in text for text in p["undetermined_starts"].values())
    code, _, err = run_cli(["cycles", "--config", config, "--t-max", "-1 s"], capsys)
    assert code == 2 and "--t-max" in err


def test_estimated_multiplier_is_the_contraction_of_a_run_onto_the_cycle() -> None:
    # source: the run from start-up converges on the cycle; successive breakaway states'
    # differences shrink by the dominant multiplier's modulus each period (one nonzero
    # multiplier: the stick phase resets the slider's velocity)
    from stickslip.analysis.contact.cycles import find_contact_cycles

    system = slider(0.1 / 1.62)
    result = find_contact_cycles(system)
    assert len(result.cycles) == 1
    moduli = np.abs(result.cycles[0].multipliers)
    run = simulate_contact(system)
    states = np.array([run.segment_states[i + 1] for i, e in enumerate(run.events)
                       if e.kind == "breakaway forward"])
    steps = np.linalg.norm(np.diff(states, axis=0) / system.state_scale, axis=1)
    ratio = steps[4] / steps[3]  # well above the 1e-9 repeat tolerance
    print(f"|multipliers| {moduli} | contraction {steps[1:] / steps[:-1]}")
    assert moduli[0] == pytest.approx(ratio, rel=1e-3)
    assert moduli[1] < 1e-6  # the reset direction
    assert result.cycles[0].trivial == pytest.approx(1.0, abs=1e-5)


def test_basin_labels_equal_direct_runs(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    config = write(tmp_path, slider_text(0.05))
    out_dir = tmp_path / "run"
    code, out, err = run_cli(["basin", "--config", config, "--samples", "12", "--seed", "4",
                              "--box", "v=-0.05:0.1", "--out", str(out_dir), "--json"], capsys)
    assert code == 0, err
    p = json.loads(out)
    assert p["n"] == 12 and p["columns"] == ["x", "v"] and "observed, not proven" in p["status"]
    fr, se = p["fractions"], p["standard_errors"]
    assert sum(fr.values()) == pytest.approx(1.0)
    assert se["stick-slip"] == pytest.approx(math.sqrt(fr["stick-slip"] * (1 - fr["stick-slip"]) / 12))
    rows = list(csv.DictReader((out_dir / "labels.csv").open()))
    assert len(rows) == 12 and list(rows[0]) == ["x_m", "v_m_s", "verdict", "period_s", "separated"]
    assert {r["verdict"] for r in rows} == {"stick-slip", "steady-sliding"}
    system = slider(0.05)
    # source: direct runs from the state built from the equations (e* = -mu_k W / k_t)
    for row in rows[:4]:
        x, v = float(row["x_m"]), float(row["v_m_s"])
        assert x == pytest.approx(MU_K / 1.0, rel=1e-12)  # the box left x at steady sliding
        run = simulate_contact(system, initial=np.array([x, v, -MU_K / KT]))
        assert row["verdict"] == run.verdict.value
        if run.period_s is not None:
            assert float(row["period_s"]) == pytest.approx(run.period_s, rel=1e-12)
    code, _, err = run_cli(["basin", "--config", config, "--samples", "3", "--out", str(out_dir)],
                           capsys)
    assert code == 2 and "exists" in one_error(err)


def test_continuation_periods_equal_direct_runs(tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    config = write(tmp_path, slider_text(0.05))
    table = tmp_path / "branches.csv"
    code, out, err = run_cli(["continue", "--config", config, "--param", "speed", "--range",
                              "2 cm/s:8 cm/s", "--points", "5", "--json", "--out", str(table)],
                             capsys)
    assert code == 0, err
    p = json.loads(out)
    assert p["param_units"] == "m/s" and len(p["points"]) == 5
    assert "unstable orbits and folds are not found" in p["followed"]
    values = [pt["value"] for pt in p["points"]]
    assert values == pytest.approx(np.geomspace(0.02, 0.08, 5).tolist(), rel=1e-12)
    # source: direct runs from start-up at three of the speeds (0.02, 0.04, 0.08 m/s)
    for i in (0, 2, 4):
        point, run = p["points"][i], simulate_contact(slider(values[i]))
        assert point["startup"]["verdict"] == run.verdict.value
        assert point["continued"]["verdict"] == run.verdict.value
        if run.period_s is not None:
            assert point["startup"]["period_s"] == pytest.approx(run.period_s, rel=1e-12)
            assert point["continued"]["period_s"] == pytest.approx(run.period_s, rel=1e-6)
    assert p["points"][4]["continued"]["verdict"] == "steady-sliding"  # lambda 1.25 < 1.5568
    rows = list(csv.DictReader(table.open()))
    assert len(rows) == 10 and rows[0]["speed_m_s"] and rows[0]["source"] == "continued"
    kinds = [b["verdict"] for b in p["branches"] if b["source"] == "continued"]
    assert kinds == ["stick-slip", "steady-sliding"]


def test_continuation_plot_has_si_labels_and_takes_an_axes() -> None:
    from matplotlib.figure import Figure

    result = continue_contact(slider(0.05), "load", (0.5, 2.0), points=3, workers=1)
    _fig, axes, artists = result.plot()
    assert len(axes) == 2 and artists
    assert "(N)" in axes[1].get_xlabel() and "(s)" in axes[0].get_ylabel()
    assert "(m)" in axes[1].get_ylabel() and "$" in axes[1].get_xlabel()
    ax = Figure().add_subplot()
    assert result.plot(ax=ax).axes[0] is ax


# starting two pools of worker processes: 6.5 s alone on the machine
def test_a_pool_gives_the_same_outcomes_and_ends_its_workers_on_ctrl_c() -> None:
    # two worker processes (pool forced by a zero threshold) against this process; processes
    # other tests of the session started (the app's worker) are not this pool's
    before = set(multiprocessing.active_children())
    jobs = [(slider(0.05), None), (slider(0.03), None), (slider(0.08), None)]
    here = run_many(jobs, workers=1)
    pooled = run_many(jobs, workers=2, pool_threshold=0.0)
    assert [(o.verdict, o.period_s) for o in here] == [(o.verdict, o.period_s) for o in pooled]

    def interrupt(done: int, total: int) -> None:
        if done >= 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_many(jobs * 3, workers=2, pool_threshold=0.0, progress=interrupt)
    assert set(multiprocessing.active_children()) <= before


@pytest.mark.parametrize(("args", "why"), [
    (["cycles", "--seeds", "3"], "--seeds cannot be given to `cycles` with a [contact] machine"),
    (["basin", "--plot", "b.png"], "--plot cannot be given to `basin` with a [contact] machine"),
    (["basin", "--box", "q=0:1"], "box columns q are not among x, v"),
    (["basin", "--samples", "0"], "samples=0 must be a whole number"),
    (["continue", "--param", "mu_s", "--range", "0.3:0.4"], "is continued in speed or load"),
    (["continue", "--param", "speed", "--range", "1:2", "--out", "b.nc"], "must end in .csv or .json"),
    (["continue", "--param", "speed", "--range", "1:2", "--points", "1"], "--points 1 must be from 2"),
    (["continue", "--param", "load", "--range", "1 m/s:2 m/s"], "--range '1 m/s:2 m/s' must be A:B"),
])
def test_bad_input_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                               args: list[str], why: str) -> None:
    config = write(tmp_path, slider_text(0.05))
    code, out, err = run_cli([args[0], "--config", config, *args[1:]], capsys)
    assert code == 2 and out == ""
    assert why in one_error(err)


def test_points_without_a_contact_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    config = write(tmp_path, slider_text(0.05).split("[contact]")[0])
    code, _, err = run_cli(["continue", "--config", config, "--param", "speed", "--range", "1:2",
                            "--points", "5"], capsys)
    assert code == 2 and "--points is for a [contact] machine" in one_error(err)


@pytest.mark.slow
def test_brake_pad_cycles_has_the_oracles_period(capsys: pytest.CaptureFixture[str]) -> None:
    # the slow belt's stick-slip with separation: the solve_ivp oracle's period
    # 0.0002497536798011929 s (tests/test_contact_engine.py, quoted in
    # tests/test_cli_contact_simulate.py), to 1e-7
    config = Path(__file__).resolve().parents[1] / "examples" / "brake_pad" / "slow_belt.toml"
    code, out, err = run_cli(["cycles", "--config", str(config), "--json"], capsys)
    assert code == 0, err
    p = json.loads(out)
    periods = [c["period_s"] for c in p["cycles"] if c["kind"] == "stick-slip"]
    assert any(t == pytest.approx(0.0002497536798011929, rel=1e-7) for t in periods), periods
