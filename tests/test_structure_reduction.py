"""Reduction of a few-hundred-DOF structure (issue 18 point 5): the error stated.

Test structure: a 300-node frame chain (5 kg nodes, 1e8 N/m between them, 2e7 N/m each to the
floor) carrying a 1 kg slider on a 1e6 N/m spring at node 150; the slider is the contact
(DOF 300). References, each computed on the full 301-DOF model:

* the static receptance at the contact, ``[K^-1]_cc``: Craig-Bampton keeps it exactly;
* the receptance ``H_cc(w)`` below the cut-off, solved on the full dynamic stiffness;
* the critical friction-weakening slope: steady sliding of a velocity-weakening law turns
  unstable when the negative damping ``-dF/dv`` at the contact exceeds ``c_crit`` (for an
  exponential Stribeck law ``mu = mu_k + dmu exp(-v / v_s)`` the critical belt speed is then
  ``V_c = v_s ln(dmu W / (v_s c_crit))``, so the relative error of ``c_crit`` is the error of
  that critical speed's argument). The full model's growth rate must change sign within 1 %
  of the reduced model's ``c_crit``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp

from stickslip.analysis.reduction import default_cutoff_hz, reduce_structure
from stickslip.analysis.stability import critical_weakening, growth_rate
from stickslip.model.machine import Machine

N_FRAME, ATTACH = 300, 150
MU_S, MU_K, LOAD = 0.5, 0.3, 1000.0


def frame_with_slider(frame_damping: float = 1e-6) -> tuple[sp.csr_matrix, sp.csr_matrix,
                                                            sp.csr_matrix, int]:
    """Mass, damping, stiffness (SI, sparse) and the contact DOF of the test structure.

    The frame's damping is stiffness-proportional, ``frame_damping * K`` (s); the slider's
    dashpot is 40 N s/m.
    """
    n = N_FRAME + 1
    k = sp.lil_matrix((n, n))
    c = sp.lil_matrix((n, n))

    def stamp(mat: sp.lil_matrix, a: int, b: int | None, value: float) -> None:
        mat[a, a] += value
        if b is not None:
            mat[b, b] += value
            mat[a, b] -= value
            mat[b, a] -= value

    for i in range(N_FRAME - 1):
        stamp(k, i, i + 1, 1e8)
    for i in range(N_FRAME):
        stamp(k, i, None, 2e7)
    stamp(k, N_FRAME, ATTACH, 1e6)
    stamp(c, N_FRAME, ATTACH, 40.0)
    k_csr = k.tocsr()
    mass = sp.diags(np.r_[np.full(N_FRAME, 5.0), 1.0]).tocsr()
    damping = (c.tocsr() + frame_damping * k_csr).tocsr()
    return mass, damping, k_csr, N_FRAME


@pytest.fixture(scope="module")
def models() -> tuple[Machine, Machine, object]:
    mass, damping, stiffness, contact = frame_with_slider()
    cutoff = default_cutoff_hz(mass, stiffness, contact, speed=0.01, load=1000.0, mu_s=0.5, mu_k=0.3)
    red = reduce_structure(mass, stiffness, [contact], cutoff_hz=cutoff)
    full = Machine(mass.toarray(), damping.toarray(), stiffness.toarray(), contact, 0.5, 0.3, 1000.0, 0.01)
    reduced = Machine(red.mass, red.project(damping), red.stiffness, 0, 0.5, 0.3, 1000.0, 0.01)
    return full, reduced, red


def test_cutoff_and_size(models: tuple[Machine, Machine, object]) -> None:
    # reference: module docstring of analysis/reduction.py, 3 f_c with f_c = sqrt(1e6/1)/(2 pi)
    _, reduced, red = models
    assert red.cutoff_hz == pytest.approx(3.0 * 1000.0 / (2 * math.pi), rel=1e-12)  # type: ignore[attr-defined]
    assert 1 < reduced.n_dof <= 60 and not red.truncated  # type: ignore[attr-defined]


def test_static_receptance_at_the_contact_is_exact(models: tuple[Machine, Machine, object]) -> None:
    full, reduced, _ = models
    e = np.eye(full.n_dof)[full.contact_dof]
    exact = np.linalg.solve(full.stiffness, e)[full.contact_dof]
    assert np.linalg.solve(reduced.stiffness, np.eye(reduced.n_dof)[0])[0] == pytest.approx(exact, rel=1e-10)


def test_receptance_below_the_cutoff(models: tuple[Machine, Machine, object]) -> None:
    full, reduced, red = models
    for f_hz in np.linspace(20.0, red.cutoff_hz / 3.0, 12):  # type: ignore[attr-defined]
        w = 2 * math.pi * f_hz
        h = [np.linalg.solve(m.stiffness - w**2 * m.mass + 1j * w * m.damping,
                             np.eye(m.n_dof)[m.contact_dof])[m.contact_dof] for m in (full, reduced)]
        assert abs(h[1] / h[0] - 1.0) < 1e-3, f_hz


def test_critical_weakening_of_the_reduced_model_is_where_its_eigenvalues_cross(
        models: tuple[Machine, Machine, object]) -> None:
    # the 50-DOF reduced frame: the characteristic polynomial's roots gave no crossing in one run
    # and one 1 % off in the next (the matrices equal to round-off); the oracle is brentq on the
    # growth rate (numpy's eigenvalues) around the value found
    from scipy.optimize import brentq

    structure = models[1].structure()
    assert structure.n_dof > 40
    first = critical_weakening(structure)
    assert growth_rate(structure, 0.0) < 0.0 and np.isfinite(first)
    oracle = brentq(lambda x: growth_rate(structure, x), 0.5 * first, 1.5 * first, xtol=1e-15)
    assert first == pytest.approx(oracle, rel=1e-9)
    # no earlier loss of stability was skipped (numpy's eigenvalues at 100 weakenings below it)
    assert all(growth_rate(structure, d) < 0.0 for d in np.linspace(0.0, 0.999 * first, 100))


@pytest.mark.slow  # two eigen-solutions of the 602-state full model: ~50 s on a shared core
def test_critical_weakening_of_reduced_and_full_agree_within_one_percent(
        models: tuple[Machine, Machine, object]) -> None:
    full, reduced, _ = models
    to_si = 2.0 * math.sqrt(reduced.reference_mass * reduced.reference_stiffness)
    c_crit = critical_weakening(reduced.structure()) * to_si  # N s/m of negative damping
    full_scale = 2.0 * math.sqrt(full.reference_mass * full.reference_stiffness)
    st = full.structure()
    assert growth_rate(st, 0.99 * c_crit / full_scale) < 0.0 < growth_rate(st, 1.01 * c_crit / full_scale)


@pytest.mark.slow  # the reduced model's onset search (~15 s) and two 301-DOF runs (~15-30 s each)
def test_coulomb_critical_speed_of_reduced_and_full_agree_within_two_percent() -> None:
    # reference: the full 301-DOF model simulated from start-up (the engine at 301 DOF: its
    # phase record grows instead of holding max_events x 602 doubles, its Lyapunov solve is
    # O(n^3)); the stick-slip onset of the full model must lie within 2 % of the reduced
    # model's critical belt speed V_c (stick-slip at 0.98 V_c, steady sliding at 1.02 V_c).
    # Frame damping 2e-5 K: the frame modes at 2-9 % of critical, so runs certify.
    from stickslip.analysis.machine_absorber import CriticalPoint
    from stickslip.analysis.simulation import simulate

    mass, damping, stiffness, contact = frame_with_slider(2e-5)
    cutoff = default_cutoff_hz(mass, stiffness, contact, speed=0.01, load=LOAD, mu_s=MU_S, mu_k=MU_K)
    red = reduce_structure(mass, stiffness, [contact], cutoff_hz=cutoff)
    reduced = Machine(red.mass, red.project(damping), red.stiffness, 0, MU_S, MU_K, LOAD, 0.01)
    v_c = CriticalPoint.of(reduced).speed
    assert math.isfinite(v_c) and v_c > 0.0
    full = Machine(mass.toarray(), damping.toarray(), stiffness.toarray(), contact, MU_S, MU_K,
                   LOAD, 0.01)
    runs = []
    for factor in (0.98, 1.02):
        point = full.with_operating_point(speed=factor * v_c, load=LOAD)
        runs.append(simulate(point.structure(), point.slider(), record=True))
    below, above = runs
    # below: stick-slip. Its cycle's proof at 301 DOF would sample 20,000 603 x 603 propagators
    # per slip phase, beyond the work a proof may take even factored (_phase_flow.flow_work:
    # 3.8e11 multiply-adds against MAX_PHASE_WORK, 2.5e11), so the run ends on its stick-slip
    # candidate, declined, not on steady sliding (with the bound lifted the proof holds)
    assert (below.verdict.value == "stick-slip"
            or "candidate, not proven" in below.certificate), below.certificate
    assert below.n_stick > 1
    assert above.verdict.value == "steady-sliding"


def test_a_truncated_reduction_says_so_on_stderr(capsys: pytest.CaptureFixture[str]) -> None:
    # an independent audit's 120-DOF chain (2 kg nodes, the 1 kg contact node 60 in the middle,
    # 5e6 N/m links, 1e6 N/m to ground): 56 modes of the 60-DOF engine cannot hold the modes
    # below 1 kHz, and the reduced model's critical speed was 11.7 % above the full one's with
    # no word in the text output
    from stickslip.analysis.reduction import MAX_KEPT_MODES
    from stickslip.cli.machine_config import warn_truncated

    n = 120
    mass = np.full(n, 2.0)
    mass[60] = 1.0
    stiffness = sp.diags([np.full(n, 2 * 5e6 + 1e6), np.full(n - 1, -5e6), np.full(n - 1, -5e6)],
                         [0, 1, -1]).tocsc()
    reduced = reduce_structure(sp.diags(mass).tocsc(), stiffness, (60,), cutoff_hz=1000.0)
    assert reduced.truncated and reduced.n_modes == MAX_KEPT_MODES
    warn_truncated(reduced)
    [line] = capsys.readouterr().err.strip().splitlines()
    assert line.startswith("stickslip: warning: the 120-DOF model was reduced to 57 DOF")
    # a reduction that keeps every mode below its cut-off says nothing
    small = reduce_structure(sp.diags(mass).tocsc(), stiffness, (60,), cutoff_hz=150.0)
    assert not small.truncated and small.truncation_warning() is None
    warn_truncated(small)
    assert capsys.readouterr().err == ""


def test_a_cutoff_below_the_operating_points_default_is_said() -> None:
    # an independent audit's 120-DOF chain at a 150 Hz cut-off (the default 1,584 Hz at
    # V = 1 cm/s, W = 1000 N, mu 0.5/0.3): the reduced model called steady sliding unstable
    # (+10.1 1/s under a weakening law) where the full model's is stable (-5.65 1/s)
    from stickslip.analysis.reduction import reduce_at_operating_point

    n = 120
    mass = np.full(n, 2.0)
    mass[60] = 1.0
    stiffness = sp.diags([np.full(n, 2 * 5e6 + 1e6), np.full(n - 1, -5e6), np.full(n - 1, -5e6)],
                         [0, 1, -1]).tocsc()
    point = (0.01, 1000.0, 0.5, 0.3)
    low = reduce_at_operating_point(sp.diags(mass).tocsc(), stiffness, [60], cutoff_hz=150.0,
                                    operating_point=point)
    assert low.default_cutoff_hz == pytest.approx(
        default_cutoff_hz(sp.diags(mass).tocsc(), stiffness, 60, speed=0.01, load=1000.0,
                          mu_s=0.5, mu_k=0.3))
    assert low.cutoff_warning() is not None and "below the default" in low.cutoff_warning()
    default = reduce_at_operating_point(sp.diags(mass).tocsc(), stiffness, [60], cutoff_hz=None,
                                        operating_point=point)
    assert default.cutoff_warning() is None and default.cutoff_hz == low.default_cutoff_hz
