"""Basin stability (issue 13, point 1): certified verdicts for many initial states.

Sources: every label must equal the verdict of :func:`stickslip.simulate` started from the same
state (the engine is deterministic; the batch shares only the prepared matrices); the startup
state of DESIGN.md section 1 in physical coordinates is ``x = 0`` (springs relaxed), ``v = V``;
the binomial standard error ``sqrt(p (1 - p) / n)``; the certified safe region of
:mod:`stickslip.analysis.disturbance` contains only steady sliding.
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest

from stickslip import (
    InitialState,
    PhysicalSystem,
    Slider,
    Verdict,
    elastic_foundation,
    optimal_foundation_fit,
    rigid_base,
    simulate,
    startup_state,
)
from stickslip.analysis.disturbance import safe_disturbance
from stickslip.model.friction import LinearFriction, StribeckFriction
from stickslip.sweep.basin import basin_stability, equilibrium_state, sample_box, states_from_physical
from stickslip.sweep.execution import ExecutionOptions

from .cli_helpers import run_cli

SYSTEMS = [
    ("rigid coulomb", rigid_base(0.1), Slider(2.5)),
    ("rigid stribeck", rigid_base(0.1), Slider(2.0, friction=StribeckFriction(0.2, tolerance=1e-3))),
    ("foundation", elastic_foundation(0.1, optimal_foundation_fit(0.1).scaled(0.5)), Slider(12.0)),
]


@pytest.mark.parametrize(("name", "structure", "slider"), SYSTEMS, ids=[s[0] for s in SYSTEMS])
def test_labels_equal_single_simulations(name, structure, slider) -> None:  # type: ignore[no-untyped-def]
    names = ["xi", "v"] if structure.n_dof == 1 else ["xi", "xi_a", "v", "v_a"]
    box = {names[0]: (-4.0, 4.0), names[structure.n_dof]: (-3.0, 1.5)}
    states = sample_box(structure, slider, 60, box, seed=5)
    result = basin_stability(structure, slider, states, execution=ExecutionOptions(workers=2))
    for state, code in zip(states, result.verdict, strict=True):
        n = structure.n_dof
        single = simulate(structure, slider, initial=InitialState(state[:n], state[n:]), record=False)
        assert single.verdict.code == int(code), name
    assert sum(result.fractions.values()) == pytest.approx(1.0)
    p = result.fractions["stick-slip"]
    assert result.standard_errors["stick-slip"] == pytest.approx(math.sqrt(p * (1 - p) / 60))


def test_the_safe_region_holds_only_steady_sliding() -> None:
    structure, slider = rigid_base(0.1), Slider(2.5)
    result = basin_stability(structure, slider, sample_box(structure, slider, 3000,
                                                           {"xi": (-4, 4), "v": (-3, 1.5)}, seed=2))
    energy = 0.5 * result.states[:, 0] ** 2 + 0.5 * result.states[:, 1] ** 2
    inside = energy < safe_disturbance(structure, slider).energy
    assert inside.sum() > 100
    assert np.all(result.verdict[inside] == Verdict.STEADY_SLIDING.code)
    # bistable: the box holds both outcomes
    assert 0.05 < result.fractions["steady-sliding"] < 0.95


def test_physical_startup_state_maps_to_the_startup_state() -> None:
    system = PhysicalSystem(mass=2.0, stiffness=5e4, damping=20.0, mu_s=0.5, mu_k=0.3, load=150.0, speed=0.05)
    state = states_from_physical(system, np.array([[0.0, 0.05]]))[0]
    ref = startup_state(system.structure(), system.slider())
    assert state == pytest.approx(np.concatenate([ref.position, ref.velocity]), abs=1e-12)
    assert np.array_equal(equilibrium_state(system.structure(), system.slider()), np.zeros(2))


def test_basin_command_writes_labels_in_input_order(tmp_path: Path,
                                                    capsys: pytest.CaptureFixture[str]) -> None:
    states = tmp_path / "states.csv"
    states.write_text("id,xi,v\na,0.1,0.2\nb,3.5,-2.5\nc,-0.2,0.1\n")
    code, out, err = run_cli(["basin", "--lam", "2.5", "--zeta", "0.1", "--initial-states", str(states),
                              "--out", str(tmp_path / "run"), "--json"], capsys)
    assert code == 0, err
    payload = json.loads(out)
    assert payload["n"] == 3 and set(payload) >= {"fractions", "standard_errors", "undetermined", "elapsed_s"}
    with open(tmp_path / "run" / "labels.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["id"] for r in rows] == ["a", "b", "c"]
    expected = [
        simulate(rigid_base(0.1), Slider(2.5), initial=InitialState([x], [v]), record=False).verdict.value
        for x, v in ((0.1, 0.2), (3.5, -2.5), (-0.2, 0.1))
    ]
    assert [r["verdict"] for r in rows] == expected
    assert (tmp_path / "run" / "basin.nc").exists()


@pytest.mark.parametrize("args", [
    ["--lam", "2", "--zeta", "0.1", "--box", "q=1:2"],
    ["--lam", "2", "--zeta", "0.1", "--box", "xi=1"],
    ["--lam", "2", "--zeta", "0.1", "--samples", "0"],
    ["--lam", "2", "--zeta", "0.1", "--workers", "0"],
    ["--lam", "2"],
    ["--lam", "2", "--zeta", "0.1", "--initial-states", "/no/such.csv"],
])
def test_basin_bad_input_is_one_line(args: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(["basin", *args], capsys)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_basin_map_cells_and_the_start_up_boundary() -> None:
    # sources: the map's definition (each cell = basin_stability on the fixed deviations) and
    # Eq. (36): below the rigid-base critical lambda no cycle exists, so no disturbance can
    # end in stick-slip
    from stickslip import critical_lambda_exact, occurrence_map
    from stickslip.sweep.basin_maps import basin_map

    lams, zetas = [0.5, 2.5, 6.0], [0.05, 0.2]
    result = basin_map(lams, zetas, "none", samples=200, seed=3)
    ds = result.dataset
    assert ds["stick_slip_fraction"].dims == ("lambda", "zeta")
    startup = occurrence_map(lams, zetas, "none")
    assert np.array_equal(ds["startup_verdict"].values, startup.verdict)
    rng = np.random.default_rng(3)
    dev = {"xi": rng.uniform(-2.0, 2.0, 200), "v": rng.uniform(-2.0, 1.0, 200)}
    for i, lam in enumerate(lams):
        for j, zeta in enumerate(zetas):
            states = np.column_stack([dev["xi"], dev["v"]])
            cell = basin_stability(rigid_base(zeta), Slider(lam), states)
            assert ds["stick_slip_fraction"].values[i, j] == cell.fractions["stick-slip"]
            if lam < critical_lambda_exact(zeta):
                assert ds["stick_slip_fraction"].values[i, j] == 0.0
    assert result.plot().figure is not None


def test_basin_resumes_from_its_store(tmp_path: Path) -> None:
    # a store of finished batches: a rerun with the same system and states reuses them (a deleted
    # batch is recomputed) and gives the identical labels; other states are another configuration
    from stickslip.sweep.store import StoreMismatch

    structure, slider = rigid_base(0.1), Slider(2.5)
    states = sample_box(structure, slider, 300, {"xi": (-4, 4), "v": (-3, 1.5)}, seed=4)
    store = tmp_path / "basin.parts"
    first = basin_stability(structure, slider, states,
                            execution=ExecutionOptions(chunk_size=64, store=store))
    chunks = sorted(store.glob("chunk-*.npz"))
    assert len(chunks) == 5
    chunks[2].unlink()
    again = basin_stability(structure, slider, states,
                            execution=ExecutionOptions(chunk_size=64, store=store))
    assert np.array_equal(first.verdict, again.verdict)
    assert np.array_equal(first.float_summary, again.float_summary, equal_nan=True)
    with pytest.raises(StoreMismatch):
        basin_stability(structure, slider, states[:200],
                        execution=ExecutionOptions(chunk_size=64, store=store))


def test_basin_map_over_lambda_and_delta() -> None:
    # sources: the map's definition (each cell = basin_stability of LinearFriction(delta) on the
    # fixed deviations about the cell's own steady sliding, equilibrium_state); the start-up
    # verdict is occurrence_map with deltas on the same grid; critical_lambda_linear: on the rigid
    # base with mu = mu_k - sigma v_r every breakaway is the breakaway of Nakano's system with
    # damping zeta_e = zeta - delta, so the boundary is Eq. (36) at zeta_e, for disturbed starts
    # too (a disturbed start either never sticks, and decays to steady sliding when zeta_e > 0,
    # or sticks and then breaks away at that one state)
    from stickslip import occurrence_map
    from stickslip.analysis.theory import critical_lambda_linear
    from stickslip.model.friction import LinearFriction
    from stickslip.sweep.basin_maps import basin_map

    zeta = 0.1
    lams, deltas = [0.25, 0.4, 3.5, 6.0], [-0.05, 0.0, 0.05, 0.15]
    result = basin_map(lams, [zeta], "none", samples=200, seed=3, deltas=deltas)
    ds = result.dataset
    assert ds["stick_slip_fraction"].dims == ("lambda", "delta") and result.second_axis_name == "delta"
    assert ds.attrs["zeta"] == zeta
    startup = occurrence_map(lams, [zeta], "none", deltas=deltas)
    assert np.array_equal(ds["startup_verdict"].values, startup.verdict)
    rng = np.random.default_rng(3)
    dev = np.column_stack([rng.uniform(-2.0, 2.0, 200), rng.uniform(-2.0, 1.0, 200)])
    fraction = ds["stick_slip_fraction"].values
    for i, lam in enumerate(lams):
        for j, delta in enumerate(deltas):
            slider = Slider(lam, friction=LinearFriction(delta))
            # steady sliding moves with the law: K xi = F(1) - gamma lambda = -2 delta (Eq. 22)
            eq = equilibrium_state(rigid_base(zeta), slider)
            assert eq == pytest.approx([-2.0 * delta, 0.0], abs=1e-15)
            cell = basin_stability(rigid_base(zeta), slider, eq + dev)
            assert fraction[i, j] == cell.fractions["stick-slip"]
            lam_c = critical_lambda_linear(zeta, delta)  # 2.057, 1.470, 0.911, 0 (zeta_e < 0)
            if lam <= 0.5 * lam_c:
                # well below Eq. (36) at zeta_e: no stick-slip cycle exists, whatever the start
                assert fraction[i, j] == 0.0, (lam, delta)
                assert startup.verdict_at(lam, delta=delta) == Verdict.STEADY_SLIDING
            if lam >= 1.5 * lam_c:
                # well above: the start-up ends on the cycle, and part of the box does too
                # (measured 0.36, 0.515, 0.635 of this sample for delta = -0.05, 0, 0.05)
                assert fraction[i, j] > 0.3, (lam, delta)
                assert startup.verdict_at(lam, delta=delta) == Verdict.STICK_SLIP
            if delta > zeta:
                # zeta_e < 0: steady sliding is unstable (negative slip damping), so every
                # disturbance grows until the slider sticks, then the cycle
                assert fraction[i, j] == 1.0, (lam, delta)
    # the rigid base is never bistable below its boundary: where the start-up slides steadily,
    # no disturbance of the sample ends in stick-slip
    steady = ds["startup_verdict"].values == Verdict.STEADY_SLIDING.code
    assert steady.any() and np.all(fraction[steady] == 0.0)
    assert result.to_dict()["disturbable_cells"] == 0
    assert ds["undetermined_fraction"].values.max() == 0.0


def test_basin_map_plot_names_the_second_axis() -> None:
    # source: basin_map_plot labels the grid's second coordinate (issue 13, point 2)
    from stickslip.sweep.basin_maps import basin_map

    by_zeta = basin_map([0.5, 3.0], [0.05, 0.2], "none", samples=20).plot()
    assert "zeta" in by_zeta.axes[0].get_xlabel()
    by_delta = basin_map([0.5, 3.0], [0.1], "none", samples=20, deltas=[0.0, 0.05]).plot()
    ax = by_delta.axes[0]
    assert "delta" in ax.get_xlabel() and "zeta" not in ax.get_xlabel()
    assert "= 0.1" in ax.get_title()


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"deltas": [0.0, 0.05], "zetas": [0.05, 0.1]}, "one fixed zeta"),
    ({"deltas": [0.0], "friction": LinearFriction(0.1)}, "exclude each other"),
    ({"box": {"xi_a": (-1.0, 1.0)}}, "not among"),
    ({"box": {"xi": (1.0, -1.0)}}, "lo <= hi"),
    ({"samples": 0}, "samples"),
])
def test_basin_map_rejects_bad_input_before_running(kwargs, message) -> None:  # type: ignore[no-untyped-def]
    from stickslip.sweep.basin_maps import basin_map

    args = {"lams": [1.0], "zetas": [0.1], **kwargs}
    with pytest.raises(ValueError, match=message):
        basin_map(args.pop("lams"), args.pop("zetas"), "none", **args)
