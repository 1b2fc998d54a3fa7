"""Every command that takes a machine takes the user's machine (issue 18 point 3, issue 22.2).

``simulate``, ``basin``, ``cycles``, ``map`` and ``tune`` with ``--config machine.toml``: a flat
file of the paper's slider or a ``[structure]`` of any linear structure with the contact on
any DOF. SI answers are checked against the dimensionless run times the scales written out
here (``omega_n = sqrt(k_ref / m_ref)`` with ``m_ref = M[c, c]``, ``k_ref = K[c, c]`` read from
the matrices; ``tau = omega_n t``, Eq. 17; displacements in ``V / omega_n``, Eqs. 15-16;
``lambda = (mu_s - mu_k) W / (V sqrt(m_ref k_ref))``, after Eq. 27), and the dimensionless run
is the one the dimensionless commands make from those groups.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import scipy.io

from tests.cli_helpers import run_cli

SLIDEWAY = Path(__file__).resolve().parents[1] / "examples" / "slideway"

# A 3-DOF chain, the contact in the middle (DOF 1): kg, N/m, N s/m.
M3 = [[2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 3.0]]
K3 = [[300.0, -100.0, 0.0], [-100.0, 150.0, -50.0], [0.0, -50.0, 250.0]]
C3 = [[0.6, -0.2, 0.0], [-0.2, 0.5, -0.1], [0.0, -0.1, 0.8]]


def _rows(matrix: list[list[float]]) -> str:
    return "[" + ", ".join("[" + ", ".join(repr(x) for x in row) + "]" for row in matrix) + "]"


def write_structure_file(path: Path, *, perm: list[int] | None = None, speed: str = "0.05",
                         load: str = "20.0", friction: str = "") -> Path:
    """A machine TOML with the 3-DOF chain inline (DOFs permuted by ``perm``)."""
    order = perm or [0, 1, 2]
    ix = np.ix_(order, order)
    m, k, c = (np.array(a)[ix].tolist() for a in (M3, K3, C3))
    contact = order.index(1)
    path.write_text(
        f"mu_s = 0.5\nmu_k = 0.3\nload = {load}\nspeed = {speed}\n{friction}\n"
        f"[structure]\nname = \"chain3\"\nmass = {_rows(m)}\nstiffness = {_rows(k)}\n"
        f"damping = {_rows(c)}\ncontact_dof = {contact}\n", encoding="utf-8")
    return path


def write_flat_file(path: Path, *, friction: str = "", speed: str = "1.0", load: str = "30.0") -> Path:
    """The paper's slider on a rigid base: m = 2 kg, k = 8 N/m, c = 0.4 N s/m."""
    path.write_text(f"m = 2.0\nk = 8.0\nc = 0.4\nmu_s = 0.5\nmu_k = 0.3\nload = {load}\n"
                    f"speed = {speed}\n{friction}", encoding="utf-8")
    return path


def cli_json(args: list[str], capsys: pytest.CaptureFixture[str]) -> dict:
    code, out, err = run_cli([*args, "--json"], capsys)
    assert code == 0, err
    return json.loads(out)


def test_simulate_config_slideway_si_answers_are_the_dimensionless_run_times_the_scales(
        capsys: pytest.CaptureFixture[str]) -> None:
    from stickslip.analysis.simulation import simulate
    from stickslip.model.parameters import Slider
    from stickslip.model.structure import Structure

    p = cli_json(["simulate", "--config", str(SLIDEWAY / "machine.toml")], capsys)
    for key in ("verdict", "period_s", "amplitude_m", "stick_ratio", "certificate", "dimensionless"):
        assert key in p
    for key in ("lambda", "zeta", "gamma", "period", "amplitude"):
        assert key in p["dimensionless"]
    # the scales, from the shipped matrices and the file's operating point (SI)
    mass = scipy.io.mmread(SLIDEWAY / "M.mtx").toarray()
    stiff = scipy.io.mmread(SLIDEWAY / "K.mtx").toarray()
    damp = scipy.io.mmread(SLIDEWAY / "C.mtx").toarray()
    c = 2  # contact_dof of machine.toml
    m_ref, k_ref = mass[c, c], stiff[c, c]
    omega = math.sqrt(k_ref / m_ref)
    speed, load, mu_s, mu_k = 0.5e-3, 2600.0, 0.15, 0.10
    lam = (mu_s - mu_k) * load / (speed * math.sqrt(m_ref * k_ref))
    assert p["dimensionless"]["lambda"] == pytest.approx(lam, rel=1e-12)
    assert p["dimensionless"]["gamma"] == pytest.approx(mu_k / (mu_s - mu_k), rel=1e-12)
    assert p["dimensionless"]["zeta"] == pytest.approx(damp[c, c] / (2 * math.sqrt(m_ref * k_ref)), rel=1e-12)
    assert p["verdict"] == "stick-slip"
    assert p["period_s"] == pytest.approx(p["period"] / omega, rel=1e-12)
    assert p["amplitude_m"] == pytest.approx(p["amplitude"] * speed / omega, rel=1e-12)
    # the dimensionless run made from the matrices here gives the same cycle
    root = math.sqrt(m_ref * k_ref)
    ref = simulate(Structure(mass / m_ref, damp / root, stiff / k_ref, contact_dof=c),
                   Slider(lam, gamma=mu_k / (mu_s - mu_k)))
    assert ref.verdict.value == p["verdict"]
    assert p["period"] == pytest.approx(ref.period, rel=1e-9)
    assert p["amplitude"] == pytest.approx(ref.amplitude, rel=1e-9)


def test_simulate_config_flat_file_equals_the_dimensionless_command(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = write_flat_file(tmp_path / "m.toml")
    p = cli_json(["simulate", "--config", str(path)], capsys)
    # groups of the slider (Eqs. 15-18): sqrt(m k) = 4, zeta = c / 8
    lam, gamma, zeta = 0.5 - 0.3, 0.3 / (0.5 - 0.3), 0.4 / (2.0 * math.sqrt(2.0 * 8.0))
    lam = lam * 30.0 / (1.0 * math.sqrt(2.0 * 8.0))
    assert (p["lambda"], p["gamma"], p["zeta"]) == pytest.approx((lam, gamma, zeta), rel=1e-15)
    q = cli_json(["simulate", "--lam", repr(p["lambda"]), "--zeta", repr(p["zeta"]),
                  "--gamma", repr(p["gamma"])], capsys)
    for key in ("verdict", "period", "amplitude", "stick_ratio", "certificate", "n_events"):
        assert p[key] == q[key], key
    assert p["period_s"] == pytest.approx(q["period"] / math.sqrt(8.0 / 2.0), rel=1e-14)
    assert p["amplitude_m"] == pytest.approx(q["amplitude"] * 1.0 / math.sqrt(8.0 / 2.0), rel=1e-14)


def test_simulate_config_permuted_structure_gives_the_same_answers(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    a = cli_json(["simulate", "--config", str(write_structure_file(tmp_path / "a.toml"))], capsys)
    b = cli_json(["simulate", "--config",
                  str(write_structure_file(tmp_path / "b.toml", perm=[1, 2, 0]))], capsys)
    assert a["contact_dof"] == 1 and b["contact_dof"] == 0
    assert a["verdict"] == b["verdict"]
    for key in ("period_s", "amplitude_m", "stick_ratio"):
        if a[key] is None:
            assert b[key] is None
        else:
            assert b[key] == pytest.approx(a[key], rel=1e-12), key


MIX_COMMANDS = [["simulate"], ["basin", "--samples", "10"], ["cycles"], ["tune"],
                ["map", "--speed", "0.1,0.2", "--load", "10,20", "--out", "OUT.nc"]]
MIX_FLAGS = [["--lam", "3"], ["--gamma", "2"], ["--zeta", "0.1"], ["--dva", "optimal"],
             ["--friction", "linear:0.1"]]
#: tune has no --lam, --dva or --friction at all (the dimensionless tune takes --zeta, --gamma)
MIX_CASES = [(c, f) for c in MIX_COMMANDS for f in MIX_FLAGS
             if not (c[0] == "tune" and f[0] in ("--lam", "--dva", "--friction"))]


@pytest.mark.parametrize("command,flag", MIX_CASES)
def test_dimensionless_flags_next_to_config_are_refused(
        command: list[str], flag: list[str], tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = write_structure_file(tmp_path / "m.toml")
    args = [a.replace("OUT.nc", str(tmp_path / "out.nc")) for a in command]
    code, out, err = run_cli([*args, "--config", str(path), *flag], capsys)
    assert code == 2
    assert out == ""
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert flag[0] in err and "--config" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.toml"]


def test_map_config_speed_load_grid(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import xarray as xr

    from stickslip.analysis.simulation import simulate
    from stickslip.model.parameters import Slider
    from stickslip.model.structure import rigid_base

    path = write_flat_file(tmp_path / "m.toml")
    out = tmp_path / "vw.nc"
    p = cli_json(["map", "--config", str(path), "--speed", "log:0.2:5:3", "--load", "5,40",
                  "--out", str(out), "--plot", str(tmp_path / "vw.png")], capsys)
    assert p["n_speed"] == 3 and p["n_load"] == 2 and Path(p["plot"]).exists()
    ds = xr.open_dataset(out)
    assert ds["speed"].attrs["units"] == "m/s" and ds["load"].attrs["units"] == "N"
    np.testing.assert_allclose(ds["speed"].values, [0.2, 1.0, 5.0], rtol=1e-12)
    for i, v in enumerate(ds["speed"].values):
        for j, w in enumerate(ds["load"].values):
            lam = (0.5 - 0.3) * w / (v * math.sqrt(2.0 * 8.0))  # after Eq. 27
            assert float(ds["lambda"][i, j]) == pytest.approx(lam, rel=1e-12)
            ref = simulate(rigid_base(0.05), Slider(lam, gamma=1.5), record=False)
            assert verdict_words(ds)[i, j] == ref.verdict.value
            if ref.verdict.value == "stick-slip":
                assert float(ds["period"][i, j]) == pytest.approx(ref.period / 2.0, rel=1e-9)
    ds.close()


def verdict_words(ds: object) -> np.ndarray:
    """The verdicts of a map file as words, read through its CF flags (the file's contract)."""
    var = ds["verdict"]  # type: ignore[index]
    flags = dict(zip(np.atleast_1d(var.attrs["flag_values"]).tolist(),
                     str(var.attrs["flag_meanings"]).split(), strict=True))
    return np.vectorize(flags.__getitem__)(var.values)


def test_map_config_stribeck_cells_have_their_own_law(tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    """A velocity-dependent law changes shape with V (v_s / V): each cell = simulate --config there."""
    import xarray as xr

    law = "[friction]\nlaw = \"stribeck\"\nmu_0 = 0.5\nstribeck_velocity = 0.5\nexponent = 1\n"
    path = write_flat_file(tmp_path / "m.toml", friction=law)
    out = tmp_path / "vw.nc"
    cli_json(["map", "--config", str(path), "--speed", "0.3,2.0", "--load", "30", "--out", str(out)],
             capsys)
    ds = xr.open_dataset(out)
    for i, v in enumerate((0.3, 2.0)):
        one = write_flat_file(tmp_path / f"p{i}.toml", friction=law, speed=repr(v))
        q = cli_json(["simulate", "--config", str(one)], capsys)
        assert verdict_words(ds)[i, 0] == q["verdict"]
        assert float(ds["lambda"][i, 0]) == q["lambda"]
    ds.close()


@pytest.mark.parametrize("args,word", [
    (["--speed", "0:1:3", "--load", "10"], "--speed"),
    (["--speed", "0.1", "--load", "-5,10"], "--load"),
    (["--speed", "0.1"], "--load"),
    (["--speed", "1:2:1000", "--load", "1:2:1000"], "operating points"),
    # a bad-input audit: lambda = 6e7 at 1e-9 m/s ran (all undetermined) where simulate refuses
    (["--speed", "1e-9", "--load", "100"], "narrow the speed or load range"),
])
def test_map_config_bad_axes_one_line(args: list[str], word: str, tmp_path: Path,
                                      capsys: pytest.CaptureFixture[str]) -> None:
    path = write_flat_file(tmp_path / "m.toml")
    code, out, err = run_cli(["map", "--config", str(path), *args, "--out", str(tmp_path / "o.nc")],
                             capsys)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and word in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.toml"]


@pytest.mark.slow  # compiles the basin kernel for a 3-DOF structure (about a minute, once)
def test_basin_config_structure_permutation_identity(tmp_path: Path,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    """Sampling in SI (x, v = contact DOF) gives the same labels whatever the DOF order."""
    a = cli_json(["basin", "--config", str(write_structure_file(tmp_path / "a.toml")),
                  "--samples", "40", "--box", "x=-0.01:0.01,v=-0.05:0.05"], capsys)
    b = cli_json(["basin", "--config", str(write_structure_file(tmp_path / "b.toml", perm=[2, 1, 0])),
                  "--samples", "40", "--box", "x=-0.01:0.01,v=-0.05:0.05"], capsys)
    assert a["n"] == b["n"] == 40
    assert sum(a["fractions"].values()) == pytest.approx(1.0)
    # the engine order is contact first; the other two DOFs swap, but x and v are the contact's
    # and the other columns stay at steady sliding: the same states, the same verdicts
    assert a["fractions"] == b["fractions"]


def test_cycles_config_si(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = write_flat_file(tmp_path / "m.toml")
    p = cli_json(["cycles", "--config", str(path), "--seeds", "4"], capsys)
    assert p["cycles"], "lambda = 1.5 > Eq. (36) at zeta = 0.05: a stick-slip cycle exists"
    for c in p["cycles"]:
        assert c["period_s"] == pytest.approx(c["period"] / 2.0, rel=1e-14)  # omega_n = 2 rad/s
        assert c["amplitude_m"] == pytest.approx(c["amplitude"] * 1.0 / 2.0, rel=1e-14)


def test_tune_config_needs_an_absorber(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = write_structure_file(tmp_path / "m.toml")
    code, out, err = run_cli(["tune", "--config", str(path)], capsys)
    assert code == 2 and out == "" and "[absorber]" in err and len(err.strip().splitlines()) == 1


@pytest.mark.slow  # 22 s: out of the default run (kept under ten minutes)
def test_tune_config_slideway_hinf(capsys: pytest.CaptureFixture[str]) -> None:
    p = cli_json(["tune", "--config", str(SLIDEWAY / "machine.toml")], capsys)
    assert [a["objective"] for a in p["absorbers"]] == ["hinf"]
    a = p["absorbers"][0]
    assert a["mass_kg"] == pytest.approx(10.0) and a["attach"] == 2
    # V_c and W_c are the same lambda_c in the bare machine's contact scaling (after Eq. 27)
    mass = scipy.io.mmread(SLIDEWAY / "M.mtx").toarray()
    stiff = scipy.io.mmread(SLIDEWAY / "K.mtx").toarray()
    root = math.sqrt(mass[2, 2] * stiff[2, 2])
    crit = p["critical"]
    assert crit["critical_speed_m_per_s"] == pytest.approx(
        0.05 * 2600.0 / (crit["lambda_c"] * root), rel=1e-9)
    assert crit["critical_load_N"] == pytest.approx(crit["lambda_c"] * 0.5e-3 * root / 0.05, rel=1e-9)


def test_basin_config_default_box_and_si_states_in_the_dataset(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # an independent audit: basin --config without --box sampled x in [-2, 2] m and v in
    # [-2, 1.5] m/s (for the slideway at 0.5 mm/s: xi up to 7e6), and its basin.nc held the
    # starts only dimensionless. Now the default box is the dimensionless one about steady
    # sliding, and the dataset carries the starts in SI: fed back as --initial-states (SI, the
    # inverse conversion of Eqs. 15-16) they must give the same verdicts
    import xarray as xr

    out = tmp_path / "basin"
    p = cli_json(["basin", "--config", str(SLIDEWAY / "machine.toml"), "--samples", "12",
                  "--seed", "3", "--out", str(out)], capsys)
    with xr.open_dataset(out / "basin.nc") as ds:
        assert np.all(np.abs(ds["xi"].values) <= 2.0) and np.all(ds["v"].values >= -2.0)
        assert np.all(ds["v"].values <= 1.5) and ds["x_si"].attrs["units"] == "m"
        assert np.allclose(ds["v_si"].values, ds["v"].values * ds.attrs["speed_m_per_s"], rtol=1e-15)
        names = [f"{n}_si" for n in ("x", "x_a", "x_a2", "x_a3", "x_a4", "x_a5",
                                     "v", "v_a", "v_a2", "v_a3", "v_a4", "v_a5")]
        rows = np.stack([ds[n].values for n in names], axis=1)
        verdicts = ds["verdict"].values.copy()
    starts = tmp_path / "starts.csv"
    header = ",".join(n[:-3] for n in names)
    starts.write_text(header + "\n" + "\n".join(",".join(repr(float(x)) for x in r) for r in rows))
    again = tmp_path / "again"
    cli_json(["basin", "--config", str(SLIDEWAY / "machine.toml"), "--initial-states", str(starts),
              "--out", str(again)], capsys)
    with xr.open_dataset(again / "basin.nc") as ds:
        assert np.array_equal(ds["verdict"].values, verdicts)
    assert p["n"] == 12
