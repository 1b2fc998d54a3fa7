"""Issue 32 item 2: hostile structure files get one line each, or are used right.

The contract is that of ``tests/test_bad_input.py``: a bad value exits with code 2 and exactly
one ``stickslip: error:`` line naming the file, the key and why (never "aborted (Ctrl-C)",
never a traceback or a warning), nothing written. References: the Matrix Market format
(its size line ``rows cols entries``; math.nist.gov/MatrixMarket/formats.html), the ``.npy``
format (``numpy.lib.format``: the magic ``\\x93NUMPY``), Sylvester's law of inertia (a
symmetric matrix has as many negative eigenvalues as its LDL' factorisation has negative
pivots), and unit arithmetic (1 rpm = 1/60 rev/s; 1 rad/s = 1/(2 pi) Hz).
"""

from __future__ import annotations

import math
import os
import pickle
import re
import time
import tracemalloc
from pathlib import Path

import numpy as np
import pytest
import scipy.io
import scipy.sparse

from stickslip.io.machine_file import build_structure, read_machine_file
from stickslip.io.structure_files import read_matrix
from stickslip.model.structure import check_large_matrices, check_symmetric
from tests.cli_helpers import run_cli

HEAD = 'mu_s = 0.5\nmu_k = 0.3\nload = "100 N"\nspeed = "1 cm/s"\n'
M3 = [[2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 5.0]]
K3 = [[3e4, -1e4, 0.0], [-1e4, 2e4, -1e4], [0.0, -1e4, 3e4]]
DESIGN = ["design", "--json", "--no-stick-slip-optimum", "--config"]


def _machine(folder: Path, structure: str, top: str = "") -> Path:
    path = folder / "machine.toml"
    path.write_text(HEAD + top + "[structure]\n" + structure)
    return path


def _refused(folder: Path, structure: str, capsys: pytest.CaptureFixture[str], top: str = "") -> str:
    path = _machine(folder, structure, top)
    before = sorted(p.name for p in folder.iterdir())
    code, out, err = run_cli([*DESIGN, str(path)], capsys)
    lines = err.strip().splitlines()
    assert code == 2 and out == "" and len(lines) == 1, (code, err)
    assert lines[0].startswith("stickslip: error:") and "machine.toml" in lines[0], err
    assert "Traceback" not in err and "warning" not in err.lower() and "Ctrl-C" not in err
    assert sorted(p.name for p in folder.iterdir()) == before
    return lines[0]


def _chain(n: int, spring: float = 1e4, grounded: bool = True) -> scipy.sparse.csr_matrix:
    """Springs between neighbours; both ends to the ground (or neither: a floating chain)."""
    main = np.full(n, 2.0 * spring)
    if not grounded:
        main[0] = main[-1] = spring
    off = -spring * np.ones(n - 1)
    return scipy.sparse.diags([main, off, off], [0, 1, -1], format="csr")


# --- Matrix Market headers that lie ------------------------------------------------------

def test_mtx_header_claiming_1e12_entries_is_refused_before_allocating(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "big.mtx").write_text("%%MatrixMarket matrix coordinate real general\n"
                                      "3 3 1000000000000\n1 1 1\n2 2 1\n3 3 1\n")
    tracemalloc.start()
    with pytest.raises(ValueError, match=r"declares 1000000000000 entries .* hold at most"):
        read_matrix("big.mtx", quantity="mass", base_dir=tmp_path, source="mass")
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert peak < 10 * 1024**2  # today: an attempt at 3.64 TiB
    line = _refused(tmp_path, f'mass = "big.mtx"\nstiffness = {K3}\ncontact_dof = 0\n', capsys)
    assert "big.mtx" in line and "header does not match the data" in line


def test_mtx_header_claiming_9e5_dof_but_holding_3_entries_is_refused(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "dof.mtx").write_text("%%MatrixMarket matrix coordinate real general\n"
                                      "900000 900000 3\n1 1 1\n2 2 1\n3 3 1\n")
    # a positive definite matrix has a positive diagonal: DOF 3 (0-based) has no mass
    line = _refused(tmp_path, 'mass = "dof.mtx"\nstiffness = "dof.mtx"\ncontact_dof = 0\n', capsys)
    assert re.search(r"mass = 'dof.mtx' must be positive definite .* mass at DOF 3 .* is 0", line)


SYMMETRIC = "%%MatrixMarket matrix coordinate real symmetric\n"


def test_a_symmetric_mtx_with_both_triangles_is_refused_not_doubled(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # the format: a symmetric coordinate file lists one triangle and the reader mirrors it;
    # before, both triangles were read and each off-diagonal term doubled (an independent
    # audit: a 4-DOF machine's frequencies 6.83..45.26 Hz instead of 7.17..39.32 Hz)
    (tmp_path / "K.mtx").write_text(SYMMETRIC + "3 3 7\n1 1 3e4\n2 1 -1e4\n1 2 -1e4\n2 2 2e4\n"
                                    "3 2 -1e4\n2 3 -1e4\n3 3 3e4\n")
    line = _refused(tmp_path, f'mass = {M3}\nstiffness = "K.mtx"\ncontact_dof = 0\n', capsys)
    assert "K.mtx" in line and "gives the term (2, 1) twice" in line
    # the lower triangle alone (the format's), or the upper alone, is K3
    for rows in ("2 1 -1e4\n3 2 -1e4", "1 2 -1e4\n2 3 -1e4"):
        (tmp_path / "K.mtx").write_text(SYMMETRIC + f"3 3 5\n1 1 3e4\n2 2 2e4\n3 3 3e4\n{rows}\n")
        read = read_matrix("K.mtx", quantity="stiffness", base_dir=tmp_path, source="k")
        assert np.array_equal(read.toarray(), np.array(K3))


def test_a_pattern_mtx_is_refused_not_read_as_ones(tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    # a pattern file has positions without values (the format); before, read as ones: K = I N/m
    (tmp_path / "K.mtx").write_text("%%MatrixMarket matrix coordinate pattern symmetric\n"
                                    "3 3 3\n1 1\n2 2\n3 3\n")
    line = _refused(tmp_path, f'mass = {M3}\nstiffness = "K.mtx"\ncontact_dof = 0\n', capsys)
    assert "K.mtx" in line and "pattern matrix (positions without values)" in line


# --- .npy files that are not ------------------------------------------------------------

def _npz(path: Path, **arrays: object) -> None:
    with path.open("wb") as handle:
        np.savez(handle, **arrays)  # type: ignore[arg-type]


@pytest.mark.parametrize(("kind", "message"), [
    ("npz", r"\.npz archive"), ("pickled npz", r"\.npz archive"), ("pickle", "Python pickle"),
    ("empty", r"is empty \(0 bytes\)"), ("text", "not a NumPy .npy file"),
])
def test_npy_that_is_not_a_npy_array_is_refused(kind: str, message: str, tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "M.npy"
    if kind == "npz":
        _npz(path, a=np.array(M3))
    elif kind == "pickled npz":
        _npz(path, a=np.array([{"a": 1}], dtype=object))
    elif kind == "pickle":
        path.write_bytes(pickle.dumps(np.array(M3)))
    elif kind == "empty":
        path.write_bytes(b"")  # reported as "aborted (Ctrl-C)", exit 130, before
    else:
        path.write_text("2 0 0\n0 1 0\n0 0 5\n")
    line = _refused(tmp_path, f'mass = "M.npy"\nstiffness = {K3}\ncontact_dof = 0\n', capsys)
    assert "mass = 'M.npy'" in line and re.search(message, line), line


def test_a_fifo_named_as_a_matrix_is_refused_without_blocking(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    os.mkfifo(tmp_path / "M.csv")  # nobody writes to it: a reader would wait for ever
    line = _refused(tmp_path, f'mass = "M.csv"\nstiffness = {K3}\ncontact_dof = 0\n', capsys)
    assert "is not a regular file" in line


# --- matrices the engine cannot take --------------------------------------------------------

def test_singular_stiffness_of_a_floating_chain_is_refused_at_any_size(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    float3 = _chain(3, grounded=False).toarray().tolist()
    line = _refused(tmp_path, f"mass = {M3}\nstiffness = {float3}\ncontact_dof = 0\n", capsys)
    assert "not grounded" in line and "free rigid-body mode" in line
    scipy.io.mmwrite(str(tmp_path / "K.mtx"), _chain(1000, grounded=False))
    scipy.io.mmwrite(str(tmp_path / "M.mtx"), scipy.sparse.identity(1000))
    line = _refused(tmp_path, 'mass = "M.mtx"\nstiffness = "K.mtx"\ncontact_dof = 0\n', capsys)
    assert "stiffness = 'K.mtx' is singular" in line and "not grounded" in line


def test_an_all_zero_stiffness_is_said_so(tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    # an audit: it was "a free rigid-body mode (stiffness eigenvalue 0, at most 1e-12 of the
    # largest 2.23e-308)", the floor of the floats shown as a stiffness
    zeros = np.zeros((3, 3)).tolist()
    line = _refused(tmp_path, f"mass = {M3}\nstiffness = {zeros}\ncontact_dof = 0\n", capsys)
    assert "stiffness matrix is all zeros" in line and "e-308" not in line


@pytest.mark.parametrize("n", [3, 100])
def test_zero_mass_at_one_dof_is_refused_naming_the_dof(n: int, tmp_path: Path,
                                                        capsys: pytest.CaptureFixture[str]) -> None:
    mass = np.eye(n)
    mass[1, 1] = 0.0
    np.save(tmp_path / "M.npy", mass)
    np.save(tmp_path / "K.npy", _chain(n).toarray())
    line = _refused(tmp_path, 'mass = "M.npy"\nstiffness = "K.npy"\ncontact_dof = 0\n', capsys)
    assert "positive definite" in line and "mass at DOF 1" in line


def test_indefinite_100_dof_stiffness_is_named_with_its_reason(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before: "error: math domain error"
    stiffness = _chain(100).toarray()
    stiffness[5, 5] = -5e4  # Gershgorin: row 5 has -5e4 + 2e4 < 0 -> one negative eigenvalue
    assert int(np.sum(np.linalg.eigvalsh(stiffness) < 0)) == 1
    np.save(tmp_path / "K.npy", stiffness)
    np.save(tmp_path / "M.npy", np.eye(100))
    line = _refused(tmp_path, 'mass = "M.npy"\nstiffness = "K.npy"\ncontact_dof = 0\n', capsys)
    assert re.search(r"stiffness = 'K.npy' is not positive definite: it has 1 negative "
                     r"eigenvalue.*DOF 5", line), line


def test_sparse_inertia_test_counts_the_negative_eigenvalues() -> None:
    # reference: numpy.linalg.eigvalsh of the same matrices (Sylvester's law of inertia)
    rng = np.random.default_rng(3)
    for shift in (-3e4, -1e4, -1e3):
        k = _chain(80).toarray() + np.diag(rng.uniform(0.0, 1e3, 80))
        k[::7, ::7] += np.diag(np.full(k[::7, ::7].shape[0], shift))
        negative = int(np.sum(np.linalg.eigvalsh(k) < 0))
        if negative == 0:
            check_large_matrices(np.eye(80), None, scipy.sparse.csr_matrix(k))
            continue
        with pytest.raises(ValueError, match=rf"has {negative} negative eigenvalue"):
            check_large_matrices(np.eye(80), None, scipy.sparse.csr_matrix(k))


def test_1e5_dof_sparse_stiffness_30_percent_asymmetric_is_refused(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    n = 100_000
    k = _chain(n).tocoo()
    data = k.data.copy()
    data[k.row < k.col] *= 1.3  # the upper off-diagonal springs 30 % stiffer than the lower
    scipy.io.mmwrite(str(tmp_path / "K.mtx"), scipy.sparse.coo_matrix((data, (k.row, k.col)), shape=k.shape))
    scipy.io.mmwrite(str(tmp_path / "M.mtx"), scipy.sparse.identity(n, format="coo"))
    tic = time.perf_counter()
    line = _refused(tmp_path, 'mass = "M.mtx"\nstiffness = "K.mtx"\ncontact_dof = 0\n', capsys)
    assert time.perf_counter() - tic < 60.0
    # |A - A^T| = 0.3 * 1e4 beside the largest entry 2e4
    assert "stiffness = 'K.mtx' is not symmetric: |A - A^T| reaches 3e+03" in line, line


@pytest.mark.parametrize("n", [3, 100])
def test_asymmetric_damping_is_refused_at_any_size_and_round_off_accepted(
        n: int, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before: refused at 3 DOF, silently symmetrised at 100 DOF (above the reduction's 60)
    stiffness = _chain(n).toarray()
    np.save(tmp_path / "M.npy", np.eye(n))
    np.save(tmp_path / "K.npy", stiffness)
    damping = 1e-3 * stiffness
    damping[0, 1] *= 3.0
    np.save(tmp_path / "C.npy", damping)
    table = 'mass = "M.npy"\nstiffness = "K.npy"\ndamping = "C.npy"\ncontact_dof = 0\ncutoff = "100 Hz"\n'
    line = _refused(tmp_path, table, capsys)
    assert "damping = 'C.npy' is not symmetric" in line
    damping = 1e-3 * stiffness
    damping[0, 1] *= 1.0 + 1e-12  # what a file written with 12 digits keeps: accepted
    np.save(tmp_path / "C.npy", damping)
    _m, c, k, _contact, _name, _reduction = build_structure(
        {"mass": "M.npy", "stiffness": "K.npy", "damping": "C.npy", "contact_dof": 0,
         "cutoff": "100 Hz"}, base_dir=tmp_path, source="[structure]")
    # stiffness-proportional damping stays proportional through the (linear) reduction
    np.testing.assert_allclose(c, 1e-3 * k, rtol=0.0, atol=1e-9 * np.abs(c).max())


def test_symmetry_rule_is_the_same_for_dense_and_sparse() -> None:
    a = _chain(10).toarray()
    for factor, ok in ((1.0 + 1e-10, True), (1.0 + 1e-8, False)):
        b = a.copy()
        b[2, 3] *= factor
        for form in (b, scipy.sparse.csr_matrix(b)):
            if ok:
                check_symmetric("K", form)
            else:
                with pytest.raises(ValueError, match="K is not symmetric"):
                    check_symmetric("K", form)


def test_booleans_as_a_mass_are_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    for mass in ("[[true, false, false], [false, true, false], [false, false, true]]",
                 "[[2.0, 0.0, 0.0], [0.0, true, 0.0], [0.0, 0.0, 5.0]]"):
        line = _refused(tmp_path, f"mass = {mass}\nstiffness = {K3}\ncontact_dof = 0\n", capsys)
        assert "mass (inline) has true/false entries" in line


def test_top_level_quantities_and_a_system_table_together_are_refused(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before: the top-level mu_s = 0.5 was ignored for the [system] table's 0.6
    path = _machine(tmp_path, f"mass = {M3}\nstiffness = {K3}\ncontact_dof = 0\n",
                    top="[system]\nmu_s = 0.6\n")
    with pytest.raises(ValueError, match=r"mu_s.* at the top level and a \[system\] table"):
        read_machine_file(path)
    line = _refused(tmp_path, f"mass = {M3}\nstiffness = {K3}\ncontact_dof = 0\n", capsys,
                    top="[system]\nmu_s = 0.6\n")
    assert "[system]" in line


# --- cut-off and modes ------------------------------------------------------------------

def test_cutoff_of_1e300_hz_is_refused_without_overflow(tmp_path: Path,
                                                       capsys: pytest.CaptureFixture[str]) -> None:
    np.save(tmp_path / "M.npy", np.eye(100))
    np.save(tmp_path / "K.npy", _chain(100).toarray())
    line = _refused(tmp_path, 'mass = "M.npy"\nstiffness = "K.npy"\ncontact_dof = 0\n'
                              'cutoff = "1e300 Hz"\n', capsys)
    assert "cutoff = '1e300 Hz' must be a positive frequency up to 1e+09 Hz" in line


def test_a_modes_table_beyond_the_direct_limit_is_refused_with_the_limit(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before: no answer in 300 s (400 modes run as 400 DOF, unreduced)
    f = np.linspace(10.0, 4000.0, 400).tolist()
    line = _refused(tmp_path, f"modes = {{frequencies = {f}, damping_ratios = {[0.02] * 400}, "
                              f"shapes = {[0.1] * 400}}}\n", capsys)
    assert "modes has 400 modes; at most 60" in line


@pytest.mark.parametrize("attach", [1, 5])
def test_an_absorber_on_a_modal_coordinate_is_refused(attach: int, tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    # a modes table's coordinates after the contact are modal amplitudes (m sqrt(kg)): an
    # absorber there is no machine (an audit: attach_dof = 1 "tuned" c_a = 1e-149 N s/m, and
    # attach_dof = 5 was a 50-line IndexError traceback)
    line = _refused(tmp_path, "modes = {frequencies = [41.1, 71.2], damping_ratios = [0.02, 0.05], "
                              "shapes = [-0.866, 0.5]}\n[absorber]\nmass = \"0.1 kg\"\n"
                              f"attach_dof = {attach}\n", capsys)
    assert f"[absorber] attach_dof = {attach}: a structure given by modes has one point" in line


@pytest.mark.parametrize(("frequencies", "shapes"), [("[1e300, 40.0]", "[0.5, 0.2]"),
                                                     ("[12.0, 40.0]", "[1e300, 0.2]")])
def test_modes_of_1e300_are_refused_without_overflow_warnings(
        frequencies: str, shapes: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before: "stickslip: warning: overflow encountered in square" and a second line
    line = _refused(tmp_path, f"modes = {{frequencies = {frequencies}, damping_ratios = [0.02, 0.03], "
                              f"shapes = {shapes}}}\n", capsys)
    assert "beyond the range of floating-point numbers" in line


def test_a_mass_of_1e40_beside_1_kg_is_refused_without_overflow_warnings(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # before (at 1e300): "warning: overflow encountered in dot" and a step-budget error
    line = _refused(tmp_path, f"mass = [[1e40, 0, 0], [0, 1, 0], [0, 0, 1]]\nstiffness = {K3}\n"
                              "contact_dof = 0\n", capsys)
    assert "mass matrix is numerically singular" in line


@pytest.mark.parametrize("entry", ["1e300", "1e308", "-1e60"])
def test_a_matrix_entry_beyond_1e50_si_is_refused_by_name(
        tmp_path: Path, entry: str, capsys: pytest.CaptureFixture[str]) -> None:
    # before: at 1e308 "overflow encountered in add" and "Eigenvalues did not converge"; the
    # supported magnitude of an SI input is 1e50 (stickslip.model.physical.MAX_SI)
    line = _refused(tmp_path, f"mass = [[{entry}, 0, 0], [0, 1, 0], [0, 0, 1]]\nstiffness = {K3}\n"
                              "contact_dof = 0\n", capsys)
    assert "mass (inline) has an entry of magnitude" in line and "beyond the 1e+50" in line


@pytest.mark.parametrize("units", [("75.398 rad/s", "251.327 rad/s"), ("720 rpm", "2400 rpm"),
                                   (12.0, 40.0)])
def test_mode_frequencies_in_rad_per_s_and_rpm_are_converted_to_hz(units: tuple[object, object]) -> None:
    # reference: 720 rpm = 720/60 = 12 Hz, 2400 rpm = 40 Hz; 75.398 rad/s = 75.398/(2 pi) Hz
    # = 11.99996 Hz, 251.327 rad/s = 39.99998 Hz (before: read as 75.398 Hz and 720 Hz)
    table = {"modes": {"frequencies": [units[0], units[1]], "damping_ratios": [0.02, 0.03],
                       "shapes": [0.5, 0.2]}}
    m, _c, k, *_ = build_structure(table, base_dir=None, source="[structure]")
    from scipy.linalg import eigh

    f = np.sqrt(eigh(k, m, eigvals_only=True)) / (2 * math.pi)
    expected = [75.398 / (2 * math.pi), 251.327 / (2 * math.pi)] if "rad" in str(units[0]) else [12.0, 40.0]
    np.testing.assert_allclose(f, expected, rtol=1e-12)


# --- uploads (the web app's limits): refused from the header, before the entries ---------

def test_an_npy_header_cut_inside_its_dictionary_is_one_line() -> None:
    # an audit: a header "{'descr': '<f8', 'fortran_order': False, 'shape': (6," escaped as
    # tokenize.TokenError ("EOF in multi-line statement")
    header = b"{'descr': '<f8', 'fortran_order': False, 'shape': (6,".ljust(63) + b"\n"
    content = b"\x93NUMPY\x01\x00" + len(header).to_bytes(2, "little") + header + bytes(288)
    with pytest.raises(ValueError, match=r"K.npy' cannot be read: its .npy header is not valid"):
        read_matrix("K.npy", quantity="stiffness", source="stiffness", content=content)


@pytest.mark.parametrize("kind", ["csv", "mtx", "npy"])
def test_a_model_above_max_dof_is_refused_before_its_entries_are_read(kind: str,
                                                                       tmp_path: Path) -> None:
    # an audit: a 4990x4990 CSV of zeros (47.5 MB, under the upload limit) took 18 s and
    # 1.36 GB of the app's memory before its 1,000-DOF limit refused it; here a 1,200-DOF
    # model against max_dof = 1,000, and the same file read in full without the limit
    n = 1200
    path = tmp_path / f"K.{kind}"
    if kind == "csv":
        path.write_text("\n".join(",".join(["0"] * n) for _ in range(n)) + "\n")
    elif kind == "mtx":
        scipy.io.mmwrite(str(path), scipy.sparse.identity(n, format="coo"))
    else:
        np.save(path, np.eye(n))
    content = path.read_bytes()
    tracemalloc.start()
    with pytest.raises(ValueError, match=rf"it is {n}x{n}, a {n}-DOF model, beyond the 1000 DOF"):
        read_matrix(path.name, quantity="stiffness", source="stiffness", content=content,
                    max_dof=1000)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert peak < 2 * len(content) + 1_000_000  # the text or bytes themselves, no parsed rows
    assert read_matrix(path.name, quantity="stiffness", source="stiffness",
                       content=content).shape == (n, n)
