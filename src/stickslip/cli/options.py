"""Command-line options shared by several commands (one definition, one help text)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

GAMMA = Annotated[float, typer.Option("--gamma", help="mu_k / (mu_s - mu_k) >= 0 (paper: 2)")]
DVA = Annotated[
    str,
    typer.Option(
        "--dva",
        help="foundation: none (rigid base), optimal (fitted Eqs. 28-30 at each zeta), "
        "optimal-exact (numerical optimum), or M,K,ZETA_A",
    ),
]
K_SCALE = Annotated[float, typer.Option("--k-scale", help="multiply the foundation's K (Figs. 11-15)")]
JSON = Annotated[bool, typer.Option("--json", help="print one JSON object and nothing else")]
PLOT = Annotated[Path | None, typer.Option("--plot", help="write the figure here (.png, .pdf, .svg)")]
OVERWRITE = Annotated[
    bool, typer.Option("--overwrite", help="replace existing output files (refused otherwise)")
]
FRICTION = Annotated[
    str,
    typer.Option(
        "--friction",
        help="friction law while sliding (dimensionless): coulomb (the paper's), linear:DELTA, "
        "table:FILE.csv (columns v = v_r/V and f = (mu - mu_k)/(mu_s - mu_k)), or "
        "stribeck:vs=V_S/V, optionally followed by ,n=N ,viscous=D_V ,mu0=R0 ,tol=TOL "
        "(e.g. stribeck:vs=0.2,viscous=0.01); on simulate also the laws with memory "
        "rate-state: (keys a, b, dc, mu_ref, vref, optionally evolution=slip) and lugre: (keys "
        "sigma0, sigma1, sigma2, mu_c, mu_s, vs), dimensionless, see docs/friction_memory.md",
    ),
]
#: The backend options of resumable runs (``map``, ``basin``): same names, same help.
BACKEND = Annotated[
    str | None,
    typer.Option("--backend", help="serial, threads (default) or dask (default with --scheduler)"),
]
SCHEDULER = Annotated[
    str | None, typer.Option("--scheduler", help="address of a running Dask scheduler")
]
SCHEDULER_TIMEOUT = Annotated[
    float, typer.Option("--scheduler-timeout", help="seconds allowed to reach the --scheduler (default 10)")
]


def parse_range(text: str, quantity: str | None, *, positive: bool = False) -> tuple[float, float]:
    """``--range A:B`` as two floats, ``A < B``; with a machine quantity (``speed``, ``load``,
    ...) each end may carry a unit (converted to SI, its dimension checked); ``positive``:
    both ends positive and finite. One line naming the value when it is wrong."""
    import math

    from stickslip.cli.console import BadInput
    from stickslip.model.physical import MAX_SI, MIN_SI
    from stickslip.model.units import to_si

    lo_text, sep, hi_text = text.partition(":")
    try:
        if quantity is None:
            lo, hi = float(lo_text), float(hi_text)
        else:
            lo, hi = (to_si(quantity, part.strip(), source="--range") for part in (lo_text, hi_text))
    except ValueError as exc:
        detail = "two numbers" if quantity is None else f"two values of {quantity} ({exc})"
        raise BadInput(f"--range {text!r} must be A:B with {detail}") from None
    if sep and ":" not in hi_text and not (math.isfinite(lo) and math.isfinite(hi)):
        raise BadInput(f"--range {text!r}: both ends must be finite numbers")
    if not sep or ":" in hi_text or not lo < hi:
        raise BadInput(f"--range {text!r} must be A:B with A < B")
    if positive and not (math.isfinite(lo) and math.isfinite(hi) and lo > 0.0):
        raise BadInput(f"--range {text!r} must be positive and finite with A < B")
    if positive and quantity is not None and not (MIN_SI <= lo and hi <= MAX_SI):
        raise BadInput(f"--range {text!r} reaches beyond the supported {quantity} range "
                       f"[{MIN_SI:g}, {MAX_SI:g}] in SI units")
    return lo, hi


def operating_axes(speed: str | None, load: str | None, example: str) -> list[Any]:
    """``map --config``'s ``--speed`` and ``--load`` grids (:class:`~stickslip.sweep.grid.Axis`),
    every value positive and finite; one line naming the flag otherwise (``example``: grids
    to suggest when one is missing)."""
    import math

    from stickslip.cli.console import BadInput, flag_error
    from stickslip.model.physical import MAX_SI
    from stickslip.sweep.grid import Axis

    if speed is None or load is None:
        raise BadInput(f"map --config needs --speed (m/s) and --load (N) grids, e.g. {example}")
    axes = []
    for flag, text, unit in (("--speed", speed, "m/s"), ("--load", load, "N")):
        try:
            axis = Axis.parse(text, flag.lstrip("-"), limit=MAX_SI)
        except ValueError as exc:
            raise flag_error(flag, text, exc) from None
        values = axis.values
        if not (all(math.isfinite(x) for x in values) and min(values) > 0.0):
            raise BadInput(f"{flag} {text!r}: every value must be positive and finite [{unit}]")
        axes.append(axis)
    return axes


def check_map_outputs(out: Path, csv: Path | None, plot: Path | None, overwrite: bool) -> None:
    """``--out`` (netCDF), ``--csv`` and ``--plot`` of ``map --config`` checked before any work:
    one line naming the file when it is wrong or exists without ``--overwrite``."""
    from stickslip.cli.console import BadInput, check_figure_path, check_output_path

    if out.suffix.lower() != ".nc":
        raise BadInput(f"output file {str(out)!r} must end in .nc (netCDF)")
    check_output_path(out, overwrite=overwrite, option="--out")
    if csv is not None:
        check_output_path(csv, overwrite=overwrite, option="--csv")
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)


#: Longest ``--scheduler-timeout``, seconds: one day.
MAX_SCHEDULER_TIMEOUT = 86_400.0


def scheduler_context(scheduler: str | None, timeout: float) -> Any:
    """Check ``--scheduler-timeout``; reach ``--scheduler`` within it (one line if not).

    Returns the Dask configuration context that makes the run's own client use the same
    bound (``stickslip.scheduler-timeout``), or a no-op context without a scheduler.
    """
    import contextlib
    import math

    from stickslip.cli.console import BadInput

    if not (timeout > 0.0 and math.isfinite(timeout)):
        raise BadInput(f"--scheduler-timeout {timeout!r} must be a positive number of seconds")
    if timeout > MAX_SCHEDULER_TIMEOUT:  # a socket's timeout overflows the platform's time_t
        raise BadInput(f"--scheduler-timeout {timeout!r} is beyond {MAX_SCHEDULER_TIMEOUT:g} s "
                       "(one day), the longest wait for a scheduler")
    if scheduler is None:
        return contextlib.nullcontext()
    import dask

    from stickslip.sweep.executors import _probe_tcp

    _probe_tcp(scheduler, timeout)
    return dask.config.set({"stickslip.scheduler-timeout": timeout})
