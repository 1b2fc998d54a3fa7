"""Linear stability of steady sliding with friction with memory (analysis.memory.stability, issue 33).

References, all closed forms derived independently of the code under test:

* Rice and Ruina (1983): the 1-DOF rate-and-state slider is unstable for
  ``k < k_c = N (b - a)/d_c (1 + m V^2/(N a d_c))``; solved for ``V`` it gives one critical
  speed ``V_c^2 = (N a d_c/m)(k d_c/(N (b - a)) - 1)``, unstable above it.
* LuGre (Canudas de Wit et al. 1995), linearised here by hand: with ``g`` the Stribeck curve
  ``N (mu_c + (mu_s - mu_c) exp(-(v/v_s)^2))``, ``alpha = sigma0 V/g(V)`` and
  ``beta = V g'(V)/g(V)``, the bristle obeys ``dz' = beta dv - alpha dz`` and the slider's
  characteristic polynomial is ``m s^3 + (m alpha + sigma1 beta + sigma2) s^2 +
  (k + sigma0 beta + sigma2 alpha) s + k alpha``; Routh-Hurwitz (``a2 a1 > a3 a0``, all
  positive) decides stability.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from scipy.optimize import brentq

from stickslip.analysis.memory.stability import linear_spectrum, memory_stability, spectrum_sign
from stickslip.io.machine_file import read_machine_file
from stickslip.sweep.memory.maps import memory_stability_map
from tests.cli_helpers import run_cli
from tests.memory_machines import LUGRE, RATE_STATE


def _system(tmp_path: Path, text: str):  # type: ignore[no-untyped-def]
    path = tmp_path / "machine.toml"
    path.write_text(text, encoding="utf-8")
    return path, read_machine_file(path).memory_system()



def _k_c(load: float, speed: float) -> float:
    """Rice and Ruina's k_c of RATE_STATE's slider (m = 1 kg, a = 0.01, b = 0.015, d_c = 10 um)."""
    return load * 0.005 / 1e-5 * (1.0 + speed**2 / (load * 0.01 * 1e-5))


def test_rate_state_critical_stiffness_and_speed(tmp_path: Path) -> None:
    _, system = _system(tmp_path, RATE_STATE)
    result = memory_stability(system)
    assert result.verdict == "unstable"  # k = 8000 < k_c(1 mm/s) = 1e4 N/m
    assert result.critical_stiffness == pytest.approx(1e4, rel=1e-10)
    v_c = math.sqrt(10.0 * 0.01 * 1e-5 / 1.0 * (8000.0 * 1e-5 / (10.0 * 0.005) - 1.0))
    assert result.critical_speeds == [pytest.approx(v_c, rel=1e-9)]
    assert result.unstable_speeds[0][0] == pytest.approx(v_c, rel=1e-9)
    assert result.to_dict()["rice_ruina"]["critical_speed_m_per_s"] == pytest.approx(v_c, rel=1e-14)


DAMPED = """
[system]
m = "2 kg"
k = "3000 N/m"
c = "5 N*s/m"
load = "20 N"
speed = "3 mm/s"
[friction]
law = "rate-state"
a = 0.012
b = 0.02
d_c = "20 um"
mu_ref = 0.5
v_ref = "1 um/s"
evolution = "slip"
"""


def test_damped_slider_hopf_stiffness_and_the_undamped_closed_form(tmp_path: Path) -> None:
    # Derivation: about steady sliding dF = (N a/V) dv + N dpsi, dpsi' = -(b/d_c) dv - (V/d_c) dpsi
    # and dv = -dx'; with L = V/d_c and C = c + N a/V the characteristic polynomial is
    # m s^3 + (m L + C) s^2 + (k + L C - N b/d_c) s + k L, whose Hopf boundary (a2 a1 = a3 a0) is
    # k = (m L + C)(N (b - a)/d_c - c V/d_c)/C; c = 0 gives Rice and Ruina's k_c (38000 N/m
    # here, while the damped boundary is 32838.2 N/m: the summary must not pass one for the other)
    _, system = _system(tmp_path, DAMPED)
    m, c, load, v, a, b, d_c = 2.0, 5.0, 20.0, 3e-3, 0.012, 0.02, 2e-5
    big_c = c + load * a / v
    k_hopf = (m * v / d_c + big_c) * (load * (b - a) / d_c - c * v / d_c) / big_c
    result = memory_stability(system)
    assert result.critical_stiffness == pytest.approx(k_hopf, rel=1e-9)
    assert result.to_dict()["rice_ruina"]["critical_stiffness_N_per_m"] == pytest.approx(
        load * (b - a) / d_c * (1.0 + m * v**2 / (load * a * d_c)), rel=1e-12)
    # at the boundary s = i w solves the cubic: w^2 = a0/a2 = k L/(m L + C)
    w_hopf = math.sqrt(k_hopf * (v / d_c) / (m * v / d_c + big_c))
    assert result.hopf_frequency == pytest.approx(w_hopf / (2.0 * math.pi), rel=1e-6)
    assert result.to_dict()["hopf_frequency_Hz"] == result.hopf_frequency
    text = result.summary()
    assert f"Hopf boundary at {w_hopf / (2.0 * math.pi):.6g} Hz" in text
    assert "critical k  32838.2352" in text
    assert "closed form of an undamped slider" in text
    assert "critical V  0.031953" in text  # the damped boundary along the speed
    # no critical speed in the scan about 1e-5 m/s (1e-7 to 1e-3 m/s): "none", with no unit
    slow = memory_stability(system, speed=1e-5).summary()
    assert "critical V  none (scan" in slow
    assert "none m/s" not in slow
    _, undamped_system = _system(tmp_path, DAMPED.replace('c = "5 N*s/m"', 'c = "0 N*s/m"'))
    assert "undamped slider" not in memory_stability(undamped_system).summary()


def test_rate_state_map_matches_rice_ruina_everywhere(tmp_path: Path) -> None:
    _, system = _system(tmp_path, RATE_STATE)
    speeds, loads = np.geomspace(1e-5, 1e-1, 30), np.geomspace(1.0, 100.0, 20)
    data = memory_stability_map(system, speeds, loads)
    checked = 0
    for i, v in enumerate(speeds):
        for j, w in enumerate(loads):
            k_c = _k_c(float(w), float(v))
            if abs(8000.0 - k_c) <= 1e-6 * k_c:
                continue  # on the boundary: either side within round-off
            expected = "unstable" if 8000.0 < k_c else "stable"
            assert data.verdict[i, j] == expected, (v, w, k_c, data.growth_rate[i, j])
            checked += 1
    assert checked == speeds.size * loads.size
    assert 0.0 < data.fractions()["unstable"] < 1.0


def _lugre_coefficients(speed: float) -> tuple[float, float, float, float]:
    """``a3, a2, a1, a0`` of the hand-linearised LuGre slider (module notes)."""
    m, k, load, s0, s1, s2, mu_c, mu_s, vs = 1.0, 2.0, 1.0, 1e5, math.sqrt(1e5), 0.4, 1.0, 1.5, 1e-3
    g = load * (mu_c + (mu_s - mu_c) * math.exp(-(speed / vs) ** 2))
    dg = load * (mu_s - mu_c) * math.exp(-(speed / vs) ** 2) * (-2.0 * speed / vs**2)
    alpha, beta = s0 * speed / g, speed * dg / g
    return m, m * alpha + s1 * beta + s2, k + s0 * beta + s2 * alpha, k * alpha


def _lugre_hurwitz(speed: float) -> float:
    """``a2 a1 - a3 a0``: with every coefficient positive, > 0 is stable (Routh-Hurwitz)."""
    a3, a2, a1, a0 = _lugre_coefficients(speed)
    return a2 * a1 - a3 * a0


def _lugre_stable(speed: float) -> bool:
    return min(_lugre_coefficients(speed)) > 0.0 and _lugre_hurwitz(speed) > 0.0


def test_lugre_critical_speed_is_routh_hurwitz(tmp_path: Path) -> None:
    _, system = _system(tmp_path, LUGRE)
    result = memory_stability(system)
    assert result.verdict == "stable"  # at 0.1 m/s the Stribeck slope has died out
    # scanned from V/100 = 1 mm/s: the last crossing, where the Stribeck slope dies out
    (v_c,) = result.critical_speeds
    exact = brentq(_lugre_hurwitz, 2e-3, 1e-2, xtol=1e-16, rtol=1e-14)
    assert v_c == pytest.approx(exact, rel=1e-8)
    for speed in np.geomspace(1e-4, 1e-1, 37).tolist():  # below, in and above the Stribeck range
        expected = -1 if _lugre_stable(speed) else 1
        assert spectrum_sign(*linear_spectrum(system, speed)) == expected, speed


def test_lugre_critical_stiffness_side_is_read_not_assumed(tmp_path: Path,
                                                           capsys: pytest.CaptureFixture[str]) -> None:
    # Routh-Hurwitz of the module notes' cubic in k: a2 a1 > a3 a0 reads k (sigma1 beta + sigma2)
    # + A B > 0 with A = m alpha + sigma1 beta + sigma2, B = sigma0 beta + sigma2 alpha, so
    # k_c = -A B / (sigma1 beta + sigma2), and where sigma1 beta + sigma2 < 0 a STIFFER slider
    # is unstable (an audit: the summary said "unstable below it" while k = 5000 N/m, above
    # k_c, was unstable and 1000 N/m stable). The audit's slider: m = 1 kg, N = 10 N, V = 1 cm/s
    m, load, v, s0, s1, s2, mu_c, mu_s, vs = 1.0, 10.0, 0.01, 1e5, 2000.0, 40.0, 0.5, 0.7, 5e-3
    g = load * (mu_c + (mu_s - mu_c) * math.exp(-(v / vs) ** 2))
    dg = load * (mu_s - mu_c) * math.exp(-(v / vs) ** 2) * (-2.0 * v / vs**2)
    alpha, beta = s0 * v / g, v * dg / g
    assert s1 * beta + s2 < 0.0
    big_a, big_b = m * alpha + s1 * beta + s2, s0 * beta + s2 * alpha
    k_c = -big_a * big_b / (s1 * beta + s2)
    text = LUGRE.replace('k = "2 N/m"', 'k = "{k} N/m"').replace('load = "1 N"', 'load = "10 N"')
    text = text.replace('speed = "0.1 m/s"', 'speed = "1 cm/s"').replace(
        "316.22776601683796", "2000").replace('"0.4 N*s/m"', '"40 N*s/m"').replace(
        "mu_c = 1.0", "mu_c = 0.5").replace("mu_s = 1.5", "mu_s = 0.7").replace('"1 mm/s"',
                                                                           '"5 mm/s"')
    for k, verdict in ((5000.0, "unstable"), (1000.0, "stable")):
        path, system = _system(tmp_path, text.format(k=k))
        result = memory_stability(system)
        assert result.verdict == verdict
        assert result.critical_stiffness == pytest.approx(k_c, rel=1e-10)
        assert result.unstable_side == "above"
        code, out, err = run_cli(["stability", "--config", str(path)], capsys)
        assert code == 0, err
        assert "steady sliding is unstable above it" in out
    _, system = _system(tmp_path, RATE_STATE)
    assert memory_stability(system).unstable_side == "below"  # Rice and Ruina


def test_neutral_is_not_rounded() -> None:
    values = np.array([-1.0 + 2j, 1e-15 - 2j])
    assert spectrum_sign(values, np.array([1e-12, 1e-12])) == 0
    assert spectrum_sign(values, np.array([1e-16, 1e-16])) == 1
    assert spectrum_sign(np.array([-1.0 + 0j]), np.array([1e-12])) == -1


def test_load_enters_the_map(tmp_path: Path) -> None:
    """Each column of the map is the system at that load (k_c grows with N)."""
    _, system = _system(tmp_path, RATE_STATE)
    data = memory_stability_map(system, [1e-4], [5.0, 20.0])
    for j, w in enumerate((5.0, 20.0)):
        alone = memory_stability(replace(system, load=w), 1e-4)
        assert data.growth_rate[0, j] == alone.growth_rate
    assert list(data.verdict[0]) == ["stable", "unstable"]  # k_c(1e-4) = 2500 (1.02), 1e4 (1.005)


def test_cli_stability_and_map(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path, _ = _system(tmp_path, RATE_STATE)
    code, out, err = run_cli(["stability", "--config", str(path), "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    assert payload["stable"] is False and payload["verdict"] == "unstable"
    assert payload["critical_stiffness_N_per_m"] == pytest.approx(1e4, rel=1e-10)
    assert len(payload["eigenvalues"]) == 3  # x, x' and the state variable
    out_nc = tmp_path / "map.nc"
    code, out, err = run_cli(["map", "--config", str(path), "--speed", "log:1e-5:1e-1:12",
                           "--load", "log:1:100:9", "--out", str(out_nc), "--csv",
                           str(tmp_path / "map.csv"), "--plot", str(tmp_path / "map.png"), "--json"],
                          capsys)
    assert code == 0, err
    with xr.open_dataset(out_nc) as ds:
        assert ds["growth_rate"].shape == (12, 9)
        unstable = ds["stability"].values == 1
    speeds, loads = np.geomspace(1e-5, 1e-1, 12), np.geomspace(1.0, 100.0, 9)
    expected = 8000.0 < np.array([[_k_c(w, v) for w in loads] for v in speeds])
    assert np.array_equal(unstable, expected)
    assert (tmp_path / "map.png").stat().st_size > 0
    assert len((tmp_path / "map.csv").read_text().splitlines()) == 1 + 12 * 9


@pytest.mark.parametrize(("extra", "needle"), [
    (["--t-max", "5"], "runs no simulation"),
    (["--backend", "dask"], "eigenvalue map"),
])
def test_cli_map_refusals(tmp_path: Path, capsys: pytest.CaptureFixture[str], extra: list[str],
                          needle: str) -> None:
    path, _ = _system(tmp_path, RATE_STATE)
    code, out, err = run_cli(["map", "--config", str(path), "--speed", "log:1e-5:1e-1:3", "--load",
                           "1:2:2", "--out", str(tmp_path / "m.nc"), *extra], capsys)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and needle in err
    assert not (tmp_path / "m.nc").exists()


def test_cli_stability_plot_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path, _ = _system(tmp_path, LUGRE)
    code, out, err = run_cli(["stability", "--config", str(path), "--plot", str(tmp_path / "p.png")],
                          capsys)
    assert code == 2 and out == "" and "--map draws" in err and len(err.strip().splitlines()) == 1


def test_cli_stability_mu_max_refused_with_memory(tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    """--mu-max bounds the contact's search over mu; a memory law's linearisation has none (it
    was silently ignored)."""
    path, _ = _system(tmp_path, LUGRE)
    code, out, err = run_cli(["stability", "--config", str(path), "--mu-max", "3"], capsys)
    assert code == 2 and out == "" and "--mu-max 3" in err and "leave it out" in err
    assert len(err.strip().splitlines()) == 1


def test_cli_stability_refuses_a_contact_with_memory(tmp_path: Path,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    """A [contact] table beside a law with memory is refused, not ignored (no engine has both)."""
    path, _ = _system(tmp_path, RATE_STATE + '\n[contact]\nnormal_stiffness = "1e5 N/m"\n')
    code, out, err = run_cli(["stability", "--config", str(path)], capsys)
    assert code == 2 and out == "" and "[contact]" in err and len(err.strip().splitlines()) == 1


def test_velocity_strengthening_has_no_rice_ruina_stiffness(tmp_path: Path) -> None:
    # b < a: k_c = N (b - a)/d_c (...) < 0, so no stiffness destabilises steady sliding (Rice
    # and Ruina 1983); the answer is "none", not a negative stiffness
    _, system = _system(tmp_path, RATE_STATE.replace("b = 0.015", "b = 0.005"))
    result = memory_stability(system)
    assert result.verdict == "stable"
    assert result.to_dict()["rice_ruina"]["critical_stiffness_N_per_m"] is None
    assert result.hopf_frequency is None
    assert "k_c = none (b <= a" in result.summary()
