"""Friction-law model objects: band tables, validation messages, CSV input, and the batch kernel.

References: the law definitions of DESIGN.md section 8 and the dimensionless forms of
``stickslip.model.friction`` (``F = gamma lambda - 2 delta u`` floored at zero for linear;
``F = lambda (gamma + f)`` for a table).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from stickslip import Slider, rigid_base, simulate
from stickslip.kernel.batch import coulomb_tables, run_cells, startup_vector
from stickslip.kernel.system import mode_code, mode_kind_band
from stickslip.model.friction import CoulombFriction, LinearFriction, StribeckFriction, TableFriction
from stickslip.model.friction_input import read_friction_table


def test_mode_codes_keep_the_coulomb_values() -> None:
    assert (mode_code(0, 0), mode_code(1, 0)) == (0, 1)
    assert [mode_code(k, b) for b in (1, 2) for k in (0, 1)] == [3, 4, 5, 6]
    assert [mode_kind_band(c) for c in range(7)] == [(0, 0), (1, 0), (2, 0), (0, 1), (1, 1), (0, 2), (1, 2)]


def test_coulomb_and_zero_slope_linear_tables() -> None:
    edges, a, s = CoulombFriction().bands(1.5, 2.0)
    assert edges.tolist() == [0.0, math.inf] and a.tolist() == [3.0] and s.tolist() == [0.0]
    e2, a2, s2 = LinearFriction(0.0).bands(1.5, 2.0)
    assert e2.tolist() == edges.tolist() and a2.tolist() == a.tolist() and s2.tolist() == [0.0]


def test_linear_weakening_is_floored_at_u_star() -> None:
    edges, a, s = LinearFriction(0.25).bands(1.0, 2.0)
    # u* = gamma lam / (2 delta) = 4
    assert edges.tolist() == [0.0, 4.0, math.inf]
    assert a.tolist() == [2.0, 0.0] and s.tolist() == [-0.5, 0.0]
    assert LinearFriction(0.25).value(5.0, 1.0, 2.0) == 0.0
    edges, a, s = LinearFriction(-0.1).bands(1.0, 2.0)
    assert edges.tolist() == [0.0, math.inf] and s.tolist() == [pytest.approx(0.2)]


def test_table_bands_and_constant_extension() -> None:
    law = TableFriction((0.5, 1.0, 2.0), (0.8, 0.0, 0.5))
    edges, a, s = law.bands(2.0, 1.0)
    assert edges.tolist() == [0.0, 0.5, 1.0, 2.0, math.inf]
    u = np.array([0.0, 0.25, 0.75, 1.5, 3.0])
    np.testing.assert_allclose(a[[0, 0, 1, 2, 3]] + s[[0, 0, 1, 2, 3]] * u, law.value(u, 2.0, 1.0))
    np.testing.assert_allclose(law.value(u, 2.0, 1.0), 2.0 * (1.0 + np.array([0.8, 0.8, 0.4, 0.25, 0.5])))


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"u": (0.0, 0.0), "f": (0.0, 0.1)}, "increase strictly"),
        ({"u": (-0.1, 0.5), "f": (0.0, 0.1)}, "must not be negative"),
        ({"u": (0.0,), "f": (1.2,)}, "exceeds 1"),
        ({"u": (0.0, 1.0), "f": (0.1,)}, "equally many"),
        ({"u": (0.0, float("nan")), "f": (0.1, 0.2)}, "must be finite"),
    ],
)
def test_table_refuses_bad_points(kwargs: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        TableFriction(**kwargs)


@pytest.mark.parametrize(
    ("v", "mu", "message"),
    [
        ((0.1, 0.05), (0.5, 0.45), r"increase strictly, got 0.1 m/s then 0.05 m/s"),
        ((-0.1, 0.5), (0.5, 0.45), r"speed v = -0.1 m/s must not be negative"),
        ((0.0, 0.1), (0.7, 0.5), r"mu\(0\+\) = 0.7 exceeds mu_s = 0.6"),
    ],
)
def test_a_measured_table_is_refused_in_its_own_units(v: tuple, mu: tuple, message: str) -> None:
    # the user's curve is in m/s and mu: a message in the engine's u = v / V (0.1 m/s at
    # V = 2 cm/s read "5.0") names numbers that are not in their file (an independent audit)
    with pytest.raises(ValueError, match=message):
        TableFriction.from_physical(v, mu, 0.6, 0.4, 0.02)


def test_table_refuses_negative_friction() -> None:
    with pytest.raises(ValueError, match="mu < 0"):
        TableFriction((0.0, 1.0), (0.0, -2.5)).bands(1.0, 2.0)


def test_from_physical_and_csv(tmp_path: Path) -> None:
    # mu_s = 0.6, mu_k = 0.4, V = 2 m/s: u = v / 2, f = (mu - 0.4) / 0.2
    law = TableFriction.from_physical([0.0, 1.0, 4.0], [0.6, 0.45, 0.5], 0.6, 0.4, 2.0)
    assert law.u == (0.0, 0.5, 2.0)
    np.testing.assert_allclose(law.f, (1.0, 0.25, 0.5))
    path = tmp_path / "curve.csv"
    path.write_text("# measured\nv,mu\n0.0,0.6\n1.0,0.45\n4.0,0.5\n")
    read = read_friction_table(path, mu_s=0.6, mu_k=0.4, speed=2.0)
    assert read.u == law.u
    np.testing.assert_allclose(read.f, law.f)
    path_f = tmp_path / "dimensionless.csv"
    path_f.write_text("v,f\n0,1\n0.5,0.25\n")
    assert read_friction_table(path_f).f == (1.0, 0.25)


@pytest.mark.parametrize(
    ("text", "kwargs", "message"),
    [
        ("x,y\n0,1\n", {}, "needs columns v and mu"),
        ("v,mu\n", {}, "at least one data row"),
        ("v,f\n0,abc\n", {}, "line 2: not two numbers"),
        ("v,mu\n0,0.5\n", {}, "pass mu_s, mu_k and speed"),
        ("v,mu\n0,-0.5\n", {"mu_s": 0.6, "mu_k": 0.4, "speed": 1.0}, "is negative"),
    ],
)
def test_bad_csv_files(tmp_path: Path, text: str, kwargs: dict, message: str) -> None:
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=message):
        read_friction_table(path, **kwargs)
    with pytest.raises(ValueError, match=r"friction table .*missing\.csv.* does not exist"):
        read_friction_table(tmp_path / "missing.csv")


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"velocity_ratio": 0.0}, "velocity_ratio=0.0 must be positive"),
        ({"velocity_ratio": 0.3, "mu0_ratio": 1.5}, "exceeds 1"),
        ({"velocity_ratio": 0.3, "tolerance": 0.5}, r"must lie in \[1e-9, 0.1\]"),
        ({"velocity_ratio": 0.3, "exponent": -1.0}, "exponent=-1.0 must be positive"),
    ],
)
def test_stribeck_refuses_bad_parameters(kwargs: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        StribeckFriction(**kwargs)


def test_stribeck_refuses_too_many_bands() -> None:
    with pytest.raises(ValueError, match="more than 2000"):
        StribeckFriction(0.3, tolerance=1e-9).bands(1.0, 2.0)


def test_describe_and_to_dict() -> None:
    assert CoulombFriction().describe() == "coulomb, exact"
    assert LinearFriction(0.05).describe().startswith("linear, delta = 0.05, exact")
    assert "piecewise-linear" in StribeckFriction(0.3).describe()
    assert LinearFriction(0.05).to_dict() == {"law": "linear", "delta": 0.05}
    assert Slider(1.0).friction == CoulombFriction()


def test_coulomb_json_keeps_its_keys_and_adds_the_new_ones() -> None:
    d = simulate(rigid_base(0.1), Slider(3.0)).to_dict()
    assert d["friction"] == {"law": "coulomb", "description": "coulomb, exact"}
    assert d["growth_rate"] == pytest.approx(-0.1) and d["steady_sliding_stable"] is True
    assert all(set(e) == {"t", "mode"} for e in d["events"])
    d2 = simulate(rigid_base(0.1), Slider(3.0, friction=LinearFriction(0.05))).to_dict()
    assert all("band" in e for e in d2["events"])


def test_run_cells_takes_per_cell_band_tables() -> None:
    # a small (lambda, delta) map: every cell equals its own simulate run
    st = rigid_base(0.1)
    cells = [(lam, delta) for lam in (0.5, 1.0, 3.0) for delta in (-0.05, 0.0, 0.05, 0.12)]
    tables = [LinearFriction(d).bands(lam, 2.0) for lam, d in cells]
    width = max(t[1].size for t in tables)
    n = len(cells)
    edges = np.full((n, width + 1), np.inf)
    intercepts = np.zeros((n, width))
    slopes = np.zeros((n, width))
    n_bands = np.empty(n, dtype=np.int64)
    for c, (e, a, s) in enumerate(tables):
        edges[c, : e.size] = e
        intercepts[c, : a.size] = a
        slopes[c, : s.size] = s
        n_bands[c] = a.size
    lams = np.array([lam for lam, _ in cells])
    gammas = np.full(n, 2.0)
    fout, iout = run_cells(st.mass[None], st.damping[None], st.stiffness[None], np.zeros(n, dtype=np.int64),
                           lams, gammas, edges, intercepts, slopes, n_bands, 5000.0, 100_000, 1e-9, 8)
    for c, (lam, d) in enumerate(cells):
        r = simulate(st, Slider(lam, friction=LinearFriction(d)), record=False)
        assert iout[c, 0] == r.status.code
        assert fout[c, 9] == r.t_end
    # the Coulomb helper gives the one-band table
    e, a, s, nb = coulomb_tables(lams[:2], gammas[:2])
    assert e.tolist() == [[0.0, math.inf]] * 2 and nb.tolist() == [1, 1]
    assert startup_vector(st.stiffness, 1.0, 2.0).tolist() == [-2.0, 1.0]


def test_slider_refuses_a_non_law() -> None:
    with pytest.raises(ValueError, match="is not a friction law"):
        Slider(1.0, friction=0.3)  # type: ignore[arg-type]
