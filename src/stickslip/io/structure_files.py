"""Structure matrices from files or inline arrays, with their units (DESIGN.md section 10).

Formats: Matrix Market ``.mtx`` (what finite-element programs export; read with
``scipy.io.mmread``, sparse or dense, ``symmetric`` storage expanded), NumPy ``.npy``, and
``.csv`` (comma or semicolon separated numbers, no header), or an inline TOML array of rows.
Every problem is one ``ValueError`` line naming the file (or key) and why.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.model.units import to_si

FloatArray = NDArray[np.float64]

#: Largest number of entries of a dense matrix read from a file (a 5,000-DOF dense matrix);
#: larger models must come as sparse Matrix Market files.
MAX_DENSE_ENTRIES = 25_000_000

#: Largest Matrix Market model read (DOF); beyond, even the sparse reduction is out of reach.
MAX_SPARSE_DOF = 1_000_000


def unit_factor(quantity: str, unit: object, *, source: str) -> float:
    """SI value of one ``unit`` of ``quantity`` (``"kN/m"`` for a stiffness: 1000.0)."""
    if not isinstance(unit, str) or not unit.strip():
        raise ValueError(f"{source} = {unit!r} must be a unit such as 'kg' or 'N/m'")
    return to_si(quantity, f"1 {unit.strip()}", source=source)


def _read_file(path: Path, source: str) -> Any:
    import scipy.io
    import scipy.sparse

    if not path.is_file():
        raise ValueError(f"{source}: file {str(path)!r} does not exist")
    suffix = path.suffix.lower()
    try:
        if suffix == ".mtx":
            with path.open("rb") as handle:
                header = handle.readline().decode("ascii", "replace")
            if not header.lower().startswith("%%matrixmarket"):
                raise ValueError("it has no %%MatrixMarket header")
            if " complex" in header.lower():
                raise ValueError("it holds complex numbers; the matrices must be real")
            rows, cols, _entries, fmt, _field, _symm = scipy.io.mminfo(str(path))
            if rows != cols:
                raise ValueError(f"it is {rows}x{cols}, not square")
            if rows > MAX_SPARSE_DOF:
                raise ValueError(f"it has {rows} DOF, beyond the supported {MAX_SPARSE_DOF}")
            if fmt == "array" and rows * cols > MAX_DENSE_ENTRIES:
                raise ValueError(f"it is a dense {rows}x{cols} array; store large models sparse "
                                 "(coordinate format)")
            data = scipy.io.mmread(str(path))
            if scipy.sparse.issparse(data):
                return scipy.sparse.csr_matrix(data, dtype=np.float64)
            return np.asarray(data, dtype=np.float64)
        if suffix == ".npy":
            data = np.load(path, allow_pickle=False, mmap_mode="r")
            if data.size > MAX_DENSE_ENTRIES:
                raise ValueError(f"it holds {data.size} entries, beyond {MAX_DENSE_ENTRIES} (use a "
                                 "sparse .mtx for large models)")
            if not np.issubdtype(data.dtype, np.number) or np.issubdtype(data.dtype, np.complexfloating):
                raise ValueError(f"it holds {data.dtype} values, not real numbers")
            return np.array(data, dtype=np.float64)
        if suffix == ".csv":
            text = path.read_text(encoding="utf-8-sig")
            delimiter = ";" if ";" in text and "," not in text else ","
            rows_out = [[float(x) for x in line.split(delimiter)]
                        for line in text.splitlines() if line.strip()]
            return np.array(rows_out, dtype=np.float64)
    except ValueError as exc:
        raise ValueError(f"{source}: {str(path)!r} cannot be read: {exc}") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ValueError(f"{source}: {str(path)!r} cannot be read: {exc}") from None
    raise ValueError(f"{source}: {str(path)!r} has suffix {suffix!r}; use .mtx, .npy or .csv")


def read_matrix(spec: object, *, quantity: str, unit: object = None,
                base_dir: Path | None = None, source: str = "matrix") -> Any:
    """One structure matrix in SI units: a dense array, or a ``scipy.sparse`` CSR matrix.

    Parameters
    ----------
    spec : str or list of lists
        A path (relative to ``base_dir``) to ``.mtx``, ``.npy`` or ``.csv``, or the matrix
        itself as rows.
    quantity : {"mass", "stiffness", "damping"}
        What it holds (its SI unit: kg, N/m, N s/m).
    unit : str, optional
        The unit of the entries (``"kg"``, ``"kN/m"``, ``"N*s/m"``); SI when None.
    source : str
        How the message names the value (file and key).

    Returns
    -------
    ndarray or scipy.sparse.csr_matrix
        Square, finite, in SI units; symmetry and definiteness are checked by
        :func:`stickslip.model.structure.checked_matrices` (or the reduction) next.
    """
    import scipy.sparse

    factor = 1.0 if unit is None else unit_factor(quantity, unit, source=f"{source}_unit")
    if isinstance(spec, str):
        path = Path(spec)
        if base_dir is not None and not path.is_absolute():
            path = base_dir / path
        data = _read_file(path, f"{source} = {spec!r}")
        where = f"{source} = {spec!r}"
    elif isinstance(spec, list):
        where = f"{source} (inline)"
        try:
            data = np.array(spec, dtype=np.float64)
        except (TypeError, ValueError):
            raise ValueError(f"{where} must be a list of rows of numbers of equal length") from None
    else:
        raise ValueError(f"{source} = {spec!r} must be a file path (.mtx, .npy, .csv) or a list of rows")
    shape = data.shape
    if len(shape) != 2 or shape[0] != shape[1] or shape[0] == 0:
        raise ValueError(f"{where} must be a non-empty square matrix, got shape {shape}")
    values = data.data if scipy.sparse.issparse(data) else data
    if not np.all(np.isfinite(values)):
        raise ValueError(f"{where} has NaN or infinite entries")
    return data * factor if factor != 1.0 else data
