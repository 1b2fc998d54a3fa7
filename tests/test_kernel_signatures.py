"""The engine's kernels are compiled once each (issue 21.5: a cold first run under 60 s).

numba compiles a kernel once for every distinct set of argument types it is called with,
literal constants and array layouts included, and re-optimises each compiled entry point's
whole call tree. The engine therefore passes constants as ``np.int64``/``np.bool_``, copies
arrays instead of slice-assigning them, and hands the kernels one layout per argument
(:mod:`stickslip.kernel.linalg`'s note); ``engine.run`` is a Python function over three
compiled entry points. The measured effect is in ``benchmarks/bench_startup.py --cold``; this
checks the cause: after simulations of every kind the engine runs (1, 2, 3 and 5 DOFs,
Coulomb and velocity-dependent laws, dense output), each heavy kernel holds one signature.
It compiles into an empty numba cache (a kernel loaded from the cache brings its callees
inside it, so only a cold run shows them): about a minute, hence ``slow``.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

#: Kernels whose compile took 0.3 s or more of a cold ``simulate`` (the profile of issue 21.5).
HEAVY = {
    "engine": ["run_prepared", "record_state"],
    "dense_output": ["evaluate_prepared"],
    "system": ["structure_data", "prepare_point", "lyapunov_data", "_common_lyapunov"],
    "modes": ["structure_matrices", "slip_matrices", "mode_step", "twin_mode_step", "fill_mode",
              "mode_signature"],
    "linalg": ["expm", "inverse", "gauss_solve", "lyapunov_solve", "solve_lyapunov",
               "solve_lyapunov_sign", "inverse_lu", "forced_step", "step_norm"],
    "events": ["first_reach", "interior_range", "_polynomials"],
    "polynomial": ["taylor_vectors", "functional_polynomials", "poly_value", "monotone_root",
                   "monotone_breakpoints"],
}

SCRIPT = """
import importlib, json, sys
import numpy as np
from stickslip import (Foundation, LinearFriction, Slider, StribeckFriction, TableFriction,
                       chain_structure, simulate)

structures = [chain_structure(0.1, ()), chain_structure(0.05, (Foundation(0.1, 0.9, 0.1),)),
              chain_structure(0.05, (Foundation(0.1, 0.9, 0.1), Foundation(0.05, 1.3, 0.05))),
              chain_structure(0.05, tuple(Foundation(0.05, 0.8 + 0.1 * k, 0.05) for k in range(4)))]
laws = [None, StribeckFriction(0.2, tolerance=1e-3), LinearFriction(0.05),
        TableFriction((0.0, 0.3, 1.0, 3.0), (1.0, 0.8, 0.7, 0.75))]
for structure in structures:
    for law in laws:
        slider = Slider(2.0) if law is None else Slider(2.0, friction=law)
        result = simulate(structure, slider)
        result.state_at(np.linspace(0.0, result.t_end, 7))
heavy = json.loads(sys.argv[1])
counts = {f"{module}.{name}": len(getattr(importlib.import_module("stickslip.kernel." + module),
                                          name).signatures)
          for module, names in heavy.items() for name in names}
print(json.dumps(counts))
"""


@pytest.mark.slow
def test_every_heavy_engine_kernel_is_compiled_for_one_signature(tmp_path: Path) -> None:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}  # cold: every kernel compiles here
    done = subprocess.run([sys.executable, "-c", SCRIPT, json.dumps(HEAVY)], capture_output=True,
                          text=True, check=True, timeout=1800, env=env)
    counts = json.loads(done.stdout.splitlines()[-1])
    assert len(counts) == sum(len(names) for names in HEAVY.values())
    assert {name: n for name, n in counts.items() if n != 1} == {}


BATCH_SCRIPT = """
import json
import numpy as np
from stickslip import Foundation, Slider, StribeckFriction, elastic_foundation, rigid_base
from stickslip.analysis.engine_run import EngineOptions
from stickslip.kernel import batch
from stickslip.sweep.basin import basin_stability, sample_box

opts = EngineOptions()
limits = (opts.t_max, opts.max_events, opts.cycle_tol, opts.max_period)
for structure in (rigid_base(0.1), elastic_foundation(0.1, Foundation(0.05, 1.0, 0.1))):
    slider = Slider(2.0, friction=StribeckFriction(0.2, tolerance=1e-3))
    states = sample_box(structure, slider, 1000, {"xi": (-1.0, 1.0), "v": (-1.0, 1.5)}, seed=3)
    basin_stability(structure, slider, states[:40])  # the command's path (prepared once)
    edges, intercepts, slopes = slider.friction.bands(slider.lam, slider.gamma)
    args = (structure.mass, structure.damping, structure.stiffness, slider.lam, slider.gamma,
            edges, intercepts, slopes)  # a Structure's own, read-only matrices
    batch.prepare_states(*args)  # the defaults left out
    batch.prepare_states(*args, False)
    batch.run_states(*args, states[:20], *limits)
    batch.run_states(*args, states[:20], *limits, False, False)
    lams = np.array([1.0, 2.0])
    e, a, s, nb = batch.coulomb_tables(lams, np.full(2, 2.0))
    cells = (np.zeros(2, dtype=np.int64), lams, np.full(2, 2.0), e, a, s, nb, *limits)
    batch.run_cells(structure.mass[None], structure.damping[None], structure.stiffness[None],
                    *cells)  # read-only views
    batch.run_cells(np.stack([structure.mass]), np.stack([structure.damping]),
                    np.stack([structure.stiffness]), *cells)  # writable, as a sweep stacks them
names = ("prepare_states_kernel", "run_prepared_states", "run_prepared_cells")
print(json.dumps({name: len(getattr(batch, name).signatures) for name in names}))
"""


@pytest.mark.slow
def test_batch_entry_points_share_one_compilation_per_dimension(tmp_path: Path) -> None:
    # run_states and prepare_states are Python functions that give every argument, and
    # run_cells copies read-only matrices, so a basin's own path, direct calls with or without
    # the defaults and a Dask worker's run_states load one compilation (numba types arrays by
    # dtype, dimensions and layout, so 1 and 2 DOF share it); before, each such call compiled
    # the run loop again (prepare_states without its defaults, run_states, read-only matrices)
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    done = subprocess.run([sys.executable, "-c", BATCH_SCRIPT], capture_output=True, text=True,
                          check=True, timeout=1800, env=env)
    counts = json.loads(done.stdout.splitlines()[-1])
    assert counts == {"prepare_states_kernel": 1, "run_prepared_states": 1, "run_prepared_cells": 1}
