"""Shared pieces of the command line: input parsing, errors and JSON output.

The command line is a public contract (DESIGN.md section 5): invalid input prints one line
on stderr naming the value and why, exits with code 2, and writes no file.
"""

from __future__ import annotations

import json
import math
import sys
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

if TYPE_CHECKING:
    from stickslip.model.parameters import Foundation

EXIT_BAD_INPUT = 2


class BadInput(ValueError):
    """Raised by the command layer for input it rejects; printed as one line, exit code 2."""


def fail(message: str) -> NoReturn:
    """Print ``error: message`` on stderr as one line and exit with code 2."""
    line = " ".join(str(message).split())
    print(f"stickslip: error: {line}", file=sys.stderr)
    raise SystemExit(EXIT_BAD_INPUT)


def parse_dva(text: str, zeta: float, k_scale: float = 1.0) -> Foundation | None:
    """Resolve the ``--dva`` option at damping ratio ``zeta``.

    ``none`` is the rigid base (1DOF); ``optimal`` the paper's fitted optimum, Eqs. (28)-(30);
    ``optimal-exact`` the numerical optimum of the absorber; ``M,K,ZETA_A`` explicit values.
    ``k_scale`` multiplies ``K`` (paper Figs. 11-15); it requires a foundation.
    """
    from stickslip.analysis.dva import DvaSpec

    return DvaSpec.parse(text, k_scale).resolve(zeta)


def _jsonable(value: Any) -> Any:
    import numpy as np  # imported here: ``stickslip --help`` must start fast

    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return _jsonable(value.tolist())
    if isinstance(value, (np.floating, float)):
        x = float(value)
        return x if math.isfinite(x) else None
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.bool_):
        return bool(value)
    return value


def print_json(payload: dict[str, Any]) -> None:
    """Print exactly one JSON object on stdout (non-finite numbers become null)."""
    sys.stdout.write(json.dumps(_jsonable(payload), allow_nan=False) + "\n")


def check_output_path(path: Path, *, overwrite: bool = True) -> Path:
    """Check that ``path`` can be written before any work starts.

    Rejects a directory, a missing parent folder that cannot be created, or an existing
    file when ``overwrite`` is false.
    """
    path = Path(path)
    if path.exists() and path.is_dir():
        raise BadInput(f"output path {str(path)!r} is a directory")
    if path.exists() and not overwrite:
        raise BadInput(f"output file {str(path)!r} exists; pass --overwrite to replace it")
    parent = path.parent
    try:
        parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise BadInput(f"cannot create folder {str(parent)!r}: {exc.strerror}") from None
    if not _writable(parent):
        raise BadInput(f"folder {str(parent)!r} is not writable")
    return path


FIGURE_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg")


def check_figure_path(path: Path) -> Path:
    """Like :func:`check_output_path`, and the suffix must name a figure format."""
    path = Path(path)
    if path.suffix.lower() not in FIGURE_SUFFIXES:
        raise BadInput(
            f"figure file {str(path)!r} must end in one of {', '.join(FIGURE_SUFFIXES)}"
        )
    return check_output_path(path)


def save_plot(draw: Callable[[Any], Any], path: Path, size: tuple[float, float] = (8.0, 5.5)) -> str:
    """Draw into a new ``size`` figure with ``draw(ax)`` and save it to ``path`` atomically.

    ``draw`` returns the :class:`~stickslip.plot.figure.PlotResult` of a ``*_plot`` function
    (or of a result's ``.plot(ax=ax)``); its ``savefig`` writes at 130 dpi.
    """
    from stickslip.plot.figure import new_axes

    _, ax = new_axes(figsize=size)
    return str(draw(ax).savefig(path))


def _writable(folder: Path) -> bool:
    """Try to create (and remove) a file in ``folder``: permissions alone can lie (root, /proc)."""
    import tempfile

    try:
        with tempfile.NamedTemporaryFile(dir=folder, prefix=".stickslip-write-test-"):
            return True
    except OSError:
        return False
