"""The machine file with a [structure] (issue 18 point 1) and its refusals (issue 22 point 2).

References: the slideway's generator ``examples/slideway/make_matrices.py`` (the matrices the
.mtx files must hold), unit arithmetic (1 kN/m = 1000 N/m), and the one-line contract of the
command line (exit 2, one ``stickslip: error:`` line naming file, key, value and why).
"""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import numpy as np
import pytest

from stickslip.io.machine_file import machine_from_file, read_machine_file
from tests.cli_helpers import run_cli

SLIDEWAY = Path(__file__).resolve().parents[1] / "examples" / "slideway"
OPERATING = {"mu_s": 0.15, "mu_k": 0.1, "load": 2600.0, "speed": 5e-4}


def _generator() -> object:
    spec = importlib.util.spec_from_file_location("make_matrices", SLIDEWAY / "make_matrices.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_shipped_slideway_files_hold_the_generators_matrices() -> None:
    mass, damping, stiffness = _generator().matrices()  # type: ignore[attr-defined]
    machine, reduction = machine_from_file(read_machine_file(SLIDEWAY / "machine.toml"), OPERATING)
    assert reduction is None and machine.contact_dof == 2 and machine.n_dof == 6
    np.testing.assert_allclose(machine.mass, mass, rtol=1e-15)
    np.testing.assert_allclose(machine.stiffness, stiffness, rtol=1e-15)
    np.testing.assert_allclose(machine.damping, damping, rtol=1e-15)


def _write(tmp_path: Path, structure: str, top: str = "", extra: str = "") -> Path:
    path = tmp_path / "machine.toml"
    path.write_text('mu_s = 0.5\nmu_k = 0.3\nload = "100 N"\nspeed = "1 cm/s"\n' + top
                    + "[structure]\n" + structure + extra)
    return path


M3 = [[2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 5.0]]
K3 = [[3e4, -1e4, 0.0], [-1e4, 2e4, -1e4], [0.0, -1e4, 3e4]]


def test_mtx_npy_csv_and_inline_give_the_same_machine(tmp_path: Path) -> None:
    import scipy.io
    import scipy.sparse

    scipy.io.mmwrite(str(tmp_path / "K.mtx"), scipy.sparse.coo_matrix(np.array(K3)), symmetry="symmetric")
    np.save(tmp_path / "M.npy", np.array(M3))
    (tmp_path / "K.csv").write_text("\n".join(";".join(repr(x) for x in row) for row in K3))
    machines = []
    for mass, stiffness in (("M.npy", "K.mtx"), (str(M3), "K.csv"), (str(M3), str(K3))):
        m_spec = f'"{mass}"' if mass.endswith(".npy") else mass
        k_spec = f'"{stiffness}"' if stiffness.endswith(("mtx", "csv")) else stiffness
        path = _write(tmp_path, f"mass = {m_spec}\nstiffness = {k_spec}\nrayleigh = [0.5, 1e-4]\n"
                                "contact_dof = 1\n")
        machines.append(machine_from_file(read_machine_file(path), {**OPERATING})[0])
    for other in machines[1:]:
        for attr in ("mass", "damping", "stiffness"):
            np.testing.assert_array_equal(getattr(other, attr), getattr(machines[0], attr))
    # reference: C = alpha M + beta K
    np.testing.assert_allclose(machines[0].damping, 0.5 * np.array(M3) + 1e-4 * np.array(K3), rtol=1e-15)


def test_units_of_the_matrices(tmp_path: Path) -> None:
    # reference: 1 kN/m = 1000 N/m, 1 g = 1e-3 kg
    k_kn = [[x / 1000.0 for x in row] for row in K3]
    m_g = [[x * 1000.0 for x in row] for row in M3]
    path = _write(tmp_path, f'mass = {m_g}\nmass_unit = "g"\nstiffness = {k_kn}\n'
                            'stiffness_unit = "kN/m"\ncontact_dof = 0\n')
    machine = machine_from_file(read_machine_file(path), OPERATING)[0]
    np.testing.assert_allclose(machine.stiffness, K3, rtol=1e-15)
    np.testing.assert_allclose(machine.mass, M3, rtol=1e-15)


def test_modal_damping_gives_each_mode_its_ratio(tmp_path: Path) -> None:
    # reference: Phi' C Phi = diag(2 zeta_i w_i) for mass-normalised modes (definition)
    from scipy.linalg import eigh

    path = _write(tmp_path, f"mass = {M3}\nstiffness = {K3}\nmodal_damping = [0.01, 0.02, 0.05]\n"
                            "contact_dof = 2\n")
    machine = machine_from_file(read_machine_file(path), OPERATING)[0]
    w2, phi = eigh(np.array(K3), np.array(M3))
    modal = phi.T @ machine.damping @ phi
    np.testing.assert_allclose(np.diag(modal), 2 * np.array([0.01, 0.02, 0.05]) * np.sqrt(w2), rtol=1e-10)
    assert np.abs(modal - np.diag(np.diag(modal))).max() < 1e-10 * np.abs(modal).max()


def _chain81(tmp_path: Path, ratios: str) -> Path:
    """An 81-DOF grounded chain (reduced before a run: above 60 DOF) with a modal_damping list."""
    n = 81
    np.save(tmp_path / "M.npy", np.diag(np.full(n, 2.0)))
    stiffness = 2e4 * np.eye(n) - 1e4 * (np.eye(n, k=1) + np.eye(n, k=-1))
    np.save(tmp_path / "K.npy", stiffness)
    return _write(tmp_path, f'mass = "M.npy"\nstiffness = "K.npy"\ncutoff = "30 Hz"\n'
                            f"modal_damping = {ratios}\ncontact_dof = 40\n")


def test_a_reduced_model_takes_the_first_ratios_of_a_modal_damping_list(tmp_path: Path) -> None:
    # an independent audit: an 81-DOF file needed as many ratios as the reduced model had DOF
    # (a count that moves with the cut-off); the ratios are per mode of the user's model, and
    # the reduced model's modes take the first ones (reference: Phi' C Phi = diag(2 zeta_i w_i)
    # over the reduced model's mass-normalised modes, the definition)
    from scipy.linalg import eigh

    ratios = [0.01 + 0.001 * i for i in range(81)]
    machine, reduction = machine_from_file(read_machine_file(_chain81(tmp_path, str(ratios))),
                                           OPERATING)
    n = machine.n_dof
    assert reduction is not None and 1 < n < 81
    w2, phi = eigh(machine.stiffness, machine.mass)
    modal = phi.T @ machine.damping @ phi
    np.testing.assert_allclose(np.diag(modal), 2 * np.array(ratios[:n]) * np.sqrt(w2), rtol=1e-8)
    short = _chain81(tmp_path, str(ratios[: n - 1]))
    with pytest.raises(ValueError, match=rf"has {n - 1} ratios; the 81-DOF model is reduced to {n} DOF"):
        machine_from_file(read_machine_file(short), OPERATING)
    with pytest.raises(ValueError, match="has 82 ratios for the 81 modes of the 81-DOF model"):
        machine_from_file(read_machine_file(_chain81(tmp_path, str([0.02] * 82))), OPERATING)


BAD_FILES = [
    ("m = 2\n", f"mass = {M3}\nstiffness = {K3}\ncontact_dof = 0\n", "", "m and \\[structure\\] both"),
    ("", f"mass = {M3}\nstiffness = {K3}\ncontact_dof = 3\n", "", "contact_dof = 3 is beyond the 3 DOF"),
    ("", f"mass = {M3}\nstiffness = {K3}\n", "", "contact_dof is missing"),
    ("", f'mass = "nowhere.mtx"\nstiffness = {K3}\ncontact_dof = 0\n', "", "nowhere.mtx.* does not exist"),
    ("", f'mass = "M.txt"\nstiffness = {K3}\ncontact_dof = 0\n', "", "suffix '.txt'"),
    ("", f'mass = "bad.mtx"\nstiffness = {K3}\ncontact_dof = 0\n', "", "no %%MatrixMarket header"),
    ("", f"mass = {M3}\nstiffness = [[1.0, -1.0, 0.0], [-1.0, 1.0, 0.0], [0.0, 0.0, 1.0]]\n"
         "contact_dof = 0\n", "", "free rigid-body mode .* moves DOFs 0, 1"),
    ("", f"mass = {M3}\nstiffness = {K3}\ncontact_dof = 0\nrayleigh = [1, 0]\nmodal_damping = 0.1\n", "",
     "rayleigh and modal_damping both give the damping"),
    ("", f"mass = {M3}\nstiffness = [[1.0, 2.0], [2.0, 5.0]]\ncontact_dof = 0\n", "",
     "is 2x2, but mass is 3x3"),
    ("", f'mass = {M3}\nstiffness = {K3}\ncontact_dof = 0\nmass_unit = "2 percent"\n', "",
     "mass_unit"),
    ("", f'mass = {M3}\nstiffness = {K3}\ncontact_dof = 0\nstiffness_unit = "percent"\n', "",
     "dimensionless unit"),
    ("", f"mass = {M3}\nstiffness = {K3}\ncontact_dof = 0\n",
     '[friction]\nlaw = "stribeck"\nmu_0 = 0.6\nstribeck_velocity = "1 mm/s"\n', "mu_0 = 0.6 must lie in"),
    ("", f"mass = {M3}\nstiffness = {K3}\ncontact_dof = 0\n",
     '[friction]\nlaw = "coulomb"\nslope = 0.1\n', "slope = 0.1 does not belong to the coulomb law"),
    ("", f"mass = {M3}\nstiffness = {K3}\ncontact_dof = 0\n",
     '[friction]\nlaw = "linear"\nstribeck_velocity = 0.1\n', "does not belong to the linear law"),
    ("", f"mass = {M3}\nstiffness = {K3}\ncontact_dof = 0\n",
     '[friction]\nlaw = "stribeck"\nstribeck_velocity = "3 percent"\n', "stribeck_velocity .* dimensionless"),
    ("", f"mass = {M3}\nstiffness = {K3}\ncontact_dof = 0\n", '[absorber]\nmass = "1 kg"\nattach_dof = 7\n',
     "attach_dof = 7 is beyond"),
]


@pytest.mark.parametrize(("top", "structure", "extra", "message"), BAD_FILES)
def test_bad_machine_files_are_refused_with_one_line(top: str, structure: str, extra: str, message: str,
                                                     tmp_path: Path,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "bad.mtx").write_text("1 1 1\n1 1 1.0\n")
    (tmp_path / "M.txt").write_text("1 0 0\n")
    path = _write(tmp_path, structure, top, extra)
    before = sorted(p.name for p in tmp_path.iterdir())
    code, out, err = run_cli(["design", "--config", str(path), "--json", "--no-stick-slip-optimum"], capsys)
    lines = err.strip().splitlines()
    assert code == 2 and out == "" and len(lines) == 1, err
    assert lines[0].startswith("stickslip: error:") and "Traceback" not in err
    assert str(path) in lines[0] or "machine.toml" in lines[0], lines[0]
    import re

    assert re.search(message, lines[0]), lines[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_dimensionless_unit_on_a_flat_mass_is_refused(tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "flat.toml"
    path.write_text('m = "2 percent"\nk = 1000\nmu_s = 0.5\nmu_k = 0.3\nload = 10\nspeed = 0.1\n')
    code, _, err = run_cli(["design", "--config", str(path), "--json"], capsys)
    assert code == 2 and "m =" in err and "dimensionless unit" in err and len(err.strip().splitlines()) == 1


def test_flags_for_the_paper_structure_with_a_structure_file_are_refused(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _write(tmp_path, f"mass = {M3}\nstiffness = {K3}\ncontact_dof = 0\n")
    code, _, err = run_cli(["design", "--config", str(path), "--m", "2 kg", "--json"], capsys)
    assert code == 2 and "--m cannot be given with --config" in err


def test_design_config_with_a_structure_reports_in_si(tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    # reference: the machine's own analysis (analysis/machine_absorber.design_machine) and the
    # scaling V_c = dmu W / (lambda_c sqrt(m_ref k_ref)), W_c = lambda_c V sqrt(m_ref k_ref) / dmu
    path = _write(tmp_path, f"mass = {M3}\nstiffness = {K3}\nrayleigh = [0.5, 1e-4]\ncontact_dof = 1\n")
    code, out, err = run_cli(["design", "--config", str(path), "--json", "--no-stick-slip-optimum"], capsys)
    assert code == 0, err
    report = json.loads(out)
    root = (1.0 * 2e4) ** 0.5
    lam_c = report["critical"]["lambda_c"]
    assert report["critical_speed"] == pytest.approx(0.2 * 100.0 / (lam_c * root), rel=1e-12)
    assert report["critical_load"] == pytest.approx(lam_c * 0.01 * root / 0.2, rel=1e-12)
    assert report["machine"]["contact_dof"] == 1
    assert report["lambda"] == pytest.approx(0.2 * 100 / (0.01 * root))
    assert report["verdict"] in ("stick-slip", "steady-sliding", "undetermined")


def test_a_reader_of_the_paper_slider_refuses_a_structure_with_one_line() -> None:
    # every command takes a [structure] now (tests/test_cli_machine.py); what needs the slider's
    # m, k, c itself says so in one line instead of a KeyError
    from stickslip.cli.console import BadInput
    from stickslip.cli.machine_config import config_system

    with pytest.raises(BadInput, match=r"has a \[structure\]") as info:
        config_system(SLIDEWAY / "machine.toml")
    assert len(str(info.value).splitlines()) == 1


def test_simulate_names_both_sizes_of_a_reduced_model(tmp_path: Path,
                                                       capsys: pytest.CaptureFixture[str]) -> None:
    # the machine line gave the reduced size and numbering alone ("57 DOF, contact on DOF 0"
    # for an 81-DOF file with contact_dof 80: an independent audit)
    config = _chain81(tmp_path, "0.02")
    code, out, err = run_cli(["simulate", "--config", str(config), "--t-max", "0.05 s"], capsys)
    assert code == 0, err
    line = next(x for x in out.splitlines() if x.startswith("machine "))
    assert "81 DOF reduced to " in line and ", contact on DOF 40 (reduced DOF 0)" in line
    code, out, err = run_cli(["simulate", "--config", str(config), "--t-max", "0.05 s", "--json"],
                             capsys)
    assert json.loads(out)["reduced_from"] == {"n_dof": 81, "contact_dof": 40}
