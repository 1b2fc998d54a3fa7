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
