"""The stick-slip-optimal foundation (beyond the paper, issue 6)."""

from __future__ import annotations

import math

import pytest

from stickslip import Foundation, Slider, Verdict, elastic_foundation, simulate
from stickslip.analysis.critical import lowest_onset
from stickslip.analysis.stick_slip_tuning import optimal_foundation_stick_slip
from stickslip.analysis.theory import optimal_foundation_fit
from stickslip.model.dva import DvaSpec
from stickslip.sweep import stick_slip_boundary


def test_lowest_onset_agrees_with_full_scan() -> None:
    # two independent searches of the same structure: upward scan (analysis) vs the
    # batched bracketing of every verdict change (sweep)
    zeta = 0.1
    st = elastic_foundation(zeta, optimal_foundation_fit(zeta).scaled(2.0))
    fast = lowest_onset(st, rtol=1e-7)
    full = stick_slip_boundary([zeta], DvaSpec("optimal", k_scale=2.0), rtol=1e-7)
    onsets = [c.lam for c in full.crossings[0] if c.onset]
    assert fast == pytest.approx(onsets[0], rel=1e-6)


def test_tuned_foundation_beats_absorber_optimum_and_is_checked_by_simulation() -> None:
    zeta, lam_max = 0.1, 60.0
    result = optimal_foundation_stick_slip(zeta, lam_max=lam_max)
    ref = optimal_foundation_fit(zeta)
    # default bound: the absorber optimum's mass ratio, Eq. (28)
    assert result.foundation.mass_ratio <= ref.mass_ratio * (1 + 1e-12)
    assert result.reference == ref
    # the absorber optimum's onset is a real stick-slip onset (checked on both sides)
    st_ref = elastic_foundation(zeta, ref)
    lam_ref = result.reference_lambda_crit
    assert simulate(st_ref, Slider(lam_ref * 1.001)).verdict is Verdict.STICK_SLIP
    assert simulate(st_ref, Slider(lam_ref * 0.999)).verdict is Verdict.STEADY_SLIDING
    # the paper's observation (Figs. 11a, 12-15): a softer foundation than K_opt does better
    assert result.lambda_crit > lam_ref
    assert result.foundation.stiffness_ratio < ref.stiffness_ratio
    st = elastic_foundation(zeta, result.foundation)
    probe = min(result.lambda_crit, lam_max) * 0.999
    assert simulate(st, Slider(probe)).verdict is Verdict.STEADY_SLIDING
    d = result.to_dict()
    assert {"M", "K", "zeta_a", "lambda_crit", "absorber_optimum"} <= d.keys()
    if math.isinf(result.lambda_crit):
        assert d["lambda_crit"] is None and d["lambda_crit_at_least"] == lam_max


def test_mass_ratio_bounds_are_validated() -> None:
    with pytest.raises(ValueError, match="wrong order"):
        optimal_foundation_stick_slip(0.1, mass_ratio_bounds=(2.0, 1.0))
    with pytest.raises(ValueError, match="must be positive"):
        optimal_foundation_stick_slip(0.1, mass_ratio_bounds=(0.0, 1.0))


def test_explicit_reference_is_used() -> None:
    ref = Foundation(1.0, 1.0, 1.0)
    result = optimal_foundation_stick_slip(0.2, reference=ref, lam_max=20.0, maxiter=5)
    assert result.reference == ref
    assert result.mass_ratio_bounds == (1.0 / 20.0, 1.0)


def test_tune_cli_stick_slip_objective(capsys: pytest.CaptureFixture[str]) -> None:
    import json

    from stickslip.cli.main import run

    try:
        run(["tune", "--zeta", "0.2", "--objective", "stick-slip", "--lam-max", "30", "--json"])
    except SystemExit as exc:
        assert not exc.code
    payload = json.loads(capsys.readouterr().out)
    assert {"M", "K", "zeta_a", "lambda_crit", "absorber_optimum"} <= payload.keys()
    assert {"M", "K", "zeta_a", "lambda_crit"} <= payload["absorber_optimum"].keys()
    # default mass bound: M_opt of Eq. (28) at zeta = 0.2 (5.276)
    assert payload["M"] <= 5.276 + 1e-9
    with pytest.raises(SystemExit) as err:
        run(["tune", "--zeta", "0.2", "--objective", "nonsense"])
    assert err.value.code == 2
