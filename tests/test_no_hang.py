"""Issue 12, point 1: overflowing inputs end at once with one line, never spin forever.

Each case runs the real ``stickslip`` command as a subprocess under a short timeout (start-up
included): before the fix these spun at 100 % CPU inside the matrix exponential.
"""

from __future__ import annotations

import contextlib
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from stickslip.kernel.linalg import MAX_SQUARINGS_EXPM, expm
from tests.cli_helpers import run_cli

TIMEOUT_S = 60

OVERFLOW_CASES = [
    ["simulate", "--lam", "5e307", "--zeta", "0.1", "--t-max", "10"],
    ["simulate", "--lam", "5e307", "--zeta", "0.1", "--t-max", "10", "--initial", "0,1"],
    ["simulate", "--lam", "1", "--zeta", "0.1", "--gamma", "1e308"],
    ["simulate", "--lam", "1", "--zeta", "1e308"],
    ["simulate", "--lam", "1", "--zeta", "0.1", "--dva", "1,1e200,0.1"],
    ["simulate", "--lam", "1", "--zeta", "0.1", "--dva", "1,1,0.1", "--k-scale", "1e308"],
    ["map", "--lam", "1e308", "--zeta", "0.1", "--out", "{tmp}/m.nc"],
    ["map", "--lam", "1", "--zeta", "0.1", "--gamma", "1e308", "--out", "{tmp}/m.nc"],
    ["boundary", "--gamma", "1e308", "--zeta", "0.1"],
    ["boundary", "--lam-max", "1e308", "--zeta", "0.1"],
]


@pytest.mark.parametrize("args", OVERFLOW_CASES, ids=lambda a: " ".join(a[:3]))
def test_overflowing_input_is_refused_quickly(args: list[str], tmp_path: Path) -> None:
    argv = [a.format(tmp=tmp_path) for a in args]
    proc = subprocess.run(
        [sys.executable, "-c", "from stickslip.cli.main import run; run()", *argv],
        capture_output=True, text=True, timeout=TIMEOUT_S, cwd=tmp_path,
    )
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 2, proc.stderr
    assert len(lines) == 1 and "Traceback" not in proc.stderr, proc.stderr
    assert "supported range" in lines[0] or "overflow" in lines[0]
    assert list(tmp_path.iterdir()) == []  # nothing written, no resume store


@pytest.mark.parametrize("value", [np.inf, -np.inf, np.nan, 1e308])
def test_expm_of_non_finite_matrix_ends_with_nan(value: float) -> None:
    # 3 x 1e308 sums to an infinite norm: before the fix `while norm > 0.5` never ended
    a = np.full((3, 3), value)
    assert np.all(np.isnan(expm(a)))


def test_expm_of_huge_finite_matrix_ends() -> None:
    # the largest finite norm needs about 1025 halvings, below the bound
    assert MAX_SQUARINGS_EXPM > 1025
    out = expm(np.array([[-1e300]]))
    assert out.shape == (1, 1) and np.isfinite(out).all()


# --- point 7: a Dask scheduler address that is wrong, silent or not a scheduler -------------

def _listener() -> socket.socket:
    srv = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    srv.bind(("127.0.0.1", 0))  # loopback only
    srv.listen(8)
    return srv


def _map_args(tmp_path: Path, port: int) -> list[str]:
    return ["map", "--lam", "1", "--zeta", "0.1", "--out", str(tmp_path / "m.nc"),
            "--scheduler", f"tcp://127.0.0.1:{port}", "--scheduler-timeout", "2", "--json"]


def _assert_refused(tmp_path: Path, args: list[str], capsys: pytest.CaptureFixture[str],
                    needle: str, bound_s: float) -> None:
    started = time.monotonic()
    code, out, err = run_cli(args, capsys)
    elapsed = time.monotonic() - started
    assert code == 2 and out == "", err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err and needle in lines[0], err
    assert elapsed < bound_s, elapsed
    assert list(tmp_path.iterdir()) == []  # no OUT.parts/manifest.json, no lock file


def test_silent_scheduler_fails_within_the_timeout(tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("distributed")
    out_dir = tmp_path / "run"
    out_dir.mkdir()
    with _listener() as srv:  # accepts connections (kernel backlog) and never answers
        port = srv.getsockname()[1]
        _assert_refused(out_dir, _map_args(out_dir, port), capsys, "no Dask handshake within 2 s",
                        bound_s=8.0)


def test_closed_port_fails_at_once(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("distributed")
    with _listener() as srv:
        port = srv.getsockname()[1]
    _assert_refused(tmp_path, _map_args(tmp_path, port), capsys, "cannot reach the dask scheduler",
                    bound_s=4.0)


def test_peer_that_is_not_a_scheduler_is_named(tmp_path: Path,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("distributed")

    def answer_http(srv: socket.socket) -> None:
        with contextlib.suppress(OSError):
            conn, _ = srv.accept()
            with conn:
                conn.sendall(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n")
                time.sleep(3)

    with _listener() as srv:
        thread = threading.Thread(target=answer_http, args=(srv,), daemon=True)
        thread.start()
        _assert_refused(tmp_path, _map_args(tmp_path, srv.getsockname()[1]), capsys,
                        "not a Dask scheduler", bound_s=4.0)


def test_scheduler_timeout_default_and_option_check(tmp_path: Path,
                                                    capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("distributed")
    from stickslip.sweep.executors import SCHEDULER_TIMEOUT_S, scheduler_timeout

    assert scheduler_timeout() == SCHEDULER_TIMEOUT_S == 10.0
    args = _map_args(tmp_path, 9)
    args[args.index("--scheduler-timeout") + 1] = "nan"
    code, _, err = run_cli(args, capsys)
    assert code == 2 and "--scheduler-timeout" in err and len(err.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == []
