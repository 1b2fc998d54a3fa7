"""Issue 22, point 5: Ctrl-C inside a compiled kernel exits 130 with one line, keeping finished work.

A numba kernel holds the GIL, so Python sees SIGINT only when the kernel returns; before the
fix the ``KeyboardInterrupt`` surfaced inside numba's dispatcher as a 59-line traceback ending
``SystemError: CPUDispatcher(...) returned a result with an exception set`` (and during the
first compile it could be swallowed by a finalizer while the run went on). Each test starts
the real command in a subprocess (SIGINT restored to its default, as in a terminal), waits
until a chunk is in the resume store -- so the kernels are compiled and the next chunk is
running -- sends SIGINT, and checks: exit code 130, exactly one line on stderr, nothing on
stdout, no output file, the lock released, the finished chunks kept; the same command run
again resumes from them (its report counts them as loaded) and finishes.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
RUN = "import sys; from stickslip.cli.main import run; sys.argv[0] = 'stickslip'; run()"


def _start(args: list[str], cwd: Path, env: dict[str, str] | None = None) -> subprocess.Popen[str]:
    environment = dict(os.environ, PYTHONPATH=str(SRC), **(env or {}))
    return subprocess.Popen(
        [sys.executable, "-c", RUN, *args], cwd=cwd, env=environment, text=True,
        stdout=subprocess.PIPE, stderr=subprocess.PIPE,
        # a terminal's Ctrl-C: SIGINT with Python's own handler (a background job ignores it)
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )


def _wait_for(predicate: object, process: subprocess.Popen[str], limit: float) -> None:
    deadline = time.monotonic() + limit
    while not predicate():  # type: ignore[operator]
        assert process.poll() is None, f"finished before the interrupt: {process.communicate()}"
        assert time.monotonic() < deadline, "no chunk finished in time"
        time.sleep(0.02)


def _interrupt(process: subprocess.Popen[str]) -> tuple[int, str, str]:
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=600)
    return process.returncode, out, err


def _check_aborted(code: int, out: str, err: str) -> None:
    assert "Traceback" not in err and "SystemError" not in err, err
    assert code == 130, err
    assert err.strip().splitlines() == ["stickslip: aborted (Ctrl-C)"], err
    assert out == ""


def _chunks(store: Path) -> list[Path]:
    return sorted(store.glob("chunk-*.npz"))


# long chunks: --t-max 20000 and one thread, so SIGINT lands inside a kernel call
BASIN = ["basin", "--lam", "2.5", "--zeta", "0.1", "--samples", "8192", "--t-max", "20000",
         "--workers", "1", "--out", "run", "--json"]
MAP = ["map", "--lam", "0.2:10:120", "--zeta", "0:0.3:120", "--t-max", "20000", "--workers", "1",
       "--chunk-size", "300", "--out", "m.nc", "--json"]


@pytest.mark.parametrize(("args", "store", "outputs"), [
    (BASIN, "run/basin.parts", ["run/labels.csv", "run/basin.nc"]),  # two chunks of 4096 states
    pytest.param(MAP, "m.nc.parts", ["m.nc"], marks=pytest.mark.slow),
])
def test_ctrl_c_in_a_long_chunk(args: list[str], store: str, outputs: list[str], tmp_path: Path) -> None:
    process = _start(args, tmp_path)
    _wait_for(lambda: len(_chunks(tmp_path / store)) >= 1, process, 300.0)
    code, out, err = _interrupt(process)
    _check_aborted(code, out, err)
    kept = _chunks(tmp_path / store)
    assert kept, "finished chunks must stay for resume"
    assert not any((tmp_path / name).exists() for name in outputs)
    assert not list(tmp_path.rglob("*.lock"))
    # the same command again resumes from what was kept
    again = _start(args, tmp_path)
    out, err = again.communicate(timeout=900)
    assert again.returncode == 0, err
    assert json.loads(out)["chunks"]["loaded"] >= len(kept)
    assert all((tmp_path / name).exists() for name in outputs)
    assert not (tmp_path / store).exists()


@pytest.mark.slow
def test_ctrl_c_in_basin_map(tmp_path: Path) -> None:
    # no resume store: nothing written, the lock released
    # 60 cells x 20,000 samples under a Stribeck law on one thread: 73 s of work on this
    # project's machine (the Coulomb law's start-up shortcut does it in 5.6 s since issue 21),
    # so the signal lands in a cell's chunk
    process = _start(["basin-map", "--lam", "0.5:6:10", "--zeta", "0.05:0.3:6", "--samples", "20000",
                      "--t-max", "20000", "--friction", "stribeck:vs=0.2", "--workers", "1",
                      "--out", "bm.nc", "--json"], tmp_path)
    time.sleep(15.0)
    assert process.poll() is None, process.communicate()
    code, out, err = _interrupt(process)
    _check_aborted(code, out, err)
    assert not (tmp_path / "bm.nc").exists() and not list(tmp_path.rglob("*.lock"))


@pytest.mark.slow
def test_ctrl_c_during_the_first_compile(tmp_path: Path) -> None:
    # an empty numba cache: the first kernel call compiles for a minute or more; SIGINT in the
    # middle of it is held until the compile and the chunk are done, then the chunk is kept
    cache = tmp_path / "numba-cache"
    cache.mkdir()
    args = ["basin", "--lam", "2.5", "--zeta", "0.1", "--samples", "8192", "--workers", "1",
            "--out", "run", "--json"]
    process = _start(args, tmp_path, {"NUMBA_CACHE_DIR": str(cache)})
    _wait_for(lambda: any(cache.rglob("*.nbi")), process, 600.0)  # compiling has begun
    assert not _chunks(tmp_path / "run" / "basin.parts")
    code, out, err = _interrupt(process)
    # the first-run notice came before the signal, and what was compiled is cached (said so)
    from stickslip.cli.main import first_run_notice

    lines = err.strip().splitlines()
    assert lines[0] == first_run_notice("basin"), err
    assert "about two minutes" in lines[0]  # a basin compiles the certificates too (115 s)
    assert all(line.startswith("stickslip: compiled ") for line in lines[1:-1]), err
    _check_aborted(code, out, lines[-1])
    assert _chunks(tmp_path / "run" / "basin.parts"), "the chunk being computed is kept"


@pytest.mark.parametrize("raised", ["dispatcher", "keyboard"])
def test_ctrl_c_anywhere_is_one_line(raised: str, monkeypatch: pytest.MonkeyPatch,
                                     capsys: pytest.CaptureFixture[str]) -> None:
    # outside the chunk loops (simulate, boundary, cycles) a Ctrl-C inside a kernel reaches the
    # command line as numba's SystemError caused by the KeyboardInterrupt, elsewhere as the
    # KeyboardInterrupt itself (which typer turns into exit code 130): both are one line, 130
    import stickslip.analysis.simulation as simulation

    from .cli_helpers import run_cli

    def interrupted(*args: object, **kwargs: object) -> None:
        if raised == "keyboard":
            raise KeyboardInterrupt
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt as exc:
            raise SystemError("CPUDispatcher(<function run>) returned a result with an exception "
                              "set") from exc

    monkeypatch.setattr(simulation, "simulate", interrupted)
    code, out, err = run_cli(["simulate", "--lam", "1", "--zeta", "0.1", "--json"], capsys)
    _check_aborted(code, out, err)


def test_deferred_sigint_records_and_restores() -> None:
    # the handler only records inside the block; the previous one is back afterwards. Python's
    # own handler is installed first: a run started in the background by a shell without job
    # control inherits SIGINT ignored, where deferred_sigint rightly leaves it alone
    from stickslip.kernel.interrupt import deferred_sigint

    inherited = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        before = signal.getsignal(signal.SIGINT)
        with deferred_sigint() as sigint:
            signal.raise_signal(signal.SIGINT)  # would raise KeyboardInterrupt with Python's handler
            assert sigint.caught
        assert signal.getsignal(signal.SIGINT) is before
    finally:
        signal.signal(signal.SIGINT, inherited)
    with pytest.raises(KeyboardInterrupt):
        sigint.raise_if_caught()
    sigint.raise_if_caught()  # once only


def test_deferred_sigint_leaves_an_ignored_sigint_alone() -> None:
    # a job started in the background without job control inherits SIGINT ignored: it stays so
    from stickslip.kernel.interrupt import deferred_sigint

    inherited = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        with deferred_sigint() as sigint:
            assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN
            signal.raise_signal(signal.SIGINT)
        assert not sigint.caught
        assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN
        sigint.raise_if_caught()  # nothing recorded, nothing raised
    finally:
        signal.signal(signal.SIGINT, inherited)
