"""``stickslip compile`` warms every command's kernels, the ``--config`` paths included (issue 32.5).

After ``make`` (which runs ``stickslip compile``) the first ``map --config`` still compiled for
59 s: the operating map handed the cell kernels read-only views of the structure's matrices,
which numba compiles as another signature (``Array(float64, 3, 'C', True)``) than the
writable stacks of ``map``, and the cycle proof of an N-DOF stick-slip cycle called
``kernel.linalg.expm`` from Python, which no warm-up run reached. The check is not a timing:
a subprocess runs the warm-up list of :mod:`stickslip.cli.compile_command` in one process,
notes every signature each stickslip numba dispatcher then holds (compiled or loaded from the
cache, whichever the cache's state), runs the commands a user runs on a machine file, and
lists the signatures they add. A signature added is a compile the warm-up did not do.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
SLIDEWAY = ROOT / "examples" / "slideway" / "machine.toml"

#: A 1-DOF machine with the Stribeck law of issue 32.1 (m 0.538 kg, k 6957 N/m, ...).
STRIBECK_MACHINE = """\
m = "0.538 kg"
k = "6957 N/m"
c = "5.746 N*s/m"
mu_s = 0.6
mu_k = 0.2
load = "10 N"
speed = "0.1 m/s"

[friction]
law = "stribeck"
stribeck_velocity = "0.1 m/s"
viscous = "0.02 s/m"
"""

#: What a user runs on a machine file after `make` (``{tmp}`` a scratch folder).
PROBES = [
    ["map", "--config", str(SLIDEWAY), "--speed", "log:1e-4:0.1:4", "--load", "100:1000:3",
     "--out", "{tmp}/probe-slideway.nc", "--json"],
    ["simulate", "--config", str(SLIDEWAY), "--json"],
    ["basin", "--config", str(SLIDEWAY), "--samples", "200", "--json"],
    ["map", "--config", "{tmp}/stribeck.toml", "--speed", "0.05:0.3:3", "--load", "5:20:3",
     "--out", "{tmp}/probe-stribeck.nc", "--json"],
    ["simulate", "--config", "{tmp}/stribeck.toml", "--json"],
]

SCRIPT = r"""
import contextlib, io, json, os, sys, tempfile
from pathlib import Path

from numba.core.dispatcher import Dispatcher

from stickslip.cli.compile_command import WARM_UP_MACHINE, WARM_UP_RUNS
from stickslip.cli.main import run


def signatures():
    held = {}
    for name, module in list(sys.modules.items()):
        if name.startswith("stickslip.") and module is not None:
            for value in vars(module).values():
                if isinstance(value, Dispatcher):
                    key = f"{value.py_func.__module__}.{value.py_func.__qualname__}"
                    held[key] = {str(s) for s in value.signatures}
    return held


def command(args, tmp):
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        try:
            run([a.format(tmp=tmp) for a in args])
        except SystemExit as exc:
            assert not exc.code, (args, exc.code)


probes, stribeck = json.loads(sys.argv[1]), sys.argv[2]
with tempfile.TemporaryDirectory() as tmp:
    os.chdir(tmp)
    Path(tmp, "machine.toml").write_text(WARM_UP_MACHINE)
    Path(tmp, "stribeck.toml").write_text(stribeck)
    for _, args in WARM_UP_RUNS:
        command(args, tmp)
    before = signatures()
    added = {}
    for args in probes:
        command(args, tmp)
        now = signatures()
        new = {k: sorted(v - before.get(k, set())) for k, v in now.items() if v - before.get(k, set())}
        added[" ".join(args[:2])] = new
print(json.dumps(added))
"""


@pytest.mark.slow  # the warm-up list and five machine-file runs in one process: minutes
def test_no_machine_file_command_compiles_after_the_warm_up() -> None:
    done = subprocess.run([sys.executable, "-c", SCRIPT, json.dumps(PROBES), STRIBECK_MACHINE],
                          capture_output=True, text=True, timeout=3600,
                          env=dict(os.environ, PYTHONPATH=str(ROOT / "src")))
    assert done.returncode == 0, done.stderr
    added = json.loads(done.stdout.strip().splitlines()[-1])
    assert added == {" ".join(p[:2]): {} for p in PROBES}, json.dumps(added, indent=1)


def test_the_operating_map_runs_its_cells_on_writable_stacks() -> None:
    # the read-only views it passed were a second numba signature of every cell kernel (a
    # 59 s compile after `stickslip compile`); `map`'s StructureSet.resolve stacks with
    # np.stack, writable and C-contiguous
    from stickslip.cli.machine_config import config_machine
    from stickslip.model.dva import DvaSpec
    from stickslip.sweep.executors import StructureSet
    from stickslip.sweep.operating_map import OperatingCells

    machine, _ = config_machine(SLIDEWAY)  # as `map --config` reads it
    cells = OperatingCells.of(machine, np.array([1e-3, 1e-2]), np.array([100.0, 1000.0]))
    reference = StructureSet.resolve(DvaSpec.parse("optimal"), [0.1])  # as `map` stacks
    for name in ("masses", "dampings", "stiffnesses"):
        stack = getattr(cells.structures, name)
        like = getattr(reference, name)
        assert stack.flags.writeable and stack.flags.c_contiguous, name
        assert (stack.dtype, stack.ndim, stack.flags.writeable, stack.flags.c_contiguous) == \
            (like.dtype, like.ndim, like.flags.writeable, like.flags.c_contiguous)


def test_the_compile_list_names_each_family_once_and_runs_a_machine_file() -> None:
    from stickslip.cli.compile_command import WARM_UP_RUNS

    families = [family for family, _ in WARM_UP_RUNS]
    assert len(families) == len(set(families))
    assert any("--config" in args for _, args in WARM_UP_RUNS)


def test_make_says_what_it_does_before_each_quiet_step() -> None:
    # a first `make` printed nothing for about 70 s (pip --quiet) and 116 s (compile): each
    # quiet step of the install recipe is announced by an echo line right before it
    recipe = (ROOT / "Makefile").read_text().split("$(STAMP): pyproject.toml\n", 1)[1].split("\n\n", 1)[0]
    lines = [line.strip() for line in recipe.splitlines()]
    for step in ('pip install --quiet -e ".[all]"', "stickslip compile"):
        at = next(i for i, line in enumerate(lines) if step in line)
        said = [line for line in lines[:at] if line.startswith("@echo")]
        assert said, f"nothing is said before {step!r}"
    pip = next(i for i, line in enumerate(lines) if "pip install --quiet --upgrade pip" in line)
    assert lines[pip - 1].startswith("@echo") and "pip" in lines[pip - 1]
    compile_at = next(i for i, line in enumerate(lines) if "stickslip compile" in line
                      and not line.startswith("@"))
    assert any("compil" in line for line in lines[pip:compile_at] if line.startswith("@echo"))
