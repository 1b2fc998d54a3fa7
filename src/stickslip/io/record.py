"""Read a measured stick-slip record (CSV) into SI units and the rig's sign conventions.

The record is a CSV file with a header row (``#`` starts a comment line). Its roles:

* ``t``: time (default unit s);
* ``x``: the slider's displacement from where the spring is relaxed, positive along the belt's
  motion (default m);
* ``v``: the slider's velocity (default m/s);
* ``F``: the load-cell force between the spring-damper and the slider, ``F = k x + c x'``,
  tension positive (default N).

Without a column specification the header names are the roles (``t``, ``x``, ``v``, ``F``;
``time``, ``force``, ``displacement`` and ``velocity`` too), and a unit may follow in brackets:
``F [kN]``, ``x (mm)``. A specification maps roles to columns, with an optional unit and sign:

* on the command line, ``--columns "t=time:ms,x=-disp:mm,F=load:kN"`` (``ROLE=[-]NAME[:UNIT]``;
  ``--columns t,x,F`` names the columns of each role in a header-less order);
* in a small TOML file, one table per role::

      [columns.F]
      name = "load"
      unit = "kN"
      sign = -1       # the load cell reads compression positive

Units are converted by pint; a unit of the wrong dimension is refused with one line.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from stickslip.analysis.identification.estimates import (
    MeasuredRecord,
    RecordError,
    check_record_length,
)
from stickslip.io.toml_file import read_toml_file
from stickslip.model.units import POWER_RULE, unit_powers_bounded
from stickslip.model.user_file import csv_rows, read_user_text

ROLES: dict[str, tuple[str, str]] = {
    "t": ("[time]", "s"),
    "x": ("[length]", "m"),
    "v": ("[length] / [time]", "m/s"),
    "F": ("[force]", "N"),
}
ALIASES = {"t": "t", "time": "t", "x": "x", "displacement": "x", "v": "v", "velocity": "v",
           "f": "F", "force": "F"}
_HEADER_UNIT = re.compile(r"^\s*(.*?)\s*(?:\[(.*)\]|\((.*)\))\s*$")


@dataclass(frozen=True)
class ColumnSpec:
    """Where one role is in the file: column ``name``, its ``unit`` and a ``sign`` (+1 or -1)."""

    role: str
    name: str
    unit: str | None = None
    sign: float = 1.0


def header_unit(column: str) -> str | None:
    """The unit in brackets or parentheses after a header's column name (``x [um]``), or None.

    Parameters
    ----------
    column : str
        One header cell.

    Returns
    -------
    str or None
        The unit's text, None when the cell names no unit.
    """
    m = _HEADER_UNIT.match(column)
    return None if m is None else (m.group(2) if m.group(2) is not None else m.group(3))


def unit_factor(role: str, unit: str | None, where: str) -> float:
    """Factor taking values in ``unit`` to the role's SI unit (pint); 1 for no unit."""
    if unit is None or not unit.strip():
        return 1.0
    import pint

    dim, si = ROLES[role]
    if not unit_powers_bounded(unit):
        raise RecordError(f"{where}: unit {unit!r}: {POWER_RULE}")
    ureg = pint.get_application_registry()
    try:
        quantity = ureg.Quantity(1.0, ureg.parse_units(unit.strip()))
    except Exception:
        raise RecordError(f"{where}: {unit!r} is not a unit pint understands") from None
    if not quantity.check(dim):
        raise RecordError(f"{where}: unit {unit!r} is not a {dim} unit for column role {role} "
                          f"(expected something convertible to {si})")
    return float(quantity.to(si.replace("/", " / ")).magnitude)


def parse_columns(text: str) -> list[ColumnSpec]:
    """``--columns`` text: ``t,x,F`` (roles in file order) or ``ROLE=[-]NAME[:UNIT],...``."""
    specs: list[ColumnSpec] = []
    for item in (p.strip() for p in text.split(",")):
        if not item:
            raise RecordError(f"--columns {text!r}: empty entry")
        role, eq, rest = item.partition("=")
        role = ALIASES.get(role.strip().lower(), role.strip())
        if role not in ROLES:
            raise RecordError(f"--columns {text!r}: {item!r} does not start with a role t, x, v or F")
        if not eq:
            specs.append(ColumnSpec(role, f"#{len(specs)}"))
            continue
        sign = 1.0
        rest = rest.strip()
        if rest.startswith("-"):
            sign, rest = -1.0, rest[1:].strip()
        name, _, unit = rest.partition(":")
        if not name.strip():
            raise RecordError(f"--columns {text!r}: {item!r} names no column")
        specs.append(ColumnSpec(role, name.strip(), unit.strip() or None, sign))
    roles = [s.role for s in specs]
    if len(set(roles)) != len(roles):
        raise RecordError(f"--columns {text!r} gives a role twice")
    return specs


def read_columns_toml(path: str | Path) -> list[ColumnSpec]:
    """A column specification from a TOML file with ``[columns.ROLE]`` tables (name, unit, sign)."""
    p = Path(path)
    if p.exists() and not p.is_file():
        raise RecordError(f"--columns {str(p)!r} is not a regular file (a folder, FIFO or device)")
    try:
        data = read_toml_file(p, f"--columns {str(p)!r}")
    except ValueError as exc:
        raise RecordError(str(exc)) from None
    table = data.get("columns")
    if not isinstance(table, dict) or not table:
        raise RecordError(f"--columns {str(p)!r} needs [columns.t], [columns.F], ... tables")
    specs = []
    for role_text, entry in table.items():
        role = ALIASES.get(role_text.lower(), role_text)
        where = f"--columns {str(p)!r}: [columns.{role_text}]"
        if role not in ROLES or not isinstance(entry, dict):
            raise RecordError(f"{where} is not a role t, x, v or F")
        unknown = sorted(set(entry) - {"name", "unit", "sign"})
        if unknown:
            raise RecordError(f"{where}: unknown keys {', '.join(unknown)} (allowed: name, unit, sign)")
        sign = entry.get("sign", 1)
        if isinstance(sign, bool) or sign not in (1, -1):
            raise RecordError(f"{where} sign = {sign!r} must be 1 or -1")
        name = entry.get("name", role_text)
        unit = entry.get("unit")
        for key, value, example in (("name", name, '"load"'), ("unit", unit, '"kN"')):
            if value is not None and (not isinstance(value, str) or not value.strip()):
                raise RecordError(f"{where} {key} = {value!r} must be a text in quotes, e.g. "
                                  f"{key} = {example}")
        specs.append(ColumnSpec(role, str(name), unit, float(sign)))
    roles = [s.role for s in specs]
    if len(set(roles)) != len(roles):
        raise RecordError(f"--columns {str(p)!r} gives a role twice")
    return specs


#: Largest record read, bytes: 1 GiB (about 3e7 rows of four numbers). A larger file, or
#: anything that is not a regular file (a FIFO, ``/dev/zero``), is refused before it is read.
MAX_RECORD_BYTES = 1024**3


def _record_text(p: Path) -> str:
    """The text of the record file ``p`` (UTF-8, a byte-order mark dropped), checked first."""
    try:
        return read_user_text(p, f"record {str(p)!r}", max_bytes=MAX_RECORD_BYTES,
                              hint="give the CSV file itself")
    except ValueError as exc:
        raise RecordError(str(exc)) from None


def read_record(path: str | Path, columns: list[ColumnSpec] | None = None) -> MeasuredRecord:
    """Read a record CSV into a :class:`MeasuredRecord` (SI units, the rig's signs).

    UTF-8 with or without a byte-order mark; at most :data:`MAX_RECORD_BYTES`; a regular file.
    """
    p = Path(path)
    return record_from_text(_record_text(p), str(p), columns)


def record_from_text(text: str, name: str, columns: list[ColumnSpec] | None = None) -> MeasuredRecord:
    """A record given as CSV text (an uploaded file), read as :func:`read_record` reads a file.

    Parameters
    ----------
    text : str
        The CSV text.
    name : str
        How messages name it (a file's path, an upload's name); the record's ``source`` is
        its last path component.
    columns : list of ColumnSpec, optional
        The roles of the columns (default: from the header's names).

    Returns
    -------
    MeasuredRecord
        In SI units, with the rig's signs.
    """
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    check_record_length(repr(name), len(lines) - 1)  # before its rows are parsed
    if len(lines) < 2:
        raise RecordError(f"record {name!r} needs a header row and data rows")
    try:
        rows = csv_rows(lines, f"record {name!r}")
    except ValueError as exc:
        raise RecordError(str(exc)) from None
    header_raw = [h.strip() for h in rows[0]]
    header: list[tuple[str, str | None]] = []
    for h in header_raw:
        m = _HEADER_UNIT.match(h)
        header.append((m.group(1), m.group(2) or m.group(3)) if m else (h, None))
    names = [n for n, _ in header]
    if columns is None:
        columns = []
        for (column, unit) in header:  # not ``name``: that is the record's, for messages
            role = ALIASES.get(column.lower())
            if role is not None and role in [c.role for c in columns]:
                raise RecordError(f"record {name!r}: two columns of the header "
                                  f"({', '.join(header_raw)}) are the {role} channel; name the "
                                  "one to use with --columns")
            if role is not None:
                columns.append(ColumnSpec(role, column, unit))
        if not any(c.role == "t" for c in columns):
            raise RecordError(f"record {name!r}: no time column (header {', '.join(header_raw)}); "
                              "name one t or give --columns")
    values: list[list[float]] = []
    for i, row in enumerate(rows[1:], start=2):  # row i of the file's data (the header is 1)
        if len(row) != len(header):
            raise RecordError(f"record {name!r}, data row {i}: {len(row)} values, the header "
                              f"names {len(header)}")
        try:
            values.append([float(v) for v in row])
        except ValueError:
            raise RecordError(f"record {name!r}, data row {i}: not all numbers") from None
    data = np.array(values, dtype=np.float64)
    if data.ndim != 2 or data.shape[1] != len(header):
        raise RecordError(f"record {name!r}: rows do not all have {len(header)} values")
    arrays: dict[str, Any] = {}
    for spec in columns:
        if spec.name.startswith("#"):
            idx = int(spec.name[1:])
        elif spec.name in names:
            idx = names.index(spec.name)
        else:
            raise RecordError(f"record {name!r} has no column {spec.name!r} (columns: {', '.join(names)})")
        if idx >= len(names):
            raise RecordError(f"record {name!r} has {len(names)} columns, fewer than --columns names")
        unit = spec.unit if spec.unit is not None else header[idx][1]
        factor = unit_factor(spec.role, unit, f"record {name!r}, column {names[idx]!r}")
        arrays[spec.role] = spec.sign * factor * data[:, idx]
    if "t" not in arrays:
        raise RecordError("the column specification has no time column t")
    return MeasuredRecord(arrays.pop("t"), source=Path(name).name, **arrays)


def write_record(path: str | Path, record: MeasuredRecord, *, comment: str = "") -> Path:
    """Write a record as CSV with SI units in the header (``t [s]``, ``x [m]``, ``F [N]``)."""
    from stickslip.io.atomic import atomic_write_text

    cols = ["t", *record.channels]
    units = {"t": "s", **{r: ROLES[r][1] for r in record.channels}}
    table = np.column_stack([record.t] + [getattr(record, c) for c in record.channels])
    head = "".join(f"# {ln}\n" for ln in comment.splitlines())
    body = "\n".join(",".join(f"{x:.9g}" for x in row) for row in table)
    atomic_write_text(path, head + ",".join(f"{c} [{units[c]}]" for c in cols) + "\n" + body + "\n")
    return Path(path)
