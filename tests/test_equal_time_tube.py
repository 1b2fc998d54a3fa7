"""The cycle tube's equal-time variant across friction-band edges (analysis._band_variation).

References: the derivation in :mod:`stickslip.analysis._band_variation` (variation of
constants and Gronwall's inequality for a law continuous at its edges), checked here against
an independent integration of the perturbed motion (scipy's DOP853 on the exact tabulated
law, rtol 1e-12); the proven ball against direct runs of the package's exact return map from
its boundary; the rank-one norm against numpy's 2-norm of the full matrix.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from stickslip import InitialState, Slider, simulate
from stickslip.analysis import _cycle_tube, _product_norms, cycle_proof
from stickslip.analysis._band_variation import BandVariation, band_growth
from stickslip.analysis.engine_run import EngineOptions
from stickslip.analysis.return_map import ReturnMap
from stickslip.kernel.modes import find_band, mode_code
from stickslip.kernel.system import SLIP_I
from stickslip.model.friction import StribeckFriction
from stickslip.model.parameters import Foundation
from stickslip.model.structure import elastic_foundation
from tests.test_cycle_proof import _check_ball


def _foundation_weak():  # type: ignore[no-untyped-def]
    """benchmarks/bench_basin.py's "foundation weak" case and its proven cycle."""
    structure = elastic_foundation(0.05, Foundation(1.0, 1.0, 0.1))
    slider = Slider(0.05 * 0.2 * math.exp(5.0), friction=StribeckFriction(0.2, tolerance=1e-4))
    run = simulate(structure, slider,
                   initial=InitialState(np.array([0.6, 0.1]), np.array([-0.7, 0.1])))
    pmap = ReturnMap(structure, slider, EngineOptions())
    cand = cycle_proof._candidate(pmap, pmap.reduce(run.cycle_proof.fixed_point),
                                  run.cycle_proof.stick_phases)
    assert not isinstance(cand, str)
    return structure, slider, run, pmap, cand


@pytest.fixture(scope="module")
def weak():  # type: ignore[no-untyped-def]
    return _foundation_weak()


def test_band_differences_are_rank_one_and_a_jump_is_refused(weak) -> None:  # type: ignore[no-untyped-def]
    _, _, _, pmap, cand = weak
    to_y, to_z = cand.coords.from_state, cand.coords.to_state
    bands = BandVariation.of(pmap.edges, pmap.flow_matrix, pmap.flow_constant, pmap.n, to_y, to_z)
    assert bands is not None
    for i, k in ((0, 1), (3, 40), (50, 99)):
        full = to_y @ (pmap.flow_matrix[mode_code(SLIP_I, k)] - pmap.flow_matrix[mode_code(SLIP_I, i)]) @ to_z
        assert bands.spread(SLIP_I, i)[k] == pytest.approx(np.linalg.norm(full, 2), rel=1e-9)
    # a force jump at one edge (a law not continuous there): no equal-time comparison
    constant = pmap.flow_constant.copy()
    constant[mode_code(SLIP_I, 5)] += 1e-6 * np.abs(constant).max()
    assert BandVariation.of(pmap.edges, pmap.flow_matrix, constant, pmap.n, to_y, to_z) is None
    # one band (Coulomb) has none
    assert BandVariation.of(np.array([0.0, np.inf]), pmap.flow_matrix[:3], pmap.flow_constant[:3],
                            pmap.n, to_y, to_z) is None
    assert band_growth(bands, SLIP_I, 3, 0.0, 2.0, lambda d: 1.0) == (0.0, 1.0)


def _flow(pmap: ReturnMap, z0: np.ndarray, t: float) -> np.ndarray:
    """The exact slip-I motion over ``t`` under the tabulated law, band chosen by the speed."""
    n = pmap.n

    def rhs(_t: float, z: np.ndarray) -> np.ndarray:
        band = find_band(pmap.edges, 1.0 - z[n])
        mode = mode_code(SLIP_I, band)
        return pmap.flow_matrix[mode] @ z + pmap.flow_constant[mode]

    sol = solve_ivp(rhs, (0.0, t), z0, method="DOP853", rtol=1e-12, atol=1e-14)
    return sol.y[:, -1]


def test_gronwall_bound_holds_against_an_independent_integration(weak) -> None:  # type: ignore[no-untyped-def]
    # every band-edge phase of the cycle in the first quarter: perturbed starts at distance Z
    # (energy coordinates) flown at equal time; their deviation from the nominal's linear
    # image stays within the bound's extra part, and it is sharp enough to matter (the worst
    # case uses a real fraction of it)
    _, _, _, pmap, cand = weak
    to_y, to_z = cand.coords.from_state, cand.coords.to_state
    rng = np.random.default_rng(3)
    z_star = pmap.state(cand.b_hat)
    starts = [z_star]
    used = []
    for ph in cand.phases[:-1]:
        starts.append(to_z @ ph.z_end)
    for i, ph in enumerate(cand.phases[:50]):
        if not (ph.bands is not None and ph.edge_end) or i == 0:
            continue
        z0 = starts[i]
        for z_dev in (1e-4, 1e-3):
            grown = _cycle_tube._equal_time_growth(ph, z_dev, 0.0)
            assert grown is not None
            _, _, extra = grown
            for _ in range(3):
                dy = rng.normal(size=z0.size)
                dy *= z_dev / np.linalg.norm(dy)
                z_t = _flow(pmap, z0 + to_z @ dy, ph.duration)
                nominal = _flow(pmap, z0, ph.duration)
                linear = ph.e_nominal @ dy
                err = float(np.linalg.norm(to_y @ (z_t - nominal) - linear))
                assert err <= extra + 1e-11
                used.append(err / extra if extra > 0 else 0.0)
    assert len(used) >= 60 and max(used) > 1e-3


def test_the_equal_time_variant_proves_a_larger_ball_that_holds(weak) -> None:  # type: ignore[no-untyped-def]
    # the band-by-band tube contracts no ball beyond 4.4e-5 here (benchmarks/profile_cycle_ball.py);
    # the proof now takes the equal-time variant's larger ball, and direct runs of the exact
    # map from its boundary contract by theta (as tests/test_cycle_proof.py's _check_ball)
    structure, slider, run, pmap, cand = weak
    proof = run.cycle_proof
    tube_at, _ = cycle_proof.tubes(pmap, cand)
    adapted = cycle_proof._adapted_norm(cand.jac)
    assert adapted is not None
    _, norm_w, kappa = adapted
    banded = tube_at(proof.radius, False)
    assert not (banded.ok and norm_w + kappa * banded.jacobian_bound < 1.0)
    assert proof.radius > 1.5e-4
    _check_ball(structure, slider, run, np.random.default_rng(11), points=16, returns=3)


def test_gram_bounds_of_many_products_give_the_same_proof(weak, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    # beyond SVD_PRODUCTS products (a fine table's cycle) the norms between phases are the
    # Gram matrices' upper bounds (two_norm_bounds: its docstring's rounding argument) instead
    # of singular values: each at or above numpy's 2-norm and within 1e-12 of it, and the
    # proof of this cycle (202 phases, 20,503 products, under the threshold) the same ball
    structure, slider, run, pmap, cand = weak
    n2 = 2 * pmap.n  # the tube's lift and reduction, as cycle_proof.tubes forms them
    lift = cand.coords.from_state @ pmap.lift
    reduce = np.delete(np.eye(n2), [0, pmap.n], axis=0) @ cand.coords.to_state
    exact = _product_norms.ProductNorms.of(cand.phases, lift, reduce)
    monkeypatch.setattr(_product_norms, "SVD_PRODUCTS", 0)
    bounded = _product_norms.ProductNorms.of(cand.phases, lift, reduce)
    upper = np.triu_indices(len(cand.phases) + 1, 1)
    assert np.all(bounded.between[upper] >= exact.between[upper])
    assert np.max(bounded.between[upper] / exact.between[upper] - 1.0) < 1e-12
    proof = cycle_proof.prove_cycle(structure, slider, run.cycle_proof.fixed_point, 1, EngineOptions())
    assert proof is not None
    assert proof.radius == run.cycle_proof.radius
    assert proof.contraction == pytest.approx(run.cycle_proof.contraction, rel=1e-9)


def test_a_tangential_window_spans_band_edges(weak) -> None:  # type: ignore[no-untyped-def]
    # at radius 2e-3 the deviation exceeds band 0's width (4e-3 in u after the first phase's
    # growth): the departure from the belt speed is bounded through the following bands (the
    # window carried across edges), so the equal-time tube passes the first phases and fails
    # only near the cycle's end (benchmarks/profile_cycle_ball.py's ladder); direct runs from
    # that ball's boundary leave the belt speed without sticking again early: each returns to
    # the section after one stick phase, near the nominal image
    _, _, _, pmap, cand = weak
    tube_at, _ = cycle_proof.tubes(pmap, cand)
    radius = 1.98e-3
    tube = tube_at(radius, True)
    assert not tube.ok and tube.failed_phase > len(cand.phases) // 2
    b_hat = cand.b_hat
    image = pmap(b_hat, 1)
    rng = np.random.default_rng(5)
    for _ in range(12):
        u = rng.normal(size=b_hat.size)
        b = b_hat + radius * u / np.linalg.norm(u)
        out = pmap(b, 1)
        assert out is not None and float(np.linalg.norm(out - image)) <= radius
