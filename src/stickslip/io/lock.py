"""A lock file next to an output, so that two runs never write the same result at once.

``OUT.lock`` is created with ``O_CREAT | O_EXCL`` (atomic: exactly one process wins) and
holds the owner's PID. A second run finds it and refuses at once, naming the PID. A lock
whose process is gone (killed with ``kill -9``, a power cut) is stale and is taken over, so
a dead run cannot block the output forever. The lock is removed when the run ends, also on
an error or Ctrl-C.
"""

from __future__ import annotations

import os
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

#: A lock file without a PID yet is being written by its owner for this long at most; an
#: older empty file is left over from a crash and is stale.
_EMPTY_GRACE_S = 10.0


class LockHeld(ValueError):
    """Another live process holds the lock of this output."""


def lock_path(target: str | os.PathLike[str]) -> Path:
    """The lock file of ``target``: ``TARGET.lock`` next to it."""
    target = Path(target)
    return target.with_name(target.name + ".lock")


def _read_pid(path: Path) -> int | None:
    try:
        text = path.read_text().strip()
    except OSError:
        return None
    try:
        return int(text.split()[0]) if text else None
    except ValueError:
        return None


def _alive(pid: int) -> bool:
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True  # exists, owned by someone else
    return True


def _stale(path: Path) -> bool:
    pid = _read_pid(path)
    if pid is not None:
        return not _alive(pid)
    try:
        age = time.time() - path.stat().st_mtime
    except FileNotFoundError:
        return True
    return age > _EMPTY_GRACE_S


@contextmanager
def output_lock(target: str | os.PathLike[str]) -> Iterator[Path]:
    """Hold ``TARGET.lock`` while the block runs; raise :class:`LockHeld` if a live run has it.

    The folder of ``target`` must exist.
    """
    lock = lock_path(target)
    for _ in range(3):
        try:
            fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
        except FileExistsError:
            if not _stale(lock):
                pid = _read_pid(lock)
                owner = f"process {pid}" if pid is not None else "another process"
                raise LockHeld(
                    f"output {str(Path(target))!r} is being written by {owner} (lock file "
                    f"{str(lock)!r}); wait for it to finish, or delete the lock file if that "
                    "run is gone"
                ) from None
            lock.unlink(missing_ok=True)  # stale: its process is dead
            continue
        with os.fdopen(fd, "w") as fh:
            fh.write(f"{os.getpid()}\n")
        break
    else:
        raise LockHeld(f"could not take the lock file {str(lock)!r} (it keeps reappearing)")
    try:
        yield lock
    finally:
        if _read_pid(lock) == os.getpid():
            lock.unlink(missing_ok=True)
