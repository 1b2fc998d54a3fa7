"""``cycles --config`` with friction with memory (analysis.memory.cycle_search, issue 33).

References: the LuGre example of Canudas de Wit et al. (1995) is bistable at 0.1 m/s (steady
sliding linearly stable, eigenvalues -0.2 +/- 1.4i 1/s by the hand linearisation of
tests/test_memory_stability.py, and a stick-slip cycle from a start stuck to the drive, period
6.3627198 s: tests/test_cli_memory_friction.py against scipy's DOP853 in test_stiff_engine);
the search must list that one cycle, reached from the stuck start, and steady sliding from small
kicks. Below Rice and Ruina's k_c the rate-and-state slider oscillates about steady sliding.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from stickslip.analysis.memory.cycle_search import find_memory_cycles
from stickslip.io.machine_file import read_machine_file
from tests.cli_helpers import run_cli
from tests.memory_machines import LUGRE


def _file(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "machine.toml"
    path.write_text(text, encoding="utf-8")
    return path



def test_lugre_bistable_point(tmp_path: Path) -> None:
    system = read_machine_file(_file(tmp_path, LUGRE)).memory_system()
    result = find_memory_cycles(system, kicks=(-1.0, 0.25, 0.5, 2.0))
    assert len(result.cycles) == 1
    (cycle,) = result.cycles
    assert cycle.kind == "stick-slip" and cycle.run.orbit is not None and cycle.run.orbit.stable
    assert cycle.run.period == pytest.approx(6.3627198, rel=1e-6)
    assert cycle.kicks == [-1.0, 2.0]
    assert result.steady_kicks == [0.25, 0.5]


def test_cli_contract(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _file(tmp_path, LUGRE)
    code, out, err = run_cli(["cycles", "--config", str(path), "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    assert payload["n_cycles"] == 1
    assert payload["cycles"][0]["period_s"] == pytest.approx(6.3627198, rel=1e-6)
    assert max(payload["cycles"][0]["multiplier_moduli"]) < 1.0
    assert "not searched" in payload["unstable_cycles"]


def test_cli_refuses_a_schedule_and_the_quasi_static_slider(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    schedule = LUGRE.replace('speed = "0.1 m/s"', 'speed = [["0 s", "0.1 m/s"], ["5 s", "0.2 m/s"]]')
    code, out, err = run_cli(["cycles", "--config", str(_file(tmp_path, schedule))], capsys)
    assert code == 2 and out == "" and "one drive speed" in err and len(err.strip().splitlines()) == 1
    quasi = """
[system]
m = "0 kg"
k = "1e5 N/m"
load = "1 kN"
speed = "1 um/s"

[friction]
law = "rate-state"
a = 0.01
b = 0.008
d_c = "10 um"
mu_ref = 0.6
v_ref = "1 um/s"
"""
    code, out, err = run_cli(["cycles", "--config", str(_file(tmp_path, quasi))], capsys)
    assert code == 2 and out == "" and "quasi-static" in err and len(err.strip().splitlines()) == 1
