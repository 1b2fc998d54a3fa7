"""Nothing is left behind by a refusal: undo the folders and resume store a command made.

A command checks what it can before it writes anything; a few refusals can only come once
writing has started (a friction table whose values go negative at the run's gamma, a Dask
scheduler that turns out not to answer). :class:`UndoOnRefusal` notes, before the command
creates anything, which folders and resume stores do not exist yet; if the command then ends
in a refusal (``ValueError``, which includes ``BadInput``, or ``OSError``), it removes the
resume stores it made that hold no finished chunk and the folders it made that are empty.
Finished chunks are never removed, and nothing is undone on Ctrl-C: that is work to resume.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from types import TracebackType


class UndoOnRefusal:
    """Context manager; create it BEFORE the command makes ``folders`` or ``stores``.

    Parameters
    ----------
    folders : sequence of Path
        Folders the command may create (with their missing parents).
    stores : sequence of Path
        Resume store folders (:class:`stickslip.sweep.store.ChunkStore`) it may create.
    """

    def __init__(self, folders: Sequence[Path], stores: Sequence[Path] = ()) -> None:
        self._new_folders: list[Path] = []
        for folder in folders:
            missing = []
            p = Path(folder).absolute()
            while not p.exists() and p != p.parent:
                missing.append(p)
                p = p.parent
            self._new_folders += missing  # deepest first
        self._new_stores = [Path(s) for s in stores if not Path(s).exists()]

    def __enter__(self) -> UndoOnRefusal:
        return self

    def __exit__(self, kind: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        from stickslip.io.lock import LockHeld

        if kind is None or not issubclass(kind, (ValueError, OSError)) or issubclass(kind, LockHeld):
            return  # success, Ctrl-C (work to resume) or another run's output: leave all
        from stickslip.sweep.store import discard_store, has_chunks

        for store in self._new_stores:
            if store.is_dir() and not has_chunks(store):
                discard_store(store)
        for folder in self._new_folders:
            try:
                folder.rmdir()  # only when empty
            except OSError:
                pass
