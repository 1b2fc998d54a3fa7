"""Start-up of the command line (issue 21, points 4 and 5).

A command loads only its own module and what it calls: ``stickslip simulate`` imports no map,
basin or design command, no sweep, plot or dataset library, and compiles (on a cold numba
cache) none of the map's or the basin's kernels. What numba compiles is told on stderr, as it
happens, never on stdout.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
import typer
from numba import njit

from stickslip.cli import main

#: Runs the command line, then lists on stderr's last line every module it loaded.
LOADED = """
import sys
from stickslip.cli.main import run
try:
    run(sys.argv[1:])
except SystemExit:
    pass
print(" ".join(sorted(sys.modules)), file=sys.stderr)
"""

SIMULATE = ["simulate", "--lam", "3", "--zeta", "0.1", "--json"]


def _loaded(argv: list[str], env: dict[str, str] | None = None) -> set[str]:
    done = subprocess.run([sys.executable, "-c", LOADED, *argv], capture_output=True, text=True,
                          check=True, timeout=900, env=env)
    return set(done.stderr.splitlines()[-1].split())


def test_command_modules_list_every_command_with_the_module_that_defines_it() -> None:
    commands = typer.main.get_command(main.build_app()).commands  # type: ignore[attr-defined]
    assert list(commands) == list(main.COMMAND_MODULES)  # the order of ``stickslip --help``
    for name, command in commands.items():
        defined_in = command.callback.__wrapped__.__module__
        assert defined_in == f"stickslip.cli.{main.COMMAND_MODULES[name]}", name


def test_a_command_is_registered_alone_and_an_unknown_word_gets_them_all() -> None:
    alone = typer.main.get_command(main.build_app("simulate")).commands  # type: ignore[attr-defined]
    assert list(alone) == ["simulate"]
    every = typer.main.get_command(main.build_app("simulat")).commands  # type: ignore[attr-defined]
    assert list(every) == list(main.COMMAND_MODULES)  # click can then suggest "simulate"


def test_simulate_loads_no_other_command_no_sweep_and_no_dataset_or_plot_library() -> None:
    loaded = _loaded([*SIMULATE[:-1], "--t-max", "50", "--json"])
    assert {"stickslip.cli.simulate_command", "stickslip.kernel.engine"} <= loaded
    unneeded = {"stickslip.cli.map_commands", "stickslip.cli.basin_command",
                "stickslip.cli.design_command", "stickslip.cli.identify_command", "stickslip.sweep",
                "stickslip.kernel.batch", "stickslip.kernel.certificate", "stickslip.plot",
                "xarray", "pandas", "matplotlib", "dask",
                # typer >= 0.25 converts every option with a pydantic TypeAdapter, 0.1-0.2 s of a
                # warm simulate's 1 s budget (issue 21.4): pyproject.toml holds typer below 0.25
                "pydantic"}
    assert not unneeded & loaded


@pytest.mark.parametrize("argv", [["--help"], ["simulate", "--help"], ["--version"],
                                  ["simulate", "--lam", "x", "--zeta", "0.1", "--json"]])
def test_help_version_and_refused_input_load_no_numba(argv: list[str]) -> None:
    loaded = _loaded(argv)
    assert "numba" not in loaded  # numba is imported (and compiles are watched) after parsing
    # a command's help needs that command alone; the main help lists them all
    assert ("stickslip.cli.map_commands" in loaded) == (argv[0] != "simulate")


def test_every_command_but_the_numba_free_ones_runs_under_a_compile_watch() -> None:
    watching = main.watching_compiles(print, announced=False).__code__
    for info in main.build_app().registered_commands:
        watched = getattr(info.callback, "__code__", None) is watching
        assert watched == (info.name not in main.NUMBA_FREE_COMMANDS), info.name


def _probe(module: str) -> object:
    """A fresh njit function (no cache, so its first call of each signature compiles) of ``module``."""
    namespace: dict[str, object] = {"__name__": module}
    exec("def probe(x):\n    return x + 1\n", namespace)
    return njit(namespace["probe"])  # type: ignore[call-overload]


def test_the_first_run_notice_says_roughly_how_long_each_command_compiles() -> None:
    # bench_startup.py --cold simulate,map,basin on 2 cores: 42 s, 78 s, 115 s
    assert main.first_run_notice("simulate") == main.FIRST_RUN_NOTICE
    assert "about a minute" in main.first_run_notice("map")
    assert "about two minutes" in main.first_run_notice("basin")
    assert set(main.FIRST_RUN_DURATION) <= main.ENGINE_COMMANDS


def test_a_compile_is_announced_once_and_summed_up_on_stderr(capsys: pytest.CaptureFixture[str]) -> None:
    watch = main.CompileWatch(announced=False)
    try:
        probe = _probe("stickslip._compile_probe")
        assert probe(1) == 2 and probe(2.0) == 3.0  # type: ignore[operator]  # two signatures
    finally:
        watch.close()
    out, err = capsys.readouterr()
    assert out == ""
    lines = err.splitlines()
    assert lines[0] == main.FIRST_RUN_NOTICE and len(lines) == 2
    assert re.fullmatch(r"stickslip: compiled 1 numba kernels \(2 signatures\) in \d+ s; "
                        r"they are cached for later runs", lines[1])
    _probe("stickslip._compile_probe")(1)  # type: ignore[operator]  # closed: no longer listening
    assert capsys.readouterr() == ("", "")


def test_no_second_notice_and_nothing_for_code_outside_the_package(
        capsys: pytest.CaptureFixture[str]) -> None:
    watch = main.CompileWatch(announced=True)  # the cache check has said it already
    try:
        _probe("stickslip._compile_probe")(1)  # type: ignore[operator]
    finally:
        watch.close()
    assert capsys.readouterr()[1].startswith("stickslip: compiled 1 numba kernels (1 signatures)")
    watch = main.CompileWatch(announced=False)
    try:
        _probe("someone_else")(1)  # type: ignore[operator]
    finally:
        watch.close()
    assert capsys.readouterr() == ("", "")


def test_a_warm_simulate_prints_only_its_json() -> None:
    from stickslip import Slider, chain_structure, simulate

    simulate(chain_structure(0.1, ()), Slider(3.0))  # compiles, or loads the cache
    done = subprocess.run([sys.executable, "-c", "from stickslip.cli.main import run; run()", *SIMULATE],
                          capture_output=True, text=True, check=True, timeout=900)
    assert done.stderr == ""
    assert json.loads(done.stdout)["verdict"] == "stick-slip"


@pytest.mark.slow
def test_the_first_simulate_compiles_only_the_engine_and_says_so(tmp_path: Path) -> None:
    from stickslip import Slider, chain_structure, simulate

    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}  # an empty cache: a fresh install
    done = subprocess.run([sys.executable, "-c", "from stickslip.cli.main import run; run()", *SIMULATE],
                          capture_output=True, text=True, check=True, timeout=1800, env=env)
    payload = json.loads(done.stdout)  # exactly one JSON object on stdout
    expected = simulate(chain_structure(0.1, ()), Slider(3.0)).to_dict()
    assert (payload["verdict"], payload["period"]) == (expected["verdict"], expected["period"])
    lines = done.stderr.splitlines()
    assert lines[0] == main.FIRST_RUN_NOTICE and len(lines) == 2
    assert re.fullmatch(r"stickslip: compiled \d+ numba kernels \(\d+ signatures\) in \d+ s; "
                        r"they are cached for later runs", lines[1])
    compiled = {index.name.split(".")[0] for index in tmp_path.rglob("*.nbi")}
    assert "engine" in compiled
    assert not compiled & {"batch", "certificate"}  # the map's and the basin's kernels
