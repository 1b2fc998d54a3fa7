"""Command-line options shared by several commands (one definition, one help text)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

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
        "(e.g. stribeck:vs=0.2,viscous=0.01)",
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
