"""Resume store: finished chunks of a sweep on disk, so that a killed run loses nothing.

A store is a folder holding ``manifest.json`` (format, configuration fingerprint, the
configuration itself, chunk size, and a log of the runs that used it) and one
``chunk-NNNNNN.npz`` file per finished chunk (the engine's float and integer summaries of
its cells, tagged with the fingerprint). Every file is written to a temporary name and
renamed over the target (``os.replace``), so a run killed at any instant leaves either the
whole chunk or none of it.

A damaged file (a truncated, empty or corrupt chunk, a manifest that is not JSON or lacks a
key) is reported in one line (a :class:`StoreDamaged` warning) and computed again; a damaged
manifest discards the chunks too, since their layout cannot be trusted without it.

A store made for another configuration is never mixed into a run: opening it raises
:class:`StoreMismatch` unless ``overwrite=True``, which empties it first.
"""

from __future__ import annotations

import json
import os
import warnings
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.io.atomic import TMP_MARK, atomic_write
from stickslip.io.provenance import utc_now
from stickslip.kernel.engine import N_FLOAT, N_INT

STORE_FORMAT = "stickslip-map-store"
STORE_VERSION = 1
MANIFEST = "manifest.json"
#: Array names inside a chunk file (part of the store format of STORE_VERSION 1; ``save``
#: writes them by these names).
_FLOAT_KEY = "fout"
_INT_KEY = "iout"
_CHUNK_PREFIX = "chunk-"


class StoreMismatch(ValueError):
    """A resume store or output file holds results of a different configuration."""


class ChunkStore:
    """Finished chunks of one sweep configuration in a folder.

    Parameters
    ----------
    path : path-like
        The folder (created if missing).
    fingerprint : str
        Hash of the resolved configuration (:meth:`MapConfig.fingerprint`).
    configuration : dict
        The resolved configuration, recorded in the manifest for humans.
    n_cells : int
        Number of cells of the sweep.
    chunk_size : int
        Cells per chunk for a new store. An existing store keeps the chunk size it was
        made with (the result does not depend on it), see :attr:`chunk_size`.
    overwrite : bool
        Empty a store of another configuration instead of raising :class:`StoreMismatch`.
    """

    def __init__(
        self,
        path: str | os.PathLike[str],
        fingerprint: str,
        configuration: dict[str, Any],
        n_cells: int,
        chunk_size: int,
        *,
        overwrite: bool = False,
    ) -> None:
        self.path = Path(path)
        self.fingerprint = fingerprint
        if self.path.exists() and not self.path.is_dir():
            raise ValueError(f"resume store {str(self.path)!r} exists and is not a folder")
        self.path.mkdir(parents=True, exist_ok=True)
        self._remove_temporaries()
        manifest = self._read_manifest()
        if manifest is _DAMAGED:
            # chunks cannot be trusted without the manifest's chunk size: recompute them
            self.clear()
            manifest = None
        if manifest is not None and manifest.get("fingerprint") != fingerprint:
            if not overwrite:
                raise StoreMismatch(
                    f"resume store {str(self.path)!r} belongs to another configuration "
                    f"(fingerprint {str(manifest.get('fingerprint'))[:12]}, this run "
                    f"{fingerprint[:12]}); pass --overwrite (overwrite=True) to discard it"
                )
            self.clear()
            manifest = None
        if manifest is None:
            if self.chunk_files() and not overwrite:
                raise StoreMismatch(
                    f"folder {str(self.path)!r} holds chunk files but no manifest; "
                    "pass --overwrite (overwrite=True) to discard them"
                )
            self.clear()
            manifest = {
                "format": STORE_FORMAT,
                "version": STORE_VERSION,
                "fingerprint": fingerprint,
                "n_cells": int(n_cells),
                "chunk_size": int(chunk_size),
                "created": utc_now(),
                "configuration": configuration,
                "runs": [],
            }
            self._write_manifest(manifest)
        if int(manifest["n_cells"]) != int(n_cells):
            raise StoreMismatch(f"resume store {str(self.path)!r} has a different number of cells")
        self._manifest = manifest

    @property
    def chunk_size(self) -> int:
        """Cells per chunk of this store."""
        return int(self._manifest["chunk_size"])

    @property
    def runs(self) -> list[dict[str, Any]]:
        """Log of the runs that used this store: start time, chunks loaded and computed."""
        return list(self._manifest["runs"])

    def chunk_path(self, index: int) -> Path:
        """File of chunk ``index``."""
        return self.path / f"{_CHUNK_PREFIX}{index:06d}.npz"

    def chunk_files(self) -> list[Path]:
        """Chunk files present in the folder."""
        return sorted(
            p for p in self.path.glob(f"{_CHUNK_PREFIX}*.npz") if TMP_MARK not in p.name
        )

    def load(self, index: int, size: int) -> tuple[NDArray[np.float64], NDArray[np.int64]] | None:
        """The summaries of a finished chunk, or None when it is missing or unusable."""
        path = self.chunk_path(index)
        if not path.exists():
            return None
        try:
            with np.load(path, allow_pickle=False) as data:
                fingerprint = str(data["fingerprint"])
                float_summary = np.array(data[_FLOAT_KEY], dtype=np.float64)
                int_summary = np.array(data[_INT_KEY], dtype=np.int64)
        except Exception as exc:  # truncated, empty, not a zip, missing arrays: all recomputed
            reason = " ".join(str(exc).split()) or type(exc).__name__
            _damaged(f"chunk file {str(path)!r} is unreadable ({reason}); computing it again")
            return None
        if fingerprint != self.fingerprint:
            raise StoreMismatch(f"chunk file {str(path)!r} belongs to another configuration")
        if float_summary.shape != (size, N_FLOAT) or int_summary.shape != (size, N_INT):
            _damaged(f"chunk file {str(path)!r} holds {float_summary.shape[0]} cells, expected {size}; "
                     "computing it again")
            return None
        return float_summary, int_summary

    def save(self, index: int, float_summary: NDArray[np.float64], int_summary: NDArray[np.int64]) -> None:
        """Write a finished chunk atomically."""
        atomic_write(
            self.chunk_path(index),
            lambda fh: np.savez(fh, fingerprint=np.array(self.fingerprint),
                                fout=float_summary, iout=int_summary),  # _FLOAT_KEY, _INT_KEY
        )

    def record_run(self, loaded: int, computed: int, backend: str) -> None:
        """Append a line to the manifest's run log (chunks loaded from disk and computed)."""
        self._manifest["runs"].append(
            {"finished": utc_now(), "chunks_loaded": int(loaded), "chunks_computed": int(computed),
             "backend": backend}
        )
        self._write_manifest(self._manifest)

    def clear(self) -> None:
        """Remove the manifest and every chunk file (only files this store writes)."""
        for p in self.chunk_files():
            p.unlink()
        manifest = self.path / MANIFEST
        if manifest.exists():
            manifest.unlink()

    def remove(self) -> None:
        """Delete the store: its files, then the folder if nothing else is in it."""
        discard_store(self.path)

    def _read_manifest(self) -> Any:
        """The manifest; None when there is none; :data:`_DAMAGED` (after a warning) when it
        cannot be used: not JSON, truncated, or a key or value missing or of the wrong type."""
        path = self.path / MANIFEST
        if not path.exists():
            return None
        try:
            manifest = json.loads(path.read_text())
        except (OSError, ValueError) as exc:
            reason = " ".join(str(exc).split()) or type(exc).__name__
            _damaged(f"resume store manifest {str(path)!r} is unreadable ({reason}); "
                     "starting the store afresh")
            return _DAMAGED
        if isinstance(manifest, dict) and "format" in manifest and manifest["format"] != STORE_FORMAT:
            raise StoreMismatch(f"{str(path)!r} is not a stickslip resume store manifest")
        problem = _manifest_problem(manifest)
        if problem:
            _damaged(f"resume store manifest {str(path)!r} is damaged ({problem}); "
                     "starting the store afresh")
            return _DAMAGED
        return manifest

    def _write_manifest(self, manifest: dict[str, Any]) -> None:
        text = json.dumps(manifest, indent=1)
        atomic_write(self.path / MANIFEST, lambda fh: fh.write(text.encode()))

    def _remove_temporaries(self) -> None:
        for p in self.path.glob(f"*{TMP_MARK}*"):
            p.unlink(missing_ok=True)


class StoreDamaged(UserWarning):
    """A resume store file was damaged (truncated, empty, corrupt); it is computed again."""


#: Marker returned by ``_read_manifest`` for a manifest that exists but cannot be used.
_DAMAGED: Any = object()

#: Keys of a manifest and the types their values must have.
_MANIFEST_KEYS: dict[str, type | tuple[type, ...]] = {
    "format": str,
    "version": int,
    "fingerprint": str,
    "n_cells": int,
    "chunk_size": int,
    "runs": list,
}


def _manifest_problem(manifest: Any) -> str:
    """What is wrong with a parsed manifest, or ``""``."""
    if not isinstance(manifest, dict):
        return f"a JSON {type(manifest).__name__}, not an object"
    for key, kind in _MANIFEST_KEYS.items():
        if key not in manifest:
            return f"missing key {key!r}"
        value = manifest[key]
        if not isinstance(value, kind) or isinstance(value, bool):
            return f"key {key!r} has the wrong type"
    if manifest["chunk_size"] < 1 or manifest["n_cells"] < 0:
        return "chunk_size or n_cells out of range"
    return ""


def _damaged(message: str) -> None:
    """Report a damaged store file: one line (a warning, not an exception)."""
    warnings.warn(message, StoreDamaged, stacklevel=3)


def has_chunks(path: str | os.PathLike[str]) -> bool:
    """True when the store folder ``path`` holds at least one finished chunk file."""
    return any(p for p in Path(path).glob(f"{_CHUNK_PREFIX}*.npz") if TMP_MARK not in p.name)


def discard_store(path: str | os.PathLike[str]) -> None:
    """Delete a store folder's manifest, chunk and temporary files, then the folder if empty.

    Files that a store does not write are left alone (and so is the folder holding them).
    """
    folder = Path(path)
    if not folder.is_dir():
        return
    for p in [*folder.glob(f"{_CHUNK_PREFIX}*.npz"), *folder.glob(f"*{TMP_MARK}*"),
              folder / MANIFEST]:
        p.unlink(missing_ok=True)
    try:
        folder.rmdir()
    except OSError:
        pass  # the folder holds files that are not ours
