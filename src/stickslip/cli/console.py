"""Shared pieces of the command line: input parsing, errors and JSON output.

The command line is a public contract: invalid input prints one line
on stderr naming the value and why, exits with code 2, and writes no file.
"""

from __future__ import annotations

import json
import math
import sys
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

from stickslip.model.user_file import is_input

if TYPE_CHECKING:
    from stickslip.model.dva import DvaSpec
    from stickslip.model.friction import FrictionLaw
    from stickslip.model.parameters import Foundation

EXIT_BAD_INPUT = 2


class BadInput(ValueError):
    """Raised by the command layer for input it rejects; printed as one line, exit code 2."""


def fail(message: str) -> NoReturn:
    """Print ``error: message`` on stderr as one line and exit with code 2."""
    line = " ".join(str(message).split())
    print(f"stickslip: error: {line}", file=sys.stderr)
    raise SystemExit(EXIT_BAD_INPUT)


def flag_error(flag: str, value: object, exc: ValueError) -> BadInput:
    """The one-line error of a model parser, with the command-line flag that gave the value.

    Model parsers speak of the model ("friction law 'x' is not one of ..."); the command line
    adds which flag it came from: ``"--friction 'x': friction law 'x' is not one of ..."``. A
    message that already starts with the flag (model messages written before issue 17 did) is
    kept as it is, so the flag is never named twice.
    """
    message = str(exc)
    if message.startswith(f"{flag} "):
        return BadInput(message)
    return BadInput(f"{flag} {str(value)!r}: {message}")


def parse_friction_option(text: str, flag: str = "--friction") -> FrictionLaw:
    """The friction law of a ``--friction`` option (:func:`stickslip.model.friction_input.parse_friction`).

    Raises :class:`BadInput` naming the flag, the value and the model's reason.
    """
    from stickslip.model.friction_input import parse_friction

    try:
        return parse_friction(text)
    except ValueError as exc:
        raise flag_error(flag, text, exc) from None


def parse_dva_option(text: str, k_scale: float = 1.0) -> DvaSpec:
    """The foundation spec of a ``--dva`` option (``DvaSpec.parse``), errors naming ``--dva``.

    ``none`` is the rigid base (1DOF); ``optimal`` the paper's fitted optimum, Eqs. (28)-(30);
    ``optimal-exact`` the numerical optimum of the absorber; ``M,K,ZETA_A`` explicit values.
    ``k_scale`` multiplies ``K`` (paper Figs. 11-15); it requires a foundation (its error
    names ``--k-scale``).
    """
    from stickslip.model.dva import DvaSpec

    try:
        spec = DvaSpec.parse(text)
    except ValueError as exc:
        raise flag_error("--dva", text, exc) from None
    if k_scale == 1.0:
        return spec
    try:
        return DvaSpec.parse(text, k_scale)
    except ValueError as exc:
        raise flag_error("--k-scale", k_scale, exc) from None


def parse_dva(text: str, zeta: float, k_scale: float = 1.0) -> Foundation | None:
    """Resolve the ``--dva`` option at damping ratio ``zeta`` (see :func:`parse_dva_option`)."""
    from stickslip.analysis.dva import resolve_dva

    return resolve_dva(parse_dva_option(text, k_scale), zeta)


def max_events_limit() -> int:
    """Largest ``--max-events``: the engine's step budget (``kernel.engine.MAX_STEPS``).

    Every mode switch ends a step and a run never takes more than ``MAX_STEPS`` steps, so a
    larger budget can never be used; the phase record is allocated for ``max_events + 1``
    rows, and 1e12 of them asked for terabytes.
    """
    from stickslip.kernel.engine import MAX_STEPS

    return int(MAX_STEPS)


def check_run_limits(lam: float, gamma: float, *, max_events: int | None = None,
                     plot_from: float | None = None) -> None:
    """Refuse values a run cannot use: overflowing ``2 gamma lambda``, an event budget beyond
    the step budget, a non-finite or negative first plotted time."""
    from stickslip.model._validate import friction_range, non_negative

    try:
        friction_range(lam, gamma)
        if plot_from is not None:
            non_negative("--plot-from", plot_from)
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    if max_events is not None:
        limit = max_events_limit()
        if max_events < 1:
            raise BadInput(f"--max-events {max_events} must be at least 1")
        if max_events > limit:
            raise BadInput(
                f"--max-events {max_events} exceeds {limit}: a run stops after {limit} steps "
                "(every event ends one), so more events can never happen"
            )


#: Copies of a map's per-cell results alive at the peak (the engine's summaries, the
#: dataset's variables, the netCDF encoding buffers): a conservative factor.
_RESULT_COPIES = 3


def physical_memory() -> int | None:
    """Bytes of RAM of this machine (``os.sysconf``), None where unknown."""
    import os

    try:
        pages, size = os.sysconf("SC_PHYS_PAGES"), os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, ValueError, OSError):
        return None
    return int(pages) * int(size) if pages > 0 and size > 0 else None


def check_grid_memory(n_cells: int, axes: str = "--lam/--zeta") -> None:
    """Refuse a grid whose results would not fit in half the RAM, before anything is written.

    ``axes`` names the options that set the grid, for the message.

    Each cell keeps ``N_FLOAT`` float and ``N_INT`` integer summaries (8 bytes each) of the
    engine, held in about :data:`_RESULT_COPIES` copies while the dataset is built and written.
    """
    from stickslip.kernel.engine import N_FLOAT, N_INT

    need = int(n_cells) * 8 * (N_FLOAT + N_INT) * _RESULT_COPIES
    ram = physical_memory()
    if ram is not None and need > ram // 2:
        raise BadInput(
            f"a grid of {n_cells:,} cells needs about {need / 2**30:,.1f} GiB for its results, "
            f"more than half of this machine's {ram / 2**30:,.1f} GiB; use fewer points "
            f"({axes}) or split the map"
        )


def show_progress() -> bool:
    """Whether long work shows a progress bar: when stderr is a terminal, with or without
    ``--json`` (the bar is on stderr, the JSON alone on stdout; a pipe or a file gets no bar).

    Returns
    -------
    bool
        ``sys.stderr.isatty()``.
    """
    return sys.stderr.isatty()


def warn(message: str) -> None:
    """Print ``warning: message`` on stderr as one line (never on stdout: --json stays clean)."""
    line = " ".join(str(message).split())
    print(f"stickslip: warning: {line}", file=sys.stderr)


def warn_fitted_range(spec: Any, zetas: Any) -> None:
    """One warning line when ``--dva optimal`` is used above the fitted range of Eqs. 28-30.

    ``spec`` is a :class:`~stickslip.model.dva.DvaSpec` or the ``--dva`` text. Call it
    after every check has passed, so that a rejected command prints only its error line.
    """
    from stickslip.analysis.dva import fitted_zeta_warning

    if isinstance(spec, str):
        spec = parse_dva_option(spec)
    note = fitted_zeta_warning(spec, zetas)
    if note:
        warn(note)


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
        return x + 0.0 if math.isfinite(x) else None  # + 0.0: a rounded -0 prints as 0
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.bool_):
        return bool(value)
    return value


def print_json(payload: dict[str, Any]) -> None:
    """Print exactly one JSON object on stdout (non-finite numbers become null, -0 is 0)."""
    sys.stdout.write(json.dumps(_jsonable(payload), allow_nan=False) + "\n")


def check_distinct_outputs(**paths: Path | None) -> None:
    """Refuse two output options (keyword: option name without dashes) naming one file."""
    seen: dict[Path, str] = {}
    for option, path in paths.items():
        if path is None:
            continue
        key = Path(path).resolve()
        name = "--" + option.replace("_", "-")
        if key in seen:
            raise BadInput(f"{seen[key]} and {name} name the same file {str(path)!r}; one would "
                           "overwrite the other")
        seen[key] = name


def check_output_path(path: Path, *, overwrite: bool = True, option: str = "output") -> Path:
    """Check that ``path`` can be written before any work starts; create nothing.

    Rejects a directory, an existing file when ``overwrite`` is false, and a parent folder
    that cannot be created or written. Missing folders are created only when the file is
    written (:func:`stickslip.io.atomic.atomic_output`), so a rejected command leaves none.
    """
    path = Path(path)
    if path.exists() and path.is_dir():
        raise BadInput(f"{option} path {str(path)!r} is a directory")
    if is_input(path):
        raise BadInput(f"{option} {str(path)!r} is an input file of this command; name another "
                       "output file")
    if path.exists() and not overwrite:
        raise BadInput(f"{option} file {str(path)!r} exists; pass --overwrite to replace it")
    parent = path.parent
    existing = parent
    while not existing.exists() and existing != existing.parent:
        existing = existing.parent
    if not existing.is_dir():
        raise BadInput(f"cannot create folder {str(parent)!r}: {str(existing)!r} is not a folder")
    if not _writable(existing):
        if existing != parent:
            raise BadInput(f"cannot create folder {str(parent)!r}: {str(existing)!r} is not writable")
        raise BadInput(f"folder {str(parent)!r} is not writable (needed for {str(path)!r})")
    return path


FIGURE_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg")


def check_figure_path(path: Path, *, overwrite: bool = False, option: str = "--plot") -> Path:
    """Like :func:`check_output_path` for ``--plot`` (or ``option``); the suffix names a figure format."""
    path = Path(path)
    if path.suffix.lower() not in FIGURE_SUFFIXES:
        raise BadInput(
            f"figure file {str(path)!r} must end in one of {', '.join(FIGURE_SUFFIXES)}"
        )
    return check_output_path(path, overwrite=overwrite, option=option)


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


def typed_options(ctx: Any, names: tuple[str, ...]) -> list[str]:
    """The options among ``names`` (parameter names) given on the command line, as flags."""
    # by name: Typer may ship its own copy of click, whose ParameterSource is another enum
    return [f"--{n.replace('_', '-')}" for n in names if n in ctx.params
            and getattr(ctx.get_parameter_source(n), "name", None) == "COMMANDLINE"]
