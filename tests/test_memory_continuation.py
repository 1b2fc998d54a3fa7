"""``continue --config`` with friction with memory (analysis.memory.continuation, issue 33).

References: the 1-DOF rate-and-state slider (m 1 kg, k 8000 N/m, N 10 N, a 0.01, b 0.015,
d_c 10 um) has one Hopf point, at the speed where Rice and Ruina's k_c(V) equals k:
V_c^2 = (N a d_c / m)(k d_c / (N (b - a)) - 1) (tests/test_memory_stability.py). Its orbits
are born there: the branch's low end is at V_c, its amplitude shrinks towards it and its
period tends to 2 pi / omega of the critical eigenvalue pair of the linearisation (an
independent path: eigenvalues, not shooting). Away from the Hopf point the branch's period is
that of simulate_memory's run from a kicked start at that speed.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from stickslip.analysis.memory.continuation import continue_memory_orbits
from stickslip.analysis.memory.simulation import simulate_memory
from stickslip.analysis.memory.stability import linear_spectrum
from stickslip.io.machine_file import read_machine_file
from stickslip.model.state_friction import SpeedSchedule
from tests.cli_helpers import run_cli
from tests.memory_machines import RATE_STATE

ROOT = Path(__file__).resolve().parents[1]
V_C = math.sqrt(10.0 * 0.01 * 1e-5 / 1.0 * (8000.0 * 1e-5 / (10.0 * 0.005) - 1.0))


def _file(tmp_path: Path) -> Path:
    path = tmp_path / "machine.toml"
    path.write_text(RATE_STATE, encoding="utf-8")
    return path


def test_branch_is_born_at_the_rice_ruina_hopf_point(tmp_path: Path) -> None:
    system = read_machine_file(_file(tmp_path)).memory_system()
    result = continue_memory_orbits(system, (3e-4, 3e-3))
    assert result.hopf == (pytest.approx(V_C, rel=1e-9),)
    (branch,) = result.branches
    first, last = branch.points[0], branch.points[-1]
    assert first.speed == pytest.approx(V_C, rel=1e-3) and last.speed == 3e-3
    assert branch.high_end == "range end" and "ceases to exist" in branch.low_end
    assert first.amplitude < 0.1 * last.amplitude
    values, _ = linear_spectrum(system, V_C)
    omega = float(np.max(np.abs(values[np.argsort(-values.real)[:2]].imag)))
    assert first.period == pytest.approx(2.0 * math.pi / omega, rel=0.01)
    # away from the Hopf point: the orbit a run settles on from a kicked start
    point = branch.points[len(branch.points) // 2]
    at = replace(system, schedule=SpeedSchedule.constant(point.speed))
    settled = simulate_memory(at, kick=2.0)
    assert settled.period == pytest.approx(point.period, rel=1e-6)
    assert all(p.stable for p in branch.points)  # supercritical: the orbits are stable



def test_cli(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _file(tmp_path)
    code, out, err = run_cli(["continue", "--config", str(path), "--param", "speed", "--range",
                           "1 mm/s:2 mm/s", "--plot", str(tmp_path / "c.png"), "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    assert payload["hopf_speeds_m_per_s"] == [] and len(payload["branches"]) == 1
    assert (tmp_path / "c.png").stat().st_size > 0
    for extra, needle in ((["--param", "load", "--range", "1:2"], "drive speed"),
                          (["--param", "speed", "--range", "1:2", "--seeds", "3"], "--seeds"),
                          (["--param", "speed", "--range", "1:2", "--out", "x.nc"], "--out")):
        code, out, err = run_cli(["continue", "--config", str(path), *extra], capsys)
        assert code == 2 and out == "" and needle in err and len(err.strip().splitlines()) == 1


@pytest.mark.slow  # 35-50 s: two continuations and two stiff runs (default run under 10 min)
def test_lugre_subcritical_hopf_gives_the_unstable_orbit_that_bounds_steady_sliding() -> None:
    # Canudas de Wit et al.'s (1995) LuGre slider (examples/friction_memory/lugre.toml): steady
    # sliding becomes stable at the Hopf point V_H = 2.986 mm/s (tests/test_memory_stability.py,
    # Routh-Hurwitz) while stick-slip goes on above it (bistable), so the Hopf point is
    # subcritical: the orbit born there is unstable and exists above V_H. Checks independent
    # of the continuation: its period tends to 2 pi / omega of the critical eigenvalue pair,
    # and it separates the basins: a start just inside it (towards steady sliding) ends at
    # steady sliding, one just outside ends on the stick-slip cycle.
    system = read_machine_file(ROOT / "examples" / "friction_memory" / "lugre.toml").memory_system()
    result = continue_memory_orbits(system, (2e-3, 5e-3))
    (v_h,) = result.hopf
    unstable = [b for b in result.branches if not any(p.stable for p in b.points)]
    assert len(unstable) == 1
    points = unstable[0].points
    assert min(p.speed for p in points) == pytest.approx(v_h, rel=5e-3)
    assert all(p.speed > v_h for p in points)
    first = min(points, key=lambda p: p.speed)
    values, _ = linear_spectrum(system, v_h)
    omega = float(np.max(values.imag))
    assert first.period == pytest.approx(2.0 * math.pi / omega, rel=0.01)
    point = points[len(points) // 2]
    at = replace(system, schedule=SpeedSchedule.constant(point.speed))
    from stickslip.analysis.memory.friction import steady_state

    y_ss = steady_state(at, point.speed)
    inside = simulate_memory(at, initial=y_ss + 0.9 * (point.orbit.y0 - y_ss))
    outside = simulate_memory(at, initial=y_ss + 1.1 * (point.orbit.y0 - y_ss))
    assert inside.verdict.value == "steady-sliding"
    assert outside.verdict.value == "stick-slip"


def test_orbits_beside_the_hopf_point_are_not_called_unstable(
        capsys: pytest.CaptureFixture[str]) -> None:
    # An independent audit: the Hopf point of examples/friction_memory/rate_state.toml is
    # supercritical (first Lyapunov coefficient -915, by sympy), so the orbits born there are
    # stable (its shooting in deviation variables: |mu| = 0.99997 at 7.7460178e-4 m/s); the
    # monodromy at the default tolerance gave |mu| = 1.0000044-1.0000055 for the three orbits
    # nearest it. Such points are unresolved, never unstable.
    from stickslip.analysis.memory.cycles import MULTIPLIER_RESOLUTION

    config = ROOT / "examples" / "friction_memory" / "rate_state.toml"
    code, out, err = run_cli(["continue", "--config", str(config), "--param", "speed", "--range",
                              "0.7 mm/s:1 mm/s", "--json"], capsys)
    assert code == 0, err
    points = [p for b in json.loads(out)["branches"] for p in b["points"]]
    assert len(points) > 10
    for p in points:
        top = max(p["multiplier_moduli"])
        assert p["stability_resolved"] is (abs(top - 1.0) > MULTIPLIER_RESOLUTION)
        assert p["stable"] or not p["stability_resolved"], p  # no resolved unstable orbit
    nearest = min(points, key=lambda p: p["amplitude_m"])
    assert not nearest["stability_resolved"]
    assert sum(p["stable"] and p["stability_resolved"] for p in points) > 10
