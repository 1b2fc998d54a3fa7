"""Issue 32, point 4: Ctrl-C at any moment of any command is one line and exit code 130.

Before the fix a Ctrl-C while the command line was still importing (typer, the command's
module, numba, scipy) printed the import chain as a traceback (up to about 150 lines) and
ended the process by the signal; a Ctrl-C that library code turned into an exception of its
own (numba's ``SystemError``, a pool's error, a ``ValueError`` from a cleanup) was reported
as that exception; ``compile`` left its warm-up processes running; and ``map --config --csv``
wrote its table straight into the target, so an interrupted write left half a table.

Each test below runs the real command in a subprocess with SIGINT at its default (a
terminal's Ctrl-C) and lands a real SIGINT at a chosen moment: from outside after a marker
file says the phase has begun, or from inside, sent by a small patch to the process itself
(``os.kill``) in the middle of an import or a write, so that the moment is exact. Python's
own start-up (before any stickslip code runs, about 0.05 s) is the one window no command
line can cover.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"
RECORD = ROOT / "examples" / "rig_record.csv"
SLIDEWAY = ROOT / "examples" / "slideway" / "machine.toml"
ABORTED = "stickslip: aborted (Ctrl-C)"

#: Run in the child before the command: ``FAULT`` (Python source, may be empty) installs the
#: patch that makes the moment; then the command line itself.
CHILD = """
import errno, importlib, os, signal, sys, time

def patch(module, name, fault):
    owner = importlib.import_module(module)
    if "." in name:
        owner_name, name = name.split(".")
        owner = getattr(owner, owner_name)
    original = getattr(owner, name)
    calls = [0]
    def patched(*args, **kwargs):
        calls[0] += 1
        return fault(original, calls[0], *args, **kwargs)
    setattr(owner, name, patched)

def sigint():
    os.kill(os.getpid(), signal.SIGINT)
    time.sleep(30)  # the handler raises KeyboardInterrupt here, at once

def half_written(path, how):
    with open(path, "wb") as fh:
        fh.write(b"half a file")
    if how == "sigint":
        sigint()
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))  # as write() raises it: no file name

FAULT
sys.argv[0] = "stickslip"
from stickslip.cli.main import run
run()
"""


def _start(args: list[str], cwd: Path, fault: str = "") -> subprocess.Popen[str]:
    return subprocess.Popen(
        [sys.executable, "-c", CHILD.replace("FAULT", fault), *args], cwd=cwd,
        env=dict(os.environ, PYTHONPATH=str(SRC)), text=True,
        stdout=subprocess.PIPE, stderr=subprocess.PIPE,
        # a terminal's Ctrl-C: SIGINT with Python's own handler (a background job ignores it)
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )


def _finish(process: subprocess.Popen[str], timeout: float = 600.0) -> tuple[int, str, str]:
    out, err = process.communicate(timeout=timeout)
    return process.returncode, out, err


def _check_aborted(code: int, out: str, err: str) -> None:
    assert "Traceback" not in err, err
    assert code == 130, (code, err)
    assert err.strip().splitlines() == [ABORTED], err
    assert out == ""


def _leftovers(folder: Path) -> list[Path]:
    """Temporary files of an atomic write (``stickslip.io.atomic.TMP_MARK``) left in ``folder``."""
    from stickslip.io.atomic import TMP_MARK

    return [p for p in folder.rglob("*") if TMP_MARK in p.name]


# -- while the command line starts ----------------------------------------------------------

#: Imports on the way to a running ``simulate``, in order: the command line's own (typer),
#: the command's module, numba (the compile watch, after parsing), the engine's analysis.
STARTUP_IMPORTS = ["typer", "stickslip.cli.simulate_command", "numba", "stickslip.analysis.simulation"]


@pytest.mark.parametrize("module", STARTUP_IMPORTS)
def test_ctrl_c_while_importing(module: str, tmp_path: Path) -> None:
    # SIGINT arrives while ``module`` is being imported (an import hook sends it when the
    # import starts): a traceback of the import chain before the fix, for ``typer`` and the
    # command's module (they were imported outside the command line's error handling)
    hook = f"""
class Hook:
    def find_spec(self, name, path=None, target=None):
        if name == {module!r}:
            sys.meta_path.remove(self)
            os.kill(os.getpid(), signal.SIGINT)
        return None
sys.meta_path.insert(0, Hook())
"""
    process = _start(["simulate", "--lam", "3", "--zeta", "0.1", "--json"], tmp_path, hook)
    _check_aborted(*_finish(process))


# -- library code that turns Ctrl-C into another error --------------------------------------

@pytest.mark.parametrize("error", [RuntimeError, ValueError, OSError])
def test_ctrl_c_turned_into_another_error_is_still_ctrl_c(
        error: type[Exception], monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str]) -> None:
    # a worker pool, a solver or a cleanup handler that catches the KeyboardInterrupt and
    # raises an error of its own, with no link to it (a ValueError was reported as
    # "error: ...", exit 2; a RuntimeError as a traceback)
    import stickslip.analysis.simulation as simulation

    from .cli_helpers import run_cli

    def interrupted(*args: object, **kwargs: object) -> None:
        caught = False
        try:
            signal.raise_signal(signal.SIGINT)
        except KeyboardInterrupt:
            caught = True
        assert caught, "the command line's SIGINT handler raises KeyboardInterrupt"
        raise error("the worker pool stopped")

    monkeypatch.setattr(simulation, "simulate", interrupted)
    before = signal.getsignal(signal.SIGINT)
    code, out, err = run_cli(["simulate", "--lam", "1", "--zeta", "0.1", "--json"], capsys)
    _check_aborted(code, out, err)
    assert signal.getsignal(signal.SIGINT) is before  # the handler is put back


def test_an_error_without_ctrl_c_is_still_an_error(monkeypatch: pytest.MonkeyPatch,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    # the other side: no SIGINT, the same ValueError is the usual one-line refusal, exit 2
    import stickslip.analysis.simulation as simulation

    from .cli_helpers import run_cli

    def refused(*args: object, **kwargs: object) -> None:
        raise ValueError("the worker pool stopped")

    monkeypatch.setattr(simulation, "simulate", refused)
    code, out, err = run_cli(["simulate", "--lam", "1", "--zeta", "0.1", "--json"], capsys)
    assert code == 2 and err.strip() == "stickslip: error: the worker pool stopped", err
    assert out == ""


# -- identify --bootstrap ---------------------------------------------------------------------

@pytest.mark.slow  # the fit before the bootstrap takes about 10 s on this project's machine
def test_ctrl_c_during_identify_bootstrap(tmp_path: Path) -> None:
    # the bootstrap's refits (scipy's least_squares over the numba engine): a marker file
    # says they have begun, then a real SIGINT from outside
    marker = tmp_path / "bootstrap-started"
    mark = f"""
def started(original, n, *args, **kwargs):
    open({str(marker)!r}, "w").close()
    return original(*args, **kwargs)
patch("stickslip.analysis.identification.record_fit", "bootstrap_intervals", started)
"""
    process = _start(["identify", str(RECORD), "--mass", "1 kg", "--load", "100 N", "--speed",
                      "5 cm/s", "--bootstrap", "2000", "--plot", "fit.png"], tmp_path, mark)
    deadline = time.monotonic() + 300.0
    while not marker.exists():
        assert process.poll() is None, process.communicate()
        assert time.monotonic() < deadline, "the bootstrap did not start in time"
        time.sleep(0.05)
    time.sleep(1.0)  # inside a refit
    process.send_signal(signal.SIGINT)
    _check_aborted(*_finish(process))
    assert not (tmp_path / "fit.png").exists() and not _leftovers(tmp_path)


# -- compile ----------------------------------------------------------------------------------

def _children(pid: int) -> list[int]:
    """Processes whose parent is ``pid`` (from /proc)."""
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            # pid (comm) state ppid ...: comm may hold spaces, so split after its ')'
            if int(stat.rsplit(")", 1)[1].split()[1]) == pid:
                found.append(int(entry.name))
    return found


def _alive(pid: int) -> bool:
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat.rsplit(")", 1)[1].split()[0] != "Z"


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads processes from /proc")
def test_ctrl_c_ends_compiles_warm_up_processes(tmp_path: Path) -> None:
    # SIGINT to `compile` alone (not to its process group): before the fix its warm-up
    # processes went on running after it had exited
    process = _start(["compile", "--jobs", "2"], tmp_path)
    deadline = time.monotonic() + 120.0
    while len(workers := _children(process.pid)) < 2:
        assert process.poll() is None, process.communicate()
        assert time.monotonic() < deadline, "compile started no warm-up process"
        time.sleep(0.05)
    process.send_signal(signal.SIGINT)
    code, out, err = _finish(process, timeout=60.0)
    # compile's own progress lines come first (what it does, each family ready), then the one line
    lines = err.strip().splitlines()
    assert all(line.startswith("stickslip compile: ") for line in lines[:-1]), err
    _check_aborted(code, out, lines[-1])
    assert not [pid for pid in workers if _alive(pid)], "warm-up processes left running"


# -- outputs: none half-written ---------------------------------------------------------------

MAP = ["map", "--lam", "1:5:3", "--zeta", "0.05:0.2:3", "--dva", "optimal", "--out", "m.nc"]
OPERATING_MAP = ["map", "--config", str(SLIDEWAY), "--speed", "log:1e-4:0.1:4", "--load",
                 "100:1000:3", "--out", "vw.nc"]
IDENTIFY = ["identify", str(RECORD), "--mass", "1 kg", "--load", "100 N", "--speed", "5 cm/s"]

#: (command, output flag, file, the function that writes it, its path argument's position)
WRITES = {
    "map --csv": (MAP, "--csv", "m.csv", "stickslip.io.csv", "_cell", None),
    "map --plot": (MAP, "--plot", "m.png", "matplotlib.figure", "Figure.savefig", 1),
    "map --config --csv": (OPERATING_MAP, "--csv", "vw.csv", "pandas", "DataFrame.to_csv", 1),
    "map --config --plot": (OPERATING_MAP, "--plot", "vw.png", "matplotlib.figure", "Figure.savefig", 1),
    "identify --plot": (IDENTIFY, "--plot", "fit.png", "matplotlib.figure", "Figure.savefig", 1),
}


def _write_fault(module: str, name: str, position: int | None, how: str) -> str:
    if position is None:  # a row-by-row writer: stop it after 20 cells
        action = "sigint()" if how == "sigint" else \
            "raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))"
        return f"""
def fault(original, n, *args, **kwargs):
    if n == 20:
        {action}
    return original(*args, **kwargs)
patch({module!r}, {name!r}, fault)
"""
    return f"""
def fault(original, n, *args, **kwargs):
    half_written(args[{position}], {how!r})
patch({module!r}, {name!r}, fault)
"""


@pytest.mark.parametrize("how", ["sigint", "disk full"])
@pytest.mark.parametrize("case", [
    "map --csv", "map --plot", "map --config --csv",
    pytest.param("map --config --plot", marks=pytest.mark.slow),
    pytest.param("identify --plot", marks=pytest.mark.slow),
])
def test_an_interrupted_or_failed_write_leaves_the_old_file(case: str, how: str,
                                                           tmp_path: Path) -> None:
    # Ctrl-C or a full disk in the middle of writing the table or the figure: the file that
    # was there before is kept as it was (--overwrite replaces it only once the new one is
    # complete), and no temporary file is left; before the fix `map --config --csv` wrote
    # straight into the target
    args, flag, name, module, function, position = WRITES[case]
    target = tmp_path / name
    target.write_bytes(b"the previous run's file")
    process = _start([*args, flag, name, "--overwrite", "--json"], tmp_path,
                     _write_fault(module, function, position, how))
    code, out, err = _finish(process)
    if how == "sigint":
        _check_aborted(code, out, err)
    else:
        assert "Traceback" not in err and code == 2, (code, err)
        assert err.strip().splitlines() == [f"stickslip: error: {name}: No space left on device"], err
    assert target.read_bytes() == b"the previous run's file"
    assert not _leftovers(tmp_path), _leftovers(tmp_path)


def test_ctrl_c_lost_in_a_finalizer_is_sent_again(monkeypatch: pytest.MonkeyPatch,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    # Python runs the SIGINT handler wherever the main thread is, a finalizer included; there
    # its KeyboardInterrupt is only printed ("Exception ignored in ... KeyboardInterrupt", seen
    # in a Dask map's weakref callback) and the command went on to finish with exit code 0
    import stickslip.analysis.simulation as simulation

    from .cli_helpers import run_cli

    class Finalised:
        def __del__(self) -> None:
            signal.raise_signal(signal.SIGINT)  # the handler's KeyboardInterrupt is lost here

    worked: list[float] = []

    def interrupted(*args: object, **kwargs: object) -> None:
        Finalised()  # dropped at once: __del__ runs, Ctrl-C is lost in it
        start = time.monotonic()
        while time.monotonic() < start + 10.0:  # the command's own work, bounded
            time.sleep(0.01)
        worked.append(time.monotonic() - start)  # reached only if Ctrl-C never came back

    monkeypatch.setattr(simulation, "simulate", interrupted)
    code, out, err = run_cli(["simulate", "--lam", "1", "--zeta", "0.1", "--json"], capsys)
    assert not worked, "the lost Ctrl-C was not sent again: the command worked on"
    assert "Exception ignored" not in err
    _check_aborted(code, out, err)
