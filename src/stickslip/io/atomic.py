"""Atomic file writes: a reader never sees a half-written file, and nothing old is lost.

Every file stickslip writes (datasets, CSV tables, figures, reports, resume-store chunks) goes
through :func:`atomic_output`: the content is written to a temporary file next to the
target, flushed, given the mode the user's umask asks for, and renamed over the target
(``os.replace``, atomic on POSIX). A run killed at any instant leaves the old file (or none)
plus at most one temporary file whose name contains :data:`TMP_MARK`.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO, Any

from stickslip.model.user_file import is_input

#: Marker in the names of temporary files (so that a resume store can clean them up).
TMP_MARK = ".tmp-"


def _umask_mode() -> int:
    """The mode a plain ``open(..., "w")`` would give a new file: ``0o666 & ~umask``."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


@contextmanager
def atomic_output(target: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary path next to ``target``; rename it over ``target`` on success.

    Missing parent folders are created. On an exception (a full disk, a failed plot) the
    temporary file is removed and ``target`` is untouched. The new file gets the mode of the
    umask (``mkstemp`` alone would leave it readable by its owner only). An ``OSError`` of
    the write that names no file, or the temporary one, is raised again naming ``target``.
    """
    target = Path(target)
    if is_input(target):  # one of the command's own inputs: never replaced by its output
        raise ValueError(f"output {str(target)!r} is an input file of this command; name "
                         "another output file")
    # missing folders are made here, when writing starts: a command rejected during its
    # checks leaves none behind
    target.parent.mkdir(parents=True, exist_ok=True)
    handle, name = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}{TMP_MARK}",
                                suffix=target.suffix)
    os.close(handle)
    tmp = Path(name)
    try:
        yield tmp
        os.chmod(tmp, _umask_mode())
        os.replace(tmp, target)
    except OSError as exc:
        if exc.errno is None or exc.filename not in (None, name, tmp):
            raise
        # a failed write (a full disk) names no file or the temporary one: name the target
        raise OSError(exc.errno, exc.strerror or str(exc), str(target)) from exc
    finally:
        tmp.unlink(missing_ok=True)


def atomic_write(target: str | os.PathLike[str], write: Callable[[IO[bytes]], object]) -> None:
    """Write through ``write(fileobj)`` to a temporary file, flush it to disk, then rename."""
    with atomic_output(target) as tmp, open(tmp, "wb") as fh:
        write(fh)
        fh.flush()
        os.fsync(fh.fileno())


def atomic_write_text(target: str | os.PathLike[str], text: str) -> None:
    """Write ``text`` (UTF-8) to ``target`` atomically."""
    atomic_write(target, lambda fh: fh.write(text.encode("utf-8")))


def atomic_savefig(figure: Any, target: str | os.PathLike[str], **savefig_kwargs: Any) -> Path:
    """Save a matplotlib figure to ``target`` atomically (the format from the suffix)."""
    target = Path(target)
    fmt = target.suffix.lstrip(".").lower() or None
    with atomic_output(target) as tmp:
        figure.savefig(tmp, format=fmt, **savefig_kwargs)
    return target
