"""``stickslip basin``: certified verdicts for many disturbed starts (basin stability)."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Annotated, Any

import typer

from stickslip.cli.console import (
    BadInput,
    check_figure_path,
    check_output_path,
    check_run_limits,
    parse_dva,
    parse_friction_option,
    print_json,
    show_progress,
    typed_options,
)
from stickslip.cli.map_commands import WORKERS
from stickslip.cli.options import (
    BACKEND,
    DVA,
    FRICTION,
    GAMMA,
    JSON,
    K_SCALE,
    SCHEDULER,
    SCHEDULER_TIMEOUT,
)
from stickslip.model.user_file import csv_rows, read_user_text

BOX_HELP = ("sampling box, e.g. 'xi=-4:4,v=-3:1.5' (dimensionless, in the shifted coordinates of "
            "Eqs. 15-16: xi, v, xi_a, v_a; their origin is steady sliding under the Coulomb law, "
            "not under a law that varies with speed, whose steady sliding sits at its own xi; "
            "basin-map's box is about each cell's steady sliding) or, with --config, "
            "'x=-0.001:0.001,v=-0.02:0.02' (SI: m, m/s; x from where the spring is relaxed, "
            "ground frame); unnamed columns keep their steady-sliding value. Default: "
            "xi=-2:2,v=-2:1.5, dimensionless, with --config too (in the machine's scales "
            "V/omega_n and V)")


def parse_box(text: str) -> dict[str, tuple[float, float]]:
    """``name=lo:hi,name=lo:hi`` to a dictionary of intervals."""
    box: dict[str, tuple[float, float]] = {}
    for item in text.split(","):
        name, eq, text_interval = item.partition("=")
        lo, colon, hi = text_interval.partition(":")
        try:
            if not (eq and colon):
                raise ValueError
            interval = (float(lo), float(hi))
        except ValueError:
            raise BadInput(f"--box {item.strip()!r} is not NAME=LO:HI") from None
        if name.strip() in box:
            raise BadInput(f"--box {text!r}: column {name.strip()!r} given twice")
        box[name.strip()] = interval
    return box


#: Largest ``--initial-states`` file read, bytes: 1 GiB (some 2e7 states of four coordinates).
MAX_STATES_BYTES = 1024**3

#: a state coordinate's column name: xi/x and v, and the other DOFs' xi_a, v_a, x_a2, v_a3, ...
STATE_NAME = re.compile(r"(xi|x|v)(_a\d*)?")


def read_states(path: Path, names: list[str]) -> tuple[list[dict[str, str]], list[str], list[list[float]]]:
    """Rows of ``--initial-states``: every row as read, the columns, and the state columns as numbers."""
    try:
        text = read_user_text(path, f"--initial-states {str(path)!r}", max_bytes=MAX_STATES_BYTES,
                              hint="name the CSV file itself")
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    try:
        table = csv_rows((line for line in text.splitlines()
                          if line.strip() and not line.startswith("#")),
                         f"--initial-states {str(path)!r}")
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    columns = table[0] if table else []
    repeated = sorted({c for c in columns if columns.count(c) > 1})
    if repeated:
        raise BadInput(f"--initial-states {str(path)!r} names the column(s) {', '.join(repeated)} "
                       "more than once; keep one of each")
    missing = [c for c in names if c not in columns]
    if missing:
        raise BadInput(f"--initial-states {str(path)!r} lacks the columns {', '.join(missing)} "
                       f"(needs {', '.join(names)})")
    # other columns are carried through to the labels; one named like a state coordinate of
    # another structure (xi_a on a rigid base) would be silently ignored, so it is refused
    foreign = [c for c in columns if c not in names and STATE_NAME.fullmatch(c.strip())]
    if foreign:
        raise BadInput(f"--initial-states {str(path)!r}: the column(s) {', '.join(foreign)} name state "
                       f"coordinates this structure does not have (its state is {', '.join(names)})")
    rows, values = [], []
    for k, fields in enumerate(table[1:], start=2):
        if len(fields) != len(columns):
            raise BadInput(f"--initial-states {str(path)!r}, row {k - 1}: {len(fields)} values "
                           f"for the {len(columns)} columns of the header")
        row = dict(zip(columns, fields, strict=True))
        try:
            values.append([float(row[c]) for c in names])
        except (TypeError, ValueError):
            raise BadInput(f"--initial-states {str(path)!r}, line {k}: "
                           f"not numbers in {', '.join(names)}") from None
        rows.append(row)
    if not rows:
        raise BadInput(f"--initial-states {str(path)!r} has no rows")
    return rows, columns, values


# Over 120 lines on purpose: Typer declares each of the command's options in this signature
# (a third of the length) and the docstring is the help text; the body is one straight path
# (check every input, then write), which split up would scatter the checks that must all pass
# before any file is made.
def basin(
    ctx: typer.Context,
    lam: Annotated[float | None, typer.Option("--lam", help="lambda > 0 (dimensionless system)")] = None,
    zeta: Annotated[float | None, typer.Option("--zeta", help="damping ratio >= 0")] = None,
    gamma: GAMMA = 2.0,
    dva: DVA = "none",
    k_scale: K_SCALE = 1.0,
    friction: FRICTION = "coulomb",
    config: Annotated[
        Path | None, typer.Option("--config", help="machine.toml in SI ([system] keys m, k, c, ... or "
                                  "a [structure]; [friction]); states in SI, x/v the contact DOF, "
                                  "x_a, x_a2, ... "
                                  "the other DOFs in order; not with --lam, --zeta, --gamma, --dva, "
                                  "--k-scale, --friction")
    ] = None,
    samples: Annotated[int, typer.Option("--samples", help="number of states drawn in --box")] = 10_000,
    seed: Annotated[int, typer.Option("--seed", help="seed of the sampling")] = 0,
    box: Annotated[str | None, typer.Option("--box", help=BOX_HELP)] = None,
    initial_states: Annotated[
        Path | None, typer.Option("--initial-states", help="CSV of states instead of sampling")
    ] = None,
    t_max: Annotated[float, typer.Option(
        "--t-max", help="dimensionless horizon omega_n t of each run (default 5000): raise it when "
        "samples end undetermined")] = 5000.0,
    backend: BACKEND = None,
    workers: WORKERS = None,
    scheduler: SCHEDULER = None,
    scheduler_timeout: SCHEDULER_TIMEOUT = 10.0,
    out_text: Annotated[str | None, typer.Option(
        "--out", help="folder for labels.csv and basin.nc; an interrupted run resumes from "
        "DIR/basin.parts")] = None,
    plot: Annotated[Path | None, typer.Option("--plot", help="basin picture (.png, .pdf, .svg)")] = None,
    overwrite: Annotated[bool, typer.Option("--overwrite", help="replace existing output files")] = False,
    json: JSON = False,
) -> None:
    """Basin stability: a certified verdict for each of many initial states (disturbed starts).

    Example: stickslip basin --lam 2.5 --zeta 0.1 --samples 20000 --box 'xi=-4:4,v=-3:1.5' --json

    On a Dask cluster (--backend dask: worker processes on this machine, or --scheduler ADDRESS),
    resumable from DIR/basin.parts like a map:

    Example: stickslip basin --lam 2.5 --zeta 0.1 --samples 200000 --backend dask --workers 2 --out run
    """
    from stickslip.analysis.simulation import EngineOptions
    from stickslip.cli.machine_config import configured_machine, refuse_mix, require_dimensionless
    from stickslip.model.parameters import Slider
    from stickslip.model.structure import chain_structure
    from stickslip.sweep.basin import (
        basin_stability,
        check_states,
        physical_names,
        sample_box,
        state_names,
        write_labels,
    )

    refuse_mix(ctx, config)
    if out_text is not None and not out_text.strip():
        # a folder: the empty name would be the current one (what typer makes of "")
        raise BadInput(f"--out {out_text!r} is empty: name a folder for labels.csv and basin.nc")
    out = None if out_text is None else Path(out_text)
    drawn = typed_options(ctx, ("samples", "seed"))
    if initial_states is not None and drawn:
        verb = "draw" if len(drawn) > 1 else "draws"
        raise BadInput(f"{' and '.join(drawn)} {verb} the states, --initial-states gives them; "
                       "give one of the two")
    run = None
    if config is not None:
        from stickslip.cli.machine_config import load_machine_file

        machine_file = load_machine_file(config, normal_coupling=True)
        if machine_file.has_contact and not machine_file.has_memory_law:
            _contact_basin(ctx, config, machine_file, samples=samples, seed=seed, box=box,
                           initial_states=initial_states, t_max=t_max, workers=workers,
                           out=out, overwrite=overwrite, json=json)
            return
        from stickslip.cli.machine_config import refuse_contact_with_memory

        refuse_contact_with_memory(machine_file)
        if machine_file.has_memory_law:  # one stiff run per start, in SI
            _memory_basin(ctx, machine_file, config, samples=samples, seed=seed, box=box,
                          initial_states=initial_states, out=out, plot=plot,
                          overwrite=overwrite, json=json, backend=backend or scheduler)
            return
        run = configured_machine(config)
        # the engine's order: the contact DOF first (the presets are already so: no change)
        structure, _ = run.structure.contact_first()
        slider = run.slider
    else:
        require_dimensionless(lam=lam, zeta=zeta)
        assert lam is not None and zeta is not None
        slider = Slider(lam, gamma=gamma, friction=parse_friction_option(friction))
        found = parse_dva(dva, zeta, k_scale)
        structure = chain_structure(zeta, () if found is None else (found,))
    check_run_limits(slider.lam, slider.gamma)  # as simulate: 2 gamma lambda must not overflow
    options = EngineOptions(t_max=t_max)
    from stickslip.sweep.executors import check_backend

    chosen = check_backend(backend or ("dask" if scheduler else "threads"), workers, scheduler)
    if chosen == "dask":
        _need_distributed()
    n_dof = structure.n_dof
    names = physical_names(n_dof) if run is not None else state_names(n_dof)
    if box is not None and initial_states is not None:
        raise BadInput("give either --box (sampling) or --initial-states, not both")
    labels = None if out is None else out / "labels.csv"
    dataset = None if out is None else out / "basin.nc"
    for path in (labels, dataset):
        if path is not None:
            check_output_path(path, overwrite=overwrite, option="--out")
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    rows = columns = None
    if initial_states is not None:
        rows, columns, values = read_states(initial_states, names)
        import numpy as np

        raw = np.array(values, dtype=np.float64)
        try:  # the bound of simulate --initial, before any file is made
            check_states(raw, names)
            states = raw if run is None else _physical_to_states(structure, slider, run.reference, raw)
            check_states(states, state_names(n_dof))
        except ValueError as exc:
            raise BadInput(f"--initial-states {str(initial_states)!r}: {exc}") from None
    else:
        if box is None:  # dimensionless about steady sliding, a machine's file or not
            default = state_names(n_dof)
            states = sample_box(structure, slider, samples,
                                {default[0]: (-2.0, 2.0), default[n_dof]: (-2.0, 1.5)}, seed)
        else:
            intervals = parse_box(box)
            unknown = sorted(set(intervals) - set(names))
            if unknown:
                raise BadInput(f"--box columns {', '.join(unknown)} are not among {', '.join(names)}")
            if run is not None:
                states = _sample_physical(structure, slider, run.reference, samples, intervals, seed)
            else:
                states = sample_box(structure, slider, samples, intervals, seed)
    from contextlib import nullcontext

    from stickslip.cli.cleanup import UndoOnRefusal
    from stickslip.cli.options import scheduler_context
    from stickslip.cli.progress import ProgressBar
    from stickslip.io.lock import output_lock
    from stickslip.sweep.execution import ExecutionOptions
    from stickslip.sweep.store import discard_store

    enabled = show_progress()
    store = None if out is None else out / "basin.parts"  # resume store, removed when done
    reach = scheduler_context(scheduler, scheduler_timeout)  # before any file is made
    undo = UndoOnRefusal([] if out is None else [out], [] if store is None else [store])
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)  # every check passed: writing starts
    with undo, output_lock(labels) if labels is not None else nullcontext(), reach:
        with ProgressBar(enabled, f"basin {len(states)} states", unit="samples") as bar:
            result = basin_stability(structure, slider, states, options=options,
                                     execution=ExecutionOptions(backend=chosen, workers=workers,
                                                                scheduler=scheduler, progress=bar,
                                                                store=store, overwrite=overwrite))
        payload = result.to_dict()
        payload.update({"labels": None, "dataset": None, "plot": None,
                        "undetermined_by": undetermined_statuses(result)})
        if out is not None:
            assert labels is not None and dataset is not None and store is not None
            write_labels(result, labels, rows, columns)
            from stickslip.io.netcdf import write_dataset

            data = result.to_xarray()
            if run is not None:
                data = _with_physical_states(data, structure, slider, run.reference)
            write_dataset(data, dataset, overwrite=True)
            discard_store(store)
            payload.update({"labels": str(labels), "dataset": str(dataset)})
    if plot is not None:
        payload["plot"] = str(result.plot().savefig(plot))
    if json:
        print_json(payload)
        return
    _print_summary(payload)


def _contact_basin(ctx: typer.Context, config: Path, machine_file: Any, *, samples: int,
                   seed: int, box: str | None, initial_states: Path | None, t_max: float,
                   workers: int | None, out: Path | None, overwrite: bool, json: bool) -> None:
    """``basin --config`` with a contact (:func:`contact_basin`): ``labels.csv`` under --out."""
    import numpy as np

    from stickslip.cli.contact.commands import DEFAULT_WORKERS, progress_bar, refuse_options
    from stickslip.cli.contact.simulation import contact_run_system
    from stickslip.sweep.contact.basin import (
        columns,
        contact_basin,
        default_box,
        sample_contact_box,
    )

    refuse_options(ctx, ("backend", "scheduler", "plot"), "basin")
    if box is not None and initial_states is not None:
        raise BadInput("give either --box (sampling) or --initial-states, not both")
    if workers is not None and not 1 <= workers <= 64:
        raise BadInput(f"--workers {workers} must be from 1 to 64")
    if not t_max > 0.0:
        raise BadInput(f"--t-max {t_max:g} must be positive (natural times of the contact DOF)")
    labels = None if out is None else out / "labels.csv"
    if labels is not None:
        check_output_path(labels, overwrite=overwrite, option="--out")
    system, machine = contact_run_system(config, machine_file)
    typed_t_max = bool(typed_options(ctx, ("t_max",)))
    horizon = t_max / system.omega_ref if typed_t_max else None
    names = columns(system)
    try:
        if initial_states is not None:
            _, _, values = read_states(initial_states, list(names))
            starts = np.array(values, dtype=np.float64)
        else:
            intervals = parse_box(box) if box is not None else default_box(system)
            starts = sample_contact_box(system, samples, intervals, seed)
        with progress_bar(json, f"basin {len(starts)} starts (contact)", "samples",
                          shorten="--samples sets fewer states, --t-max a shorter horizon") as bar:
            result = contact_basin(system, starts, t_max=horizon, workers=workers or DEFAULT_WORKERS,
                                   progress=bar)
    except BadInput:
        raise
    except ValueError as exc:
        raise BadInput(f"{machine_file.label}: {exc}") from None
    payload = result.to_dict()
    payload.update({"config": str(config), "machine": machine.name, "labels": None,
                    "t_max_s": horizon})
    if labels is not None:
        from stickslip.io.lock import output_lock

        labels.parent.mkdir(parents=True, exist_ok=True)
        with output_lock(labels):
            payload["labels"] = str(result.write_labels(labels))
    if json:
        print_json(payload)
        return
    fr, se = payload["fractions"], payload["standard_errors"]
    parts = [f"{k} {fr[k]:.4f} +- {se[k]:.4f}" for k in fr if fr[k] > 0.0]
    lines = [f"basin       {machine.name}: {system.n_dof} DOF, contact on DOF "
             f"{system.tangential_dof}, starts around {payload['base']} over "
             f"{', '.join(names)} (SI)",
             f"samples     {payload['n']} in {payload['elapsed_s']:.2f} s (one engine run each)",
             f"fractions   {', '.join(parts)} (binomial standard errors)"]
    for kind, (lo, hi) in payload["period_range_s"].items():
        lines.append(f"periods     {kind}: {lo:.6g} to {hi:.6g} s")
    for why, count in payload["undetermined_by"].items():
        lines.append(f"undecided   {count}: {why}")
    lines.append("verdicts    periodic ones observed (a state repeated to 1e-9), not proven")
    if payload["labels"]:
        lines.append(f"labels      {payload['labels']}")
    typer.echo("\n".join(lines))


def _memory_basin(ctx: typer.Context, machine_file: Any, config: Path, *, samples: int, seed: int,
                  box: str | None, initial_states: Path | None, out: Path | None,
                  plot: Path | None, overwrite: bool, json: bool, backend: str | None) -> None:
    """``basin --config`` for a friction law with memory (:func:`memory_basin`): starts ``x``
    (m) and ``v`` (m/s) of the contact DOF, each run by the stiff engine; ``labels.csv``."""
    import numpy as np
    from click.core import ParameterSource

    from stickslip.cli.memory.stability_commands import memory_system
    from stickslip.cli.progress import ProgressBar
    from stickslip.sweep.memory.basin import COLUMNS, memory_basin, sample_memory_box

    if ctx.get_parameter_source("t_max") is ParameterSource.COMMANDLINE:
        raise BadInput("--t-max is the dimensionless horizon of the curve laws; with friction "
                       "with memory each start runs for simulate's default horizon")
    if backend is not None:
        raise BadInput("--backend/--scheduler: a basin with friction with memory runs its starts "
                       "in this process")
    if plot is not None:
        raise BadInput("--plot: the basin picture is drawn for the curve laws; with friction with "
                       "memory, --out DIR writes the starts and verdicts to DIR/labels.csv")
    if box is not None and initial_states is not None:
        raise BadInput("give either --box (sampling) or --initial-states, not both")
    system = memory_system(machine_file)
    labels = None if out is None else out / "labels.csv"
    if labels is not None:
        check_output_path(labels, overwrite=overwrite, option="--out")
    try:
        if initial_states is not None:
            _, _, values = read_states(initial_states, list(COLUMNS))
            states = np.array(values, dtype=np.float64)
        else:
            y_v = 0.5 * system.schedule.first
            intervals = parse_box(box) if box is not None else {"v": (-y_v, y_v)}
            states = sample_memory_box(system, samples, intervals, seed)
        enabled = show_progress()
        with ProgressBar(enabled, f"basin {len(states)} starts (friction with memory)",
                         unit="samples") as bar:
            result = memory_basin(system, states, progress=bar)
    except BadInput:
        raise
    except ValueError as exc:
        raise BadInput(f"{machine_file.label}: {exc}") from None
    payload = result.to_dict()
    payload.update({"config": str(config), "labels": None})
    if labels is not None:
        labels.parent.mkdir(parents=True, exist_ok=True)
        payload["labels"] = str(result.write_labels(labels))
    if json:
        print_json(payload)
        return
    fr, se = payload["fractions"], payload["standard_errors"]
    parts = [f"{k} {fr[k]:.4f} +- {se[k]:.4f}" for k in fr if fr[k] > 0.0]
    lines = [f"basin       {machine_file.label}: {system.n_dof} DOF, {system.friction.describe()}",
             f"samples     {payload['n']} in {payload['elapsed_s']:.2f} s (one stiff run each)",
             f"fractions   {', '.join(parts)} (binomial standard errors)"]
    for why, count in payload["undetermined_by"].items():
        lines.append(f"undecided   {count}: {why}")
    if payload["labels"]:
        lines.append(f"labels      {payload['labels']}")
    typer.echo("\n".join(lines))


def _need_distributed() -> None:
    """The dask backend needs dask.distributed: say so in one line, before any file is made."""
    import importlib.util

    if importlib.util.find_spec("distributed") is None:
        raise BadInput("the dask backend needs dask.distributed: pip install 'stickslip[dask]'")


def _physical_to_states(structure: Any, slider: Any, reference: Any, physical: Any) -> Any:
    """Physical states ``(x, x_a, ..., v, v_a, ...)`` [m, m/s] to shifted dimensionless states.

    As :func:`stickslip.sweep.basin.states_from_physical` (positions from where every spring
    is relaxed, ground-frame velocities; ``xi = x / (V / omega_n) - gamma lambda K^-1 e_0``,
    ``xi' = v / V``, Eqs. 15-16) for any machine: ``structure`` in the engine's order (contact
    first) and ``omega_n`` of the contact's reference system (:mod:`stickslip.model.machine`).
    """
    import numpy as np

    n = structure.n_dof
    physical = np.asarray(physical, dtype=np.float64)
    shift = slider.gamma * slider.lam * structure.kinetic_equilibrium_offset()
    out = np.empty_like(physical)
    out[:, :n] = physical[:, :n] / reference.length_scale - shift
    out[:, n:] = physical[:, n:] / reference.speed
    return out


def _with_physical_states(data: Any, structure: Any, slider: Any, reference: Any) -> Any:
    """A ``basin --config`` dataset with the starts also in SI: ``x_si`` [m] from where the springs
    are relaxed and ``v_si`` [m/s] in the ground frame (the inverse of :func:`_physical_to_states`),
    and the scales that relate the two (``length_scale_m``, ``time_scale_s``, ``speed_m_per_s``)."""
    import numpy as np

    from stickslip.sweep.basin import physical_names, state_names

    n = structure.n_dof
    shift = slider.gamma * slider.lam * structure.kinetic_equilibrium_offset()
    shifted = np.stack([data[name].values for name in state_names(n)], axis=1)
    physical = np.empty_like(shifted)
    physical[:, :n] = (shifted[:, :n] + shift) * reference.length_scale
    physical[:, n:] = shifted[:, n:] * reference.speed
    out = data.copy()
    for i, name in enumerate(physical_names(n)):
        position = i < n
        out[f"{name}_si"] = (("sample",), physical[:, i], {
            "long_name": f"initial {name}: " + ("displacement from where the springs are relaxed"
                                                if position else "velocity in the ground frame"),
            "units": "m" if position else "m/s"})
    out.attrs.update({"length_scale_m": reference.length_scale, "time_scale_s": reference.time_scale,
                      "speed_m_per_s": reference.speed,
                      "dof_order": "contact DOF first, then the others in the file's order"})
    return out


def _sample_physical(structure: Any, slider: Any, reference: Any, samples: int,
                     box: dict[str, tuple[float, float]], seed: int) -> Any:
    """Uniform samples of a box in SI units (``x``, ``v``, ``x_a``, ``v_a``), made dimensionless.

    A position ``x`` [m] from where the springs are relaxed is ``xi = x / L - shift`` with
    ``L = V / omega_n`` and the kinetic-equilibrium shift of Eqs. (15)-(16); a velocity ``v``
    [m/s] is ``xi' = v / V``. The map is affine per column, so uniform stays uniform.
    ``structure`` is in the engine's order (contact first): ``x`` is the contact DOF, ``x_a``,
    ``x_a2``, ... the other DOFs in the file's order.
    """
    from stickslip.sweep.basin import physical_names, sample_box, state_names

    n = structure.n_dof
    shift = slider.gamma * slider.lam * structure.kinetic_equilibrium_offset()
    names, dimensionless = physical_names(n), state_names(n)
    converted = {}
    for name, (lo, hi) in box.items():
        i = names.index(name)
        if i < n:
            scale = reference.length_scale
            converted[dimensionless[i]] = (lo / scale - shift[i], hi / scale - shift[i])
        else:
            converted[dimensionless[i]] = (lo / reference.speed, hi / reference.speed)
    try:
        return sample_box(structure, slider, samples, converted, seed)
    except ValueError as exc:  # say it in the user's columns and units
        from stickslip.model.initial import MAX_STATE

        if "reaches beyond" not in str(exc):
            raise
        raise BadInput(f"--box {', '.join(f'{k}={lo:g}:{hi:g}' for k, (lo, hi) in box.items())} "
                       f"reaches beyond the supported state magnitude ({MAX_STATE:g} in units of "
                       f"V/omega_n = {reference.length_scale:.4g} m and V = {reference.speed:.4g} "
                       "m/s about steady sliding)") from None


def undetermined_statuses(result: Any) -> dict[str, int]:
    """How many runs of a basin ended undetermined, by run status label (``t-max``, ...)."""
    import numpy as np

    from stickslip.analysis.verdict import RunStatus, Verdict
    from stickslip.kernel import engine

    codes = result.int_summary[:, engine.I_STATUS]
    undetermined = result.verdict == Verdict.UNDETERMINED.code
    found = np.unique(codes[undetermined], return_counts=True)
    return {RunStatus.from_code(int(code)).label: int(n) for code, n in zip(*found, strict=True)}


def undetermined_line(p: dict[str, Any]) -> str | None:
    """Why the undetermined samples are so and how to decide them; None when there are none."""
    from stickslip.analysis.verdict import RunStatus

    by = p.get("undetermined_by") or {}
    if not by:
        return None
    messages = {status.label: status.message.split(";")[0] for status in RunStatus}
    why = "; ".join(f"{n} {messages[label]}" for label, n in by.items())
    hint = (f"; a longer horizon may decide them: --t-max {10 * p['t_max']:g} (now {p['t_max']:g})"
            if "t-max" in by or "unproven-cycle" in by else "")
    return f"undetermined {sum(by.values())}: {why}{hint}"


def _print_summary(p: dict[str, Any]) -> None:
    fr, se, chunks = p["fractions"], p["standard_errors"], p["chunks"]
    parts = [f"{k} {fr[k]:.4f} +- {se[k]:.4f}" for k in fr if fr[k] > 0.0]
    lines = [
        f"basin       {p['structure']} (lambda={p['lambda']:.6g}, zeta={p['zeta']:.6g}, "
        f"gamma={p['gamma']:.6g}), friction {p['friction']}",
        f"samples     {p['n']} in {p['elapsed_s']:.2f} s ({p['samples_per_second'] or 0:,.0f} samples/s) "
        f"[{p['backend']}]" + (f", {chunks['loaded']} of {chunks['total']} chunks resumed"
                               if chunks["loaded"] else ""),
        f"fractions   {', '.join(parts)} (binomial standard errors)",
    ]
    why = undetermined_line(p)
    if why:
        lines.append(why)
    for key in ("labels", "dataset", "plot"):
        if p[key]:
            lines.append(f"{key:<11} {p[key]}")
    typer.echo("\n".join(lines))


def register(app: typer.Typer) -> None:
    """Add the ``basin`` command to ``app``."""
    app.command("basin")(basin)
