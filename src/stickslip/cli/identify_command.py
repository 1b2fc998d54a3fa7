"""``stickslip identify``: stiffness, damping and a friction law from a measured record (issue 19)."""

from __future__ import annotations

import itertools
import math
from pathlib import Path
from typing import Annotated, Any

import typer

from stickslip.cli.console import BadInput, check_figure_path, check_output_path, print_json
from stickslip.model.user_file import read_user_text

#: Quantities the user may hold fixed, with the unit family ``to_si`` checks.
_FIXABLE = ("k", "c", "mu_s", "mu_k", "slope", "stribeck_velocity", "exponent", "viscous")


def _parse_fixed(items: list[str]) -> dict[str, float]:
    from stickslip.model.units import to_si

    out: dict[str, float] = {}
    for item in items:
        name, eq, value = item.partition("=")
        name = name.strip()
        if not eq or name not in (*_FIXABLE, "force_offset", "force_drift"):
            raise BadInput(f"--fix {item!r} must be NAME=VALUE with NAME one of "
                           f"{', '.join((*_FIXABLE, 'force_offset', 'force_drift'))}")
        if name in out:
            raise BadInput(f"--fix {name} is given twice; give each parameter once")
        if name in ("force_offset", "force_drift"):
            try:
                out[name] = float(value)
            except ValueError:
                raise BadInput(f"--fix {item!r}: {value!r} is not a number (SI: N or N/s)") from None
            if not math.isfinite(out[name]):
                raise BadInput(f"--fix {item!r}: {name} must be finite")
        else:
            out[name] = to_si(name, value.strip(), source=f"--fix {name} =")
    return out


def _parse_table_speeds(text: str) -> list[float]:
    """``--table-speeds "0, 1 cm/s, 3 cm/s"``: knot speeds [m/s], units allowed on each."""
    from stickslip.analysis.identification.record_fit import MAX_TABLE_KNOTS
    from stickslip.model.units import to_si

    items = [item.strip() for item in text.split(",")]
    if not 2 <= len(items) <= MAX_TABLE_KNOTS or not all(items):
        raise BadInput(f"--table-speeds {text!r} must list 2 to {MAX_TABLE_KNOTS} speeds separated by commas")
    speeds = [to_si("speed", item, source="--table-speeds") for item in items]
    if any(v < 0.0 for v in speeds) or any(b <= a for a, b in itertools.pairwise(speeds)):
        raise BadInput(f"--table-speeds {text!r} must be non-negative and increase strictly")
    return speeds


# Over 120 lines: Typer declares each of the command's sixteen options in this signature (half
# of its length) and the docstring is the help text; the body checks every input before any work.
def identify(
    record: Annotated[Path, typer.Argument(help="CSV record: t and F and/or x (and v); see --columns")],
    load: Annotated[str, typer.Option("--load", help="normal load W [N]; units allowed")],
    mass: Annotated[str | None, typer.Option(
        "--mass", help="slider mass [kg]; units allowed, e.g. '2 kg' (required but for "
        "--law rate-state)")] = None,
    speed: Annotated[str | None, typer.Option(
        "--speed", help="belt or drive speed V [m/s]; units allowed (required but for "
        "--law rate-state)")] = None,
    law: Annotated[str, typer.Option(
        "--law", help="coulomb | linear | stribeck | table | auto; rate-state (a velocity-step "
        "record: columns t, load-point displacement, mu; with --stiffness) or lugre (columns t, "
        "sliding velocity, friction force)")] = "coulomb",
    stiffness: Annotated[str | None, typer.Option(
        "--stiffness", help="--law rate-state: the machine stiffness k [N/m]; units allowed")] = None,
    evolution: Annotated[str, typer.Option(
        "--evolution", help="--law rate-state: aging | slip")] = "aging",
    columns: Annotated[
        str | None,
        typer.Option("--columns", help="roles of the columns: t,x,F (file order), "
                     "'t=time:ms,F=-load:kN' (ROLE=[-]NAME[:UNIT]) or a TOML file with [columns.F] ..."),
    ] = None,
    fix: Annotated[
        list[str] | None, typer.Option("--fix", help="hold a parameter fixed, e.g. --fix 'c=0.5 N*s/m'")
    ] = None,
    table_speeds: Annotated[
        str | None,
        typer.Option("--table-speeds", help="table law: knot speeds, e.g. '0, 1 cm/s, 3 cm/s' "
                     "(default: 0 and quantiles of the record's sliding speeds)"),
    ] = None,
    offset: Annotated[
        str, typer.Option("--offset", help="force offset and drift: auto (fit with x) | fit | zero")
    ] = "auto",
    bootstrap: Annotated[int, typer.Option("--bootstrap", help="bootstrap refits over cycles (0: none)")] = 0,
    write_config: Annotated[
        Path | None, typer.Option("--write-config", help="write the fitted machine file (TOML) here")
    ] = None,
    plot: Annotated[Path | None, typer.Option("--plot", help="write the fit figure here")] = None,
    overwrite: Annotated[bool, typer.Option("--overwrite", help="replace existing output files")] = False,
    json: Annotated[bool, typer.Option("--json", help="print one JSON object and nothing else")] = False,
) -> None:
    """Fit k, c and a friction law to a measured stick-slip record, with uncertainties.

    Example: stickslip identify examples/rig_record.csv --mass "1 kg" --load "100 N" --speed "5 cm/s" --json

    Then: stickslip identify ... --write-config machine.toml; stickslip design --config machine.toml

    A velocity-step record (rate-and-state: a, b, d_c, mu_ref of the quasi-static slider):

    Example: stickslip identify examples/friction_memory/velocity_steps.csv --law rate-state
    --stiffness "1e7 N/m" --load "1 kN" --json

    LuGre from imposed motion (t, sliding velocity, force):

    Example: stickslip identify examples/friction_memory/lugre_sine.csv --law lugre --load "1 N" --json
    """
    from stickslip.analysis.identification.record_fit import LAWS, check_known
    from stickslip.analysis.identification.record_fit import identify as run_identify
    from stickslip.io.atomic import atomic_write_text
    from stickslip.io.record import parse_columns, read_columns_toml, read_record
    from stickslip.model.units import to_si

    if law.strip().lower() == "lugre":
        _identify_lugre(record, load=load,
                        given={"--mass": mass, "--speed": speed, "--columns": columns, "--fix": fix,
                               "--table-speeds": table_speeds, "--write-config": write_config,
                               "--plot": plot, "--stiffness": stiffness,
                               "--evolution": None if evolution == "aging" else evolution},
                        bootstrap=bootstrap, offset=offset, json=json)
        return
    if law.strip().lower() == "rate-state":
        _identify_rate_state(record, load=load, stiffness=stiffness, evolution=evolution,
                             given={"--mass": mass, "--speed": speed, "--columns": columns,
                                    "--fix": fix, "--table-speeds": table_speeds,
                                    "--write-config": write_config, "--plot": plot},
                             bootstrap=bootstrap, offset=offset, json=json)
        return
    if stiffness is not None:
        raise BadInput("--stiffness is for --law rate-state (a velocity-step record)")
    if evolution != "aging":
        raise BadInput(f"--evolution {evolution!r} is for --law rate-state (a velocity-step record)")
    for flag, given in (("--mass", mass), ("--speed", speed)):
        if given is None:
            raise BadInput(f"{flag} is required (the slider's mass and the belt speed of the record)")
    assert mass is not None and speed is not None
    known = {"m": to_si("m", mass, source="--mass"), "load": to_si("load", load),
             "speed": to_si("speed", speed)}
    for name, value in known.items():
        if value <= 0.0:
            raise BadInput(f"--{'mass' if name == 'm' else name} {value!r} must be positive")
    law = law.strip().lower()
    if law not in (*LAWS, "auto"):
        raise BadInput(f"--law {law!r} is not one of {', '.join(LAWS)}, auto")
    if offset not in ("auto", "fit", "zero"):
        raise BadInput(f"--offset {offset!r} is not one of auto, fit, zero")
    if bootstrap < 0 or bootstrap > 10_000:
        raise BadInput(f"--bootstrap {bootstrap} must lie between 0 and 10000")
    fixed = _parse_fixed(fix or [])
    try:
        check_known(fixed, law)
    except ValueError as exc:
        raise BadInput(f"--fix {exc}") from None
    known.update(fixed)
    knots = None
    if table_speeds is not None:
        if law != "table":
            raise BadInput(f"--table-speeds is for --law table, not --law {law}")
        knots = _parse_table_speeds(table_speeds)
    if write_config is not None:
        check_output_path(write_config, overwrite=overwrite, option="--write-config")
        if write_config.suffix.lower() != ".toml":
            raise BadInput(f"--write-config {str(write_config)!r} must end in .toml")
        if law == "table":  # the table law's CSV is written beside it
            check_output_path(write_config.with_suffix(".friction.csv"), overwrite=overwrite,
                              option="--write-config (its table law file)")
    if plot is not None:
        check_figure_path(plot, overwrite=overwrite)
    spec = None
    if columns is not None:
        is_file = columns.strip().lower().endswith(".toml")
        spec = read_columns_toml(columns) if is_file else parse_columns(columns)
    data = read_record(record, spec)
    fit_offset = None if offset == "auto" else offset == "fit"
    from stickslip.cli.console import show_progress
    from stickslip.cli.progress import ProgressBar

    with ProgressBar(show_progress() and bootstrap > 0, "bootstrap refits", "fits",
                     shorten="--bootstrap sets fewer refits (Ctrl-C stops it)") as bar:
        result = run_identify(data, known, law=law, bootstrap=bootstrap, fit_offset=fit_offset,
                              table_speeds=knots, progress=bar if bootstrap > 0 else None)
    payload = result.to_dict()
    for warning in result.warnings:
        typer.echo(f"stickslip: warning: {warning}", err=True)
    if write_config is not None:
        table_name = write_config.with_suffix(".friction.csv").name
        text = result.to_config(table_file=table_name)
        if result.law == "table":
            atomic_write_text(write_config.with_name(table_name), result.table_csv())
        atomic_write_text(write_config, text)
        payload["config"] = str(write_config)
    if plot is not None:
        payload["plot"] = str(result.plot().savefig(plot))
    if json:
        print_json(payload)
        return
    typer.echo(result.summary())
    for key in ("config", "plot"):
        if key in payload:
            typer.echo(f"{key:<8} {payload[key]}")


def _identify_rate_state(record: Path, *, load: str, stiffness: str | None, evolution: str,
                         given: dict[str, Any], bootstrap: int, offset: str, json: bool) -> None:
    """``identify --law rate-state``: :func:`~stickslip.analysis.identification.rate_state_fit.fit_rate_state`
    on a CSV of time (s), load-point displacement (m) and friction coefficient, in that order
    (a header line is skipped)."""

    from stickslip.analysis.identification.rate_state_fit import fit_rate_state
    from stickslip.model.units import to_si

    for flag, value in given.items():
        if value:
            raise BadInput(f"{flag} is not used by --law rate-state (columns: t [s], load-point "
                           "displacement [m], mu; options --stiffness, --load, --evolution)")
    if bootstrap or offset != "auto":
        raise BadInput("--bootstrap and --offset are not used by --law rate-state")
    if stiffness is None:
        raise BadInput("--law rate-state needs --stiffness (the machine stiffness k, e.g. '1e7 N/m')")
    k = to_si("k", stiffness, source="--stiffness")
    normal = to_si("load", load, source="--load")
    for flag, value in (("--stiffness", k), ("--load", normal)):
        if not value > 0.0:
            raise BadInput(f"{flag} {value!r} must be positive")
    if evolution not in ("aging", "slip"):
        raise BadInput(f"--evolution {evolution!r} must be aging or slip")
    data = _three_columns(record, "t [s], load-point displacement [m], mu", ("t", "x", "mu"))
    try:
        fit = fit_rate_state(data[:, 0], data[:, 1], data[:, 2], stiffness=k, load=normal,
                             evolution=evolution)
    except ValueError as exc:
        raise BadInput(f"record {str(record)!r}: {exc}") from None
    _memory_fit_out(fit, record, json)


def _memory_fit_out(fit: Any, record: Path, json: bool) -> None:
    """A rate-and-state or LuGre fit on stdout (``--json``: its dict and the record), its
    warnings on stderr when the summary (which holds them) is not printed."""
    payload = fit.to_dict()
    payload["record"] = str(record)
    if json:
        for warning in fit.warnings:
            typer.echo(f"stickslip: warning: {warning}", err=True)
        print_json(payload)
        return
    typer.echo(fit.summary())


def _three_columns(record: Path, what: str, roles: tuple[str, str, str]) -> Any:
    """The record's three numeric columns in SI, ``(n, 3)``; one line each for an unreadable
    file, a bad row or a bad unit.

    A first line that is not numbers is the header; a unit in brackets or parentheses after a
    column's name (``x [um]``, ``t (ms)``) converts that column to SI (``roles``: the
    :data:`stickslip.io.record.ROLES` of the columns, ``mu`` for a friction coefficient,
    which takes no unit). Without one the column is read in SI.
    """
    import numpy as np

    from stickslip.io.record import MAX_RECORD_BYTES

    try:
        text = read_user_text(record, f"record {str(record)!r}", max_bytes=MAX_RECORD_BYTES,
                              hint="give the CSV file itself")
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    rows: list[list[float]] = []
    factors = np.ones(3)
    for number, line in enumerate(text.splitlines(), start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        parts = [p.strip() for p in line.split(",")]
        try:
            values = [float(p) for p in parts]
        except ValueError:
            if not rows and number == 1:
                factors = _header_factors(record, parts, roles)
                continue  # the header
            raise BadInput(f"record {str(record)!r}, line {number}: not three numbers ({what})") from None
        if len(values) != 3:
            raise BadInput(f"record {str(record)!r}, line {number}: {len(values)} columns, "
                           f"expected 3 ({what})")
        rows.append(values)
    return np.array(rows, dtype=np.float64).reshape(-1, 3) * factors[None, :]


def _header_factors(record: Path, names: list[str], roles: tuple[str, str, str]) -> Any:
    """SI factors of the header's units (1 where a column has none); one line for a bad unit."""
    import numpy as np

    from stickslip.io.record import RecordError, header_unit, unit_factor

    factors = np.ones(3)
    for i, (name, role) in enumerate(zip(names[:3], roles, strict=False)):
        unit = header_unit(name)
        if unit is None:
            continue
        if role == "mu":
            if unit.strip() not in ("", "1", "-"):
                raise BadInput(f"record {str(record)!r}, column {name!r}: the friction "
                               "coefficient takes no unit (a plain number, not percent)")
            continue
        try:
            factors[i] = unit_factor(role, unit, f"record {str(record)!r}, column {name!r}")
        except RecordError as exc:
            raise BadInput(str(exc)) from None
    return factors


def _identify_lugre(record: Path, *, load: str, given: dict[str, Any], bootstrap: int,
                    offset: str, json: bool) -> None:
    """``identify --law lugre``: :func:`~stickslip.analysis.identification.lugre_fit.fit_lugre` on a CSV of
    time (s), sliding velocity (m/s) and friction force (N), in that order."""
    from stickslip.analysis.identification.lugre_fit import fit_lugre
    from stickslip.model.units import to_si

    for flag, value in given.items():
        if value:
            raise BadInput(f"{flag} is not used by --law lugre (columns: t [s], sliding velocity "
                           "[m/s], friction force [N]; option --load)")
    if bootstrap or offset != "auto":
        raise BadInput("--bootstrap and --offset are not used by --law lugre")
    normal = to_si("load", load, source="--load")
    if not normal > 0.0:
        raise BadInput(f"--load {normal!r} must be positive")
    data = _three_columns(record, "t [s], sliding velocity [m/s], friction force [N]", ("t", "v", "F"))
    try:
        fit = fit_lugre(data[:, 0], data[:, 1], data[:, 2], load=normal)
    except ValueError as exc:
        raise BadInput(f"record {str(record)!r}: {exc}") from None
    _memory_fit_out(fit, record, json)


def register(app: typer.Typer) -> None:
    """Add the ``identify`` command to ``app``."""
    app.command("identify")(identify)
