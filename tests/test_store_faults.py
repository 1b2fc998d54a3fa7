"""Issue 12, point 5: a damaged resume store is reported in one line and recomputed.

Each test makes a store with a clean run, damages it (truncate, empty, delete or corrupt a
chunk; corrupt the manifest or drop one of its keys), runs again on it and checks that the
result is bit-identical to the clean run.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
import warnings
from collections.abc import Callable
from pathlib import Path

import pytest

from stickslip.sweep import OccurrenceMap, occurrence_map
from stickslip.sweep.execution import ExecutionOptions
from stickslip.sweep.store import MANIFEST, StoreDamaged
from tests.cli_helpers import run_cli
from tests.sweep_helpers import LAMS, ZETAS, assert_same_map


def _clean(tmp_path: Path) -> tuple[Path, OccurrenceMap]:
    store = tmp_path / "store"
    full = occurrence_map(LAMS, ZETAS, "none", execution=ExecutionOptions(chunk_size=4, store=store))
    assert len(list(store.glob("chunk-*.npz"))) == 8
    return store, full


def _truncate(p: Path) -> None:
    data = p.read_bytes()
    p.write_bytes(data[: len(data) // 2])


def _empty(p: Path) -> None:
    p.write_bytes(b"")


def _garbage(p: Path) -> None:
    p.write_bytes(b"PK\x03\x04 this is not a zip archive at all" * 10)


CHUNK_DAMAGE: dict[str, Callable[[Path], None]] = {
    "truncated": _truncate, "empty": _empty, "corrupt": _garbage, "deleted": Path.unlink,
}


@pytest.mark.parametrize("kind", sorted(CHUNK_DAMAGE))
def test_damaged_chunk_is_reported_and_recomputed(kind: str, tmp_path: Path) -> None:
    store, full = _clean(tmp_path)
    victim = sorted(store.glob("chunk-*.npz"))[3]
    CHUNK_DAMAGE[kind](victim)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        again = occurrence_map(LAMS, ZETAS, "none", execution=ExecutionOptions(chunk_size=4, store=store))
    damaged = [w for w in caught if issubclass(w.category, StoreDamaged)]
    if kind == "deleted":
        assert damaged == []  # a missing chunk is simply not done yet
    else:
        assert len(damaged) == 1 and victim.name in str(damaged[0].message)
        assert "\n" not in str(damaged[0].message)
    assert again.chunks_computed == 1 and again.chunks_loaded == 7
    assert_same_map(full.dataset, again.dataset)
    # the chunk was rewritten: a third run loads everything
    third = occurrence_map(LAMS, ZETAS, "none", execution=ExecutionOptions(chunk_size=4, store=store))
    assert third.chunks_computed == 0


def _drop_key(key: str) -> Callable[[Path], None]:
    def damage(p: Path) -> None:
        manifest = json.loads(p.read_text())
        del manifest[key]
        p.write_text(json.dumps(manifest))
    return damage


def _not_an_object(p: Path) -> None:
    p.write_text("[1, 2, 3]")


MANIFEST_DAMAGE: dict[str, Callable[[Path], None]] = {
    "truncated": _truncate,
    "empty": _empty,
    "not-an-object": _not_an_object,
    "no-n_cells": _drop_key("n_cells"),
    "no-chunk_size": _drop_key("chunk_size"),
    "no-runs": _drop_key("runs"),
    "no-fingerprint": _drop_key("fingerprint"),
}


@pytest.mark.parametrize("kind", sorted(MANIFEST_DAMAGE))
def test_damaged_manifest_is_reported_and_store_rebuilt(kind: str, tmp_path: Path) -> None:
    store, full = _clean(tmp_path)
    MANIFEST_DAMAGE[kind](store / MANIFEST)
    with pytest.warns(StoreDamaged, match="manifest") as caught:
        again = occurrence_map(LAMS, ZETAS, "none", execution=ExecutionOptions(chunk_size=4, store=store))
    assert len(caught) == 1
    assert_same_map(full.dataset, again.dataset)
    manifest = json.loads((store / MANIFEST).read_text())
    assert manifest["n_cells"] == 30 and manifest["fingerprint"] == full.fingerprint


def test_cli_resume_over_damaged_store_warns_once_and_completes(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # the store the CLI would resume: OUT.parts, made by an interrupted run of the same map
    out = tmp_path / "m.nc"
    store = tmp_path / "m.nc.parts"
    args = ["map", "--lam", "log:0.1:50:6", "--zeta", "0.01,0.05,0.1,0.2,0.4", "--out", str(out),
            "--chunk-size", "4", "--json"]
    occurrence_map("log:0.1:50:6", "0.01,0.05,0.1,0.2,0.4", "none",
                   execution=ExecutionOptions(chunk_size=4, store=store))
    _truncate(sorted(store.glob("chunk-*.npz"))[2])
    _empty(sorted(store.glob("chunk-*.npz"))[5])
    code, stdout, err = run_cli(args, capsys)
    assert code == 0, err
    lines = err.strip().splitlines()
    assert len(lines) == 2 and all(line.startswith("stickslip: warning: chunk file") for line in lines)
    payload = json.loads(stdout)
    assert payload["chunks"]["computed"] == 2 and payload["chunks"]["loaded"] == 6
    assert not store.exists()
    # a clean run of the same map gives the same file contents
    clean = tmp_path / "clean.nc"
    code, _, err = run_cli([*args[:6], str(clean), *args[7:]], capsys)
    assert code == 0, err
    assert_same_map(OccurrenceMap.from_netcdf(out).dataset, OccurrenceMap.from_netcdf(clean).dataset)


# --- point 6: two runs on the same --out --------------------------------------------------

def _stickslip(*args: str) -> list[str]:
    return [sys.executable, "-c", "from stickslip.cli.main import run; run()", *args]


def _lock_text(lock: Path) -> str:
    try:
        return lock.read_text().strip()
    except FileNotFoundError:
        return ""


def test_second_run_on_the_same_out_refuses_at_once(tmp_path: Path) -> None:
    out = tmp_path / "m.nc"
    lock = tmp_path / "m.nc.lock"
    args = ["map", "--lam", "log:0.1:50:80", "--zeta", "0.01:0.4:50", "--out", str(out),
            "--backend", "serial", "--chunk-size", "200", "--json"]
    first = subprocess.Popen(_stickslip(*args), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True)
    try:
        deadline = time.monotonic() + 120
        # the lock file is created (O_EXCL) a moment before its PID is written: wait for both
        while not _lock_text(lock) and first.poll() is None and time.monotonic() < deadline:
            time.sleep(0.01)
        os.kill(first.pid, signal.SIGSTOP)  # frozen while holding the lock: no race
        assert lock.read_text().split()[0] == str(first.pid)
        started = time.monotonic()
        second = subprocess.run(_stickslip(*args), capture_output=True, text=True, timeout=60)
        assert second.returncode == 2 and second.stdout == ""
        lines = second.stderr.strip().splitlines()
        assert len(lines) == 1 and f"process {first.pid}" in lines[0] and "lock" in lines[0]
        assert time.monotonic() - started < 30
        # the first run dies without cleaning up: its lock is stale and a new run takes it over
        os.kill(first.pid, signal.SIGKILL)
        first.wait(timeout=30)
    finally:
        if first.poll() is None:
            first.kill()
            first.wait()
    assert lock.exists()
    third = subprocess.run(_stickslip(*args), capture_output=True, text=True, timeout=300)
    assert third.returncode == 0, third.stderr
    assert json.loads(third.stdout)["n_cells"] == 4000
    assert not lock.exists() and out.exists()


def test_lock_of_a_live_process_is_respected_and_a_dead_one_taken_over(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "m.nc"
    lock = tmp_path / "m.nc.lock"
    args = ["map", "--lam", "0.5,2", "--zeta", "0.1", "--out", str(out), "--json"]
    sleeper = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    try:
        lock.write_text(f"{sleeper.pid}\n")
        code, stdout, err = run_cli(args, capsys)
        assert code == 2 and stdout == "" and len(err.strip().splitlines()) == 1
        assert str(sleeper.pid) in err and not out.exists()
        assert lock.read_text().strip() == str(sleeper.pid)  # not ours: left alone
    finally:
        sleeper.kill()
        sleeper.wait()
    code, stdout, err = run_cli(args, capsys)  # the PID is dead now: stale lock
    assert code == 0, err
    assert out.exists() and not lock.exists()


def test_lock_is_released_when_the_run_fails(tmp_path: Path,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "m.nc"
    store = tmp_path / "m.nc.parts"
    store.mkdir()
    (store / "chunk-000000.npz").write_bytes(b"stray")  # chunks but no manifest: refused
    code, _, err = run_cli(["map", "--lam", "0.5,2", "--zeta", "0.1", "--out", str(out)], capsys)
    assert code == 2 and "no manifest" in err
    assert not (tmp_path / "m.nc.lock").exists()
