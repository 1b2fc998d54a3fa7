"""Friction laws from text: the ``--friction`` syntax and measured friction tables (CSV).

The laws themselves live in :mod:`stickslip.model.friction`; this module only turns what a
user writes (``stribeck:vs=0.5,n=2``, a spreadsheet's ``v, mu`` export) into one of them,
with one-line errors in the model's words (the command line adds its flag name).
"""

from __future__ import annotations

from pathlib import Path

from stickslip.model.friction import (
    MAX_BANDS,
    CoulombFriction,
    FrictionLaw,
    LinearFriction,
    StribeckFriction,
    TableFriction,
    check_stribeck_parameter,
)
from stickslip.model.user_file import csv_rows, read_user_text


def _read_csv_text(path: str | Path) -> str:
    """The text of a friction table file (UTF-8, with or without a byte-order mark)."""
    return read_user_text(path, f"friction table {str(Path(path))!r}", hint="name the CSV file itself")


def read_friction_csv_columns(path: str | Path) -> tuple[list[float], list[float]]:
    """The ``v`` and ``mu`` columns of a measured friction curve (CSV with a header row).

    ``#`` starts a comment line. Returns the speeds and friction values as read (no units).
    A file with columns ``v`` and ``f`` (the dimensionless form) is refused (see
    :func:`friction_csv_columns`).
    Spreadsheet exports are read too: a UTF-8 byte-order mark, ``;`` separators and, with
    ``;``, decimal commas (``0,35``).

    Parameters
    ----------
    path : str or Path
        The CSV file.

    Returns
    -------
    tuple of list of float
        The speed and friction columns.
    """
    return friction_csv_columns(_read_csv_text(path), str(Path(path)))


def friction_csv_columns(text: str, p: str = "(text)") -> tuple[list[float], list[float]]:
    """The ``v`` [m/s] and ``mu`` columns of a friction curve given as CSV text.

    A dimensionless ``f`` column is refused: its numbers read as ``mu`` would be another law.

    The rules of :func:`read_friction_csv_columns` (which reads a file through this); ``p``
    names the source in error messages (an uploaded file's name, say).

    Parameters
    ----------
    text : str
        The CSV text.
    p : str
        Its name in error messages.

    Returns
    -------
    tuple of list of float
        The speed and friction columns.
    """
    second, v, y = _friction_csv(text, p)
    if second == "f":
        raise ValueError(
            f"friction table {p} gives f, the dimensionless form (f = (mu - mu_k)/(mu_s - mu_k) "
            "against v over the belt speed); a machine file's table takes v [m/s] and mu: "
            "convert it (mu = mu_k + f (mu_s - mu_k), v times the belt speed), or give the "
            "dimensionless table to a dimensionless command as --friction table:FILE.csv")
    return v, y


#: Largest magnitude of a friction table's entry (a speed in m/s, a friction coefficient):
#: far beyond any machine, and far from overflow once divided by a belt speed.
MAX_TABLE_VALUE = 1e6

#: The units a friction table's header may name: ``v [m/s]``, ``mu [-]`` (the app's uploader
#: and the docs write them so); another unit (``v [mm/s]``) is refused, not converted.
_HEADER_UNITS = {"v": ("m/s",), "mu": ("-", "1", ""), "f": ("-", "1", "")}


def _column_name(field: str, p: str) -> str:
    """A header field's column name, lower case, without a unit in brackets the column takes."""
    name = field.strip().lower()
    for left, right in (("[", "]"), ("(", ")")):
        if name.endswith(right) and left in name:
            base, unit = name[: name.index(left)].strip(), name[name.index(left) + 1:-1].strip()
            if base in _HEADER_UNITS:
                if unit.replace(" ", "") not in _HEADER_UNITS[base]:
                    raise ValueError(f"friction table {p}: column {base} is given in {unit!r}; "
                                     f"it takes {base} in {_HEADER_UNITS[base][0]}")
                return base
    return name


def _friction_csv(text: str, p: str) -> tuple[str, list[float], list[float]]:
    """``(name of the second column, "mu" or "f"; v; its values)`` of a friction CSV text."""
    if text.count("\n") > 8 * MAX_BANDS:  # a bound before any list of lines is made
        raise ValueError(f"friction table {p} has {text.count(chr(10))} lines, far more than "
                         f"the {MAX_BANDS - 1} points a table law takes")
    lines = [line for line in text.lstrip("\ufeff").splitlines()
             if line.strip() and not line.startswith("#")]
    # a spreadsheet in a locale with decimal commas separates its columns with ';'
    delimiter = ";" if lines and ";" in lines[0] and "," not in lines[0] else ","
    if len(lines) > MAX_BANDS:  # the header and MAX_BANDS - 1 points, counted before reading
        raise ValueError(f"friction table {p} has {len(lines) - 1} rows, more than the "
                         f"{MAX_BANDS - 1} points a table law takes")
    rows = csv_rows(lines, f"friction table {p}", delimiter)
    if len(rows) < 2:
        raise ValueError(f"friction table {p} needs a header row and at least one data row")
    header = [_column_name(h, p) for h in rows[0]]
    if "v" not in header or ("mu" not in header and "f" not in header):
        raise ValueError(f"friction table {p} needs columns v and mu (or v and f), got "
                         f"{len(header)} columns with other names")
    second = "mu" if "mu" in header else "f"
    iv = header.index("v")
    iy = header.index(second)

    def number(field: str) -> float:
        field = field.strip()
        return float(field.replace(",", ".") if delimiter == ";" else field)

    v: list[float] = []
    y: list[float] = []
    for k, row in enumerate(rows[1:], start=2):
        try:
            v.append(number(row[iv]))
            y.append(number(row[iy]))
        except (IndexError, ValueError):
            # the line itself is not quoted: the message never shows a file's content
            raise ValueError(f"friction table {p}, line {k}: not two numbers in columns "
                             f"{header[iv]} and {second}") from None
        if not (abs(v[-1]) <= MAX_TABLE_VALUE and abs(y[-1]) <= MAX_TABLE_VALUE):
            # an audit: v = 1e308 became "u=inf must be finite" once divided by the belt speed
            raise ValueError(f"friction table {p}, line {k}: {header[iv]} = {v[-1]!r}, "
                             f"{second} = {y[-1]!r}: each must be finite and at most "
                             f"{MAX_TABLE_VALUE:g} in magnitude")
    return second, v, y


def read_friction_table(
    path: str | Path, *, mu_s: float | None = None, mu_k: float | None = None, speed: float | None = None
) -> TableFriction:
    """Read a friction curve from a CSV file with a header row.

    Columns ``v`` [m/s] and ``mu`` [-] (then ``mu_s``, ``mu_k`` and the belt ``speed``
    [m/s] are required), or ``v`` and ``f`` for the dimensionless form (``v`` = sliding
    speed over belt speed, ``f = (mu - mu_k)/(mu_s - mu_k)``).

    Parameters
    ----------
    path : str or Path
        CSV with columns ``v``, ``f`` (dimensionless) or ``v`` [m/s], ``mu``.
    mu_s, mu_k : float, optional
        Friction coefficients, needed for a ``mu`` column.
    speed : float, optional
        Belt speed ``V``, m/s, needed for a ``mu`` column.

    Returns
    -------
    TableFriction
        The dimensionless law.
    """
    second, v, y = _friction_csv(_read_csv_text(path), str(Path(path)))
    if second == "f":
        return TableFriction(tuple(v), tuple(y))
    if mu_s is None or mu_k is None or speed is None:
        raise ValueError(f"friction table {path} gives mu: pass mu_s, mu_k and speed to make it "
                         "dimensionless, or give columns v (over the belt speed) and f")
    return TableFriction.from_physical(v, y, mu_s, mu_k, speed)


def _dimensionless_table(raw: str, path: str) -> TableFriction:
    """The table of ``table:FILE.csv`` (command-line text ``raw``): only the dimensionless form.

    A table of ``mu`` against ``v`` in m/s needs ``mu_s``, ``mu_k`` and the belt speed, which
    the dimensionless commands do not take: the message says how to give them.
    """
    second, v, y = _friction_csv(_read_csv_text(path), path)
    if second == "mu":
        raise ValueError(
            f"friction law {raw!r}: the table gives mu against v in m/s, which needs mu_s, mu_k "
            "and the belt speed V; on this command give it dimensionless, columns v = v_r/V and "
            "f = (mu - mu_k)/(mu_s - mu_k) (e.g. mu_s = 0.4, mu_k = 0.3, V = 0.05 m/s: v = v_r/0.05, "
            f"f = (mu - 0.3)/0.1), or name it in a machine file, [friction] table = {path!r} with "
            "mu_s, mu_k and speed under [system], and pass that file to --config (design, basin)"
        )
    return TableFriction(tuple(v), tuple(y))


FRICTION_SYNTAX = (
    "coulomb | linear:DELTA | table:FILE.csv | "
    "stribeck:vs=V_S[,n=N][,viscous=D_V][,mu0=R0][,tol=TOL]"
)


#: The keys of ``stribeck:`` on the command line and the :class:`StribeckFriction` fields they set.
STRIBECK_KEYS = {"vs": "velocity_ratio", "n": "exponent", "viscous": "viscous", "mu0": "mu0_ratio",
                 "tol": "tolerance"}


def parse_friction(text: str) -> FrictionLaw:
    """A friction law from its command-line text (dimensionless), see :data:`FRICTION_SYNTAX`.

    * ``coulomb``: the paper's law (the default);
    * ``linear:DELTA``: :class:`LinearFriction` with the dimensionless slope ``DELTA``
      (``mu(0+) = mu_k``; > 0 weakening, < 0 strengthening);
    * ``table:FILE.csv``: :class:`TableFriction` from a CSV with columns ``v`` (sliding speed
      over belt speed) and ``f = (mu - mu_k)/(mu_s - mu_k)``;
    * ``stribeck:vs=...,n=...,viscous=...,mu0=...,tol=...``: :class:`StribeckFriction` with
      ``vs = v_s / V``, exponent ``n`` (default 1), ``viscous = sigma_v W / (2 sqrt(m k))``
      (default 0), ``mu0 = (mu_0 - mu_k)/(mu_s - mu_k)`` (default 1) and the law tolerance
      ``tol`` in units of lambda (default 1e-4). Each key at most once, each value within
      :data:`STRIBECK_RANGES`; the law is tabulated here, so one that cannot be is refused.

    Parameters
    ----------
    text : str
        The law as text, one of the forms above (all values dimensionless).

    Returns
    -------
    FrictionLaw
        The law. A ``ValueError`` names the text and what is expected, in the model's words
        (the command line adds its flag name).
    """
    raw = str(text).strip()
    kind, _, arg = raw.partition(":")
    kind = kind.strip().lower()
    if kind == "coulomb" and not arg:
        return CoulombFriction()
    if kind == "linear":
        try:
            delta = float(arg)
        except ValueError:
            raise ValueError(f"friction law {raw!r}: linear needs a number, e.g. linear:0.05") from None
        try:
            return LinearFriction(delta)
        except ValueError as exc:
            raise ValueError(f"friction law {raw!r}: {exc}") from None
    if kind == "table" and arg:
        return _dimensionless_table(raw, arg.strip())
    if kind in ("rate-state", "lugre") and not arg.strip():
        example = ("lugre:sigma0=1e5,sigma1=316,sigma2=0.4,mu_c=1,mu_s=1.5,vs=0.001" if kind == "lugre"
                   else "rate-state:a=0.01,b=0.015,dc=0.01,mu_ref=0.6,vref=0.001")
        raise ValueError(f"friction law {raw!r} needs its parameters, e.g. {example}")
    if kind in ("rate-state", "lugre"):
        raise ValueError(f"friction law {raw!r}: friction with memory is not taken here (it runs on "
                         "simulate with --friction, and on every --config command but tune)")
    if kind == "stribeck" and arg:
        names = STRIBECK_KEYS
        values: dict[str, float] = {}
        for item in arg.split(","):
            key, eq, value = item.partition("=")
            key = key.strip().lower()
            if not eq or key not in names:
                raise ValueError(f"friction law {raw!r}: {item.strip()!r} is not one of "
                                 f"{', '.join(k + '=...' for k in names)}")
            if names[key] in values:
                raise ValueError(f"friction law {raw!r}: key {key!r} given twice")
            try:
                number = float(value)
            except ValueError:
                raise ValueError(f"friction law {raw!r}: {key}={value.strip()!r} is not a number") from None
            try:
                values[names[key]] = check_stribeck_parameter(names[key], number, key)
            except ValueError as exc:
                raise ValueError(f"friction law {raw!r}: {exc}") from None
        if "velocity_ratio" not in values:
            raise ValueError(f"friction law {raw!r}: stribeck needs vs=V_S/V, e.g. stribeck:vs=0.5")
        law = StribeckFriction(**values)
        try:
            law.nodes()  # tabulated now (and cached): a law that cannot be is refused before any run
        except ValueError as exc:
            raise ValueError(f"friction law {raw!r}: {exc}") from None
        return law
    raise ValueError(f"friction law {raw!r} is not one of: {FRICTION_SYNTAX}")
