"""Critical lambda against zeta by scan and bisection, non-monotone boundaries included."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from matplotlib.figure import Figure

from stickslip import Foundation, Slider, Verdict, chain_structure, simulate
from stickslip.analysis.dva import resolve_dva
from stickslip.analysis.theory import (
    critical_lambda_approx,
    critical_lambda_exact,
    equivalent_damping_fit,
)
from stickslip.model.dva import DvaSpec
from stickslip.sweep import stick_slip_boundary

#: A lightly damped, soft foundation whose stick-slip set along lambda at zeta = 0.1 is two
#: intervals (steady, stick-slip, steady, stick-slip): found by an occurrence-map survey.
TWO_BAND = DvaSpec("explicit", Foundation(1.0, 0.7, 0.02))


def _verdict(dva: DvaSpec, lam: float, zeta: float) -> Verdict:
    foundation = resolve_dva(dva, zeta)
    structure = chain_structure(zeta, () if foundation is None else (foundation,))
    return simulate(structure, Slider(lam, gamma=2.0), record=False).verdict


def test_rigid_base_boundary_equals_eq_36_root() -> None:
    # reference: root of Nakano's exact boundary, paper Eq. (36)
    zetas = [0.01, 0.05, 0.1, 0.3, 0.6]
    result = stick_slip_boundary(zetas, "none", rtol=1e-6)
    for zeta, found, crossings in zip(zetas, result.critical_lambda, result.crossings, strict=True):
        exact = critical_lambda_exact(zeta)
        digits = -math.log10(abs(found / exact - 1.0) + 1e-17)
        print(f"zeta={zeta:<5} boundary {found:.10g} | Eq. (36) {exact:.10g} | digits {digits:.1f}")
        assert abs(found / exact - 1.0) <= 1e-6
        assert len(crossings) == 1 and crossings[0].onset and crossings[0].converged
        assert crossings[0].lam_above - crossings[0].lam_below <= 1e-6 * crossings[0].lam_below


def test_non_monotone_boundary_is_found_whole() -> None:
    zeta = 0.1
    result = stick_slip_boundary([zeta], TWO_BAND, lam_min=0.1, lam_max=10.0, n_scan=40, rtol=1e-7)
    crossings = result.crossings[0]
    assert [c.onset for c in crossings] == [True, False, True]
    assert all(c.converged for c in crossings)
    # each crossing separates the two verdicts, checked by independent single runs
    for c in crossings:
        below, above = _verdict(TWO_BAND, c.lam_below, zeta), _verdict(TWO_BAND, c.lam_above, zeta)
        assert (below, above) == ((Verdict.STEADY_SLIDING, Verdict.STICK_SLIP) if c.onset
                                  else (Verdict.STICK_SLIP, Verdict.STEADY_SLIDING))
        assert c.lam_above / c.lam_below - 1.0 <= 1e-7
    assert result.critical_lambda[0] == crossings[0].lam
    assert 0.40 < crossings[0].lam < 0.43 and 0.47 < crossings[1].lam < 0.50
    assert 0.77 < crossings[2].lam < 0.80


def test_result_exports_and_analytic_values() -> None:
    result = stick_slip_boundary([0.0, 0.1, 0.2], "optimal", lam_min=0.5, lam_max=50.0, n_scan=16,
                                 rtol=1e-4)
    payload = result.to_dict()
    json.dumps(payload, allow_nan=False)
    rows = payload["rows"]
    assert [r["zeta"] for r in rows] == [0.0, 0.1, 0.2]
    # Eq. (37) with zeta_eq of Eq. (33) for the fitted optimum
    assert rows[1]["eq37"] == pytest.approx(critical_lambda_approx(equivalent_damping_fit(0.1)))
    assert rows[1]["critical_lambda"] == pytest.approx(float(result.critical_lambda[1]))
    ds = result.to_xarray()
    assert ds["crossing_kind"].attrs["flag_meanings"].split()[2] == "onset-of-stick-slip"
    assert ds["scan_verdict"].shape == (3, 16)
    np.testing.assert_array_equal(ds["critical_lambda"].values, result.critical_lambda)
    assert "critical_lambda_eq37" in ds
    ax = Figure().add_subplot()
    artists = result.plot(ax=ax).artists
    assert artists and ax.get_yscale() == "log"
    with pytest.raises(TypeError):
        result.plot(ax=ax, color="red")


def test_edge_cases_are_explained() -> None:
    # zeta = 0: the rigid base stick-slips for every lambda (Eq. 36 gives 0)
    result = stick_slip_boundary([0.0, 0.5], "none", lam_min=0.5, lam_max=2.0, n_scan=4)
    assert math.isnan(result.critical_lambda[0])
    assert "already at lam_min" in result.notes()[0]
    assert math.isinf(result.critical_lambda[1])  # Eq. (36) at 0.5 is ~8: above the range
    assert "no stick-slip" in result.notes()[1]


@pytest.mark.parametrize(
    ("kwargs", "needle"),
    [
        ({"lam_min": 0.0}, "lam_min=0.0 must be positive"),
        ({"lam_min": 2.0, "lam_max": 1.0}, "must exceed"),
        ({"n_scan": 1}, "n_scan=1"),
        ({"rtol": 0.0}, "rtol=0.0 must be positive"),
        ({"rtol": 1.5}, "rtol=1.5 must lie in "),
        ({"zetas": [-0.1]}, "zeta=-0.1 must not be negative"),
    ],
)
def test_bad_arguments(kwargs: dict[str, object], needle: str) -> None:
    args: dict[str, object] = {"zetas": [0.1], "dva": "none"}
    args.update(kwargs)
    with pytest.raises(ValueError, match=needle):
        stick_slip_boundary(**args)  # type: ignore[arg-type]


def test_a_tabulated_laws_boundary_says_whose_rtol_it_is(capsys: pytest.CaptureFixture[str]) -> None:
    """An independent audit: 2.7134704 "converged, rtol 1e-6" where the smooth law's boundary is
    2.7131087 (1.3e-4 relative; 1.1e-6 at tol=1e-6): the bisection's tolerance is the
    interpolant's, and the text says so; an exact law's has no such note."""
    from tests.cli_helpers import run_cli

    code, out, _ = run_cli(["boundary", "--zeta", "0.085", "--friction", "stribeck:vs=0.3,n=2"], capsys)
    assert code == 0 and "rtol is the bisection's, for the law's piecewise-linear interpolant" in out
    code, out, _ = run_cli(["boundary", "--zeta", "0.085"], capsys)
    assert code == 0 and "interpolant" not in out
