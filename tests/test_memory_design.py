"""``stickslip design --config`` with a friction law with memory (rate-and-state, LuGre).

Sources: Rice and Ruina (1983) for the 1-DOF rate-and-state slider's critical stiffness
``k_c = N (b - a)/d_c (1 + m V^2/(N a d_c))``, solved here for the critical load; Canudas de
Wit et al. (1995) for the LuGre stick-slip example (tests/memory_machines.py).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.cli_helpers import run_cli
from tests.memory_machines import LUGRE, RATE_STATE, machine_file


def test_rate_state_critical_load_is_rice_ruina(tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    # k = k_c(N) = N (b - a)/d_c + m V^2 (b - a)/(a d_c^2) solved for N:
    # N_c = (k - m V^2 (b - a)/(a d_c^2)) d_c/(b - a) = (8000 - 5000) 1e-5 / 0.005 = 6 N,
    # and steady sliding is unstable above it (k < k_c grows with N)
    k, m, v, a, b, d_c = 8000.0, 1.0, 1e-3, 0.01, 0.015, 1e-5
    n_c = (k - m * v**2 * (b - a) / (a * d_c**2)) * d_c / (b - a)
    code, out, err = run_cli(["design", "--config", str(machine_file(tmp_path, RATE_STATE)),
                              "--json"], capsys)
    assert code == 0, err
    p = json.loads(out)
    assert p["critical_loads_N"] == pytest.approx([n_c], rel=1e-8)
    assert p["unstable_loads_N"][0][0] == pytest.approx(n_c, rel=1e-8)
    assert p["unstable_loads_N"][0][1] == pytest.approx(100.0 * 10.0)  # the scan's end
    # the critical stiffness is Rice and Ruina's k_c at the file's N = 10 N
    k_c = 10.0 * (b - a) / d_c * (1.0 + m * v**2 / (10.0 * a * d_c))
    assert p["stability"]["critical_stiffness_N_per_m"] == pytest.approx(k_c, rel=1e-8)
    assert p["stability"]["verdict"] == "unstable"
    assert "Eqs. 28-30" in p["foundation"]


def test_lugre_bistable_like_simulate(tmp_path: Path,
                                      capsys: pytest.CaptureFixture[str]) -> None:
    # Canudas de Wit et al. (1995): the slider stuck to the drive at V = 0.1 m/s stick-slips.
    # Steady sliding there is linearly stable. Its linearisation, derived: with the slip speed
    # w = V - x', z' = w - sigma0 |w| z / g(w), z0 = g(V)/sigma0 and g'(V) = 0 (exp(-(V/v_s)^2)
    # = exp(-1e4) is 0 in floating point), dz' = -(sigma0 V / g(V)) dz with no dw term, so the
    # system is block triangular: the bristle's eigenvalue -sigma0 V / (mu_c N) = -1e4 1/s and
    # m s^2 + sigma2 s + k = 0, s = -0.2 +- 1.4j 1/s. A nudge dies out: bistable. The period is
    # simulate's from the same start (--initial-kick -1).
    path = str(machine_file(tmp_path, LUGRE))
    code, out, err = run_cli(["design", "--config", path, "--json"], capsys)
    assert code == 0, err
    p = json.loads(out)
    assert p["verdict"] == "stick-slip" and p["bistable"] is True
    assert p["nudged"]["verdict"] == "steady-sliding"
    code, out, err = run_cli(["simulate", "--config", path, "--initial-kick", "-1", "--json"],
                             capsys)
    assert code == 0, err
    direct = json.loads(out)
    assert p["startup"]["period_s"] == pytest.approx(direct["period_s"], rel=1e-9)
    values = sorted((complex(re, im) for re, im in p["stability"]["eigenvalues"]),
                    key=lambda z: (z.real, z.imag))
    expected = [complex(-1e4, 0.0), complex(-0.2, -1.4), complex(-0.2, 1.4)]
    assert values == pytest.approx(expected, rel=1e-9)
    code, out, err = run_cli(["design", "--config", path], capsys)
    assert code == 0 and "bistable" in out and "verdict     stick-slip" in out, err


def test_design_flags_refused_with_memory(tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    path = str(machine_file(tmp_path, LUGRE))
    for extra in (["--speed", "1 m/s"], ["--t-max", "100"]):
        code, out, err = run_cli(["design", "--config", path, *extra], capsys)
        lines = [line for line in err.splitlines() if line.startswith("stickslip: error:")]
        assert code != 0 and out == "" and len(lines) == 1 and "Traceback" not in err
        assert extra[0] in lines[0] and "friction law with memory" in lines[0]


def test_boundary_config_with_memory_is_rice_ruina(tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    # the 1-DOF rate-and-state slider: k = k_c(V) gives V_c^2 = (N a d_c/m)(k d_c/(N (b - a)) - 1)
    # (Rice and Ruina 1983), unstable above it; along the load N_c = 6 N (first test above)
    k, m, a, b, d_c, n = 8000.0, 1.0, 0.01, 0.015, 1e-5, 10.0
    v_c = (n * a * d_c / m * (k * d_c / (n * (b - a)) - 1.0)) ** 0.5
    path = str(machine_file(tmp_path, RATE_STATE))
    code, out, err = run_cli(["boundary", "--config", path, "--json"], capsys)
    assert code == 0, err
    (crossing,) = json.loads(out)["crossings"]
    assert crossing["value_SI"] == pytest.approx(v_c, rel=1e-9)
    assert (crossing["below"], crossing["above"]) == ("stable", "unstable")
    code, out, err = run_cli(["boundary", "--config", path, "--param", "load", "--range",
                              "1 N:100 N", "--json"], capsys)
    assert code == 0, err
    (crossing,) = json.loads(out)["crossings"]
    assert crossing["value_SI"] == pytest.approx(6.0, rel=1e-9)
    code, out, err = run_cli(["boundary", "--config", path, "--rtol", "1e-3"], capsys)
    assert code == 2 and "--rtol" in err and len(err.strip().splitlines()) == 1
