"""Structure matrices from files or inline arrays, with their units.

Formats: Matrix Market ``.mtx`` (what finite-element programs export; read with
``scipy.io.mmread``, sparse or dense, ``symmetric`` storage expanded), NumPy ``.npy``, and
``.csv`` (comma or semicolon separated numbers, no header), or an inline TOML array of rows.
Every problem is one ``ValueError`` line naming the file (or key) and why.
"""

from __future__ import annotations

import contextlib
import io
import tokenize
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.model.physical import MAX_SI
from stickslip.model.units import to_si
from stickslip.model.user_file import note_input

FloatArray = NDArray[np.float64]

#: Largest number of entries of a dense matrix read from a file (a 5,000-DOF dense matrix);
#: larger models must come as sparse Matrix Market files.
MAX_DENSE_ENTRIES = 25_000_000

#: Largest Matrix Market model read (DOF); beyond, even the sparse reduction is out of reach.
MAX_SPARSE_DOF = 1_000_000

#: Fewest bytes one entry takes in a Matrix Market file: ``"1 1\n"`` in coordinate format (a
#: pattern entry; a real one takes 6), ``"1\n"`` in array format. A header that declares more
#: entries than the file's size can hold is refused before anything is allocated.
MTX_MIN_ENTRY_BYTES = {"coordinate": 4, "array": 2}

#: Largest ``.csv`` matrix file read, bytes: :data:`MAX_DENSE_ENTRIES` numbers of 32 characters.
MAX_CSV_BYTES = 32 * MAX_DENSE_ENTRIES

#: The first bytes of a ``.npy`` file, and of what is sometimes saved under that name instead.
NPY_MAGIC = b"\x93NUMPY"
_NOT_NPY = {b"PK\x03\x04": "a .npz archive (numpy.savez), not one array; save the matrix with "
                            "numpy.save",
            b"\x80": "a Python pickle, not a .npy array; save the matrix with numpy.save"}


def unit_factor(quantity: str, unit: object, *, source: str) -> float:
    """SI value of one ``unit`` of ``quantity`` (``"kN/m"`` for a stiffness: 1000.0)."""
    if not isinstance(unit, str) or not unit.strip():
        raise ValueError(f"{source} = {unit!r} must be a unit such as 'kg' or 'N/m'")
    text = unit.strip()
    try:
        return to_si(quantity, f"1 {text}", source=source)
    except ValueError as exc:  # said of what the user wrote, not of the "1 " put before it
        message = str(exc).replace(repr(f"1 {text}"), repr(text), 1)
        if "one number followed by a unit" in message:
            message = f"{source} = {text!r} must be a unit alone (such as 'kN/m'), without a number"
        raise ValueError(message) from None


class _Unreadable(ValueError):
    """Why a file's content is refused, in our words (never quoting the file)."""


_KINDS = {".mtx": "Matrix Market", ".npy": "NumPy .npy", ".csv": "CSV"}


def _read_file(path: Path, source: str, content: bytes | None = None,
               max_dof: int | None = None) -> Any:
    """The matrix in the file ``path``, or in ``content`` (an uploaded file named ``path``).

    With ``content`` nothing is read from disk, the messages name the file by its base name
    only, and a parser's own message (which may quote the file) is replaced by ours. A model
    above ``max_dof`` DOF is refused from its header or first row, before its entries are
    read (a 4990x4990 CSV took 18 s and 1.4 GB to parse before an audit's refusal).
    """
    uploaded = content is not None
    shown = repr(path.name) if uploaded else repr(str(path))
    if not uploaded:
        _check_regular_file(path, source)
        note_input(path)
    suffix = path.suffix.lower()
    if suffix not in _KINDS:
        raise ValueError(f"{source}: {shown} has suffix {suffix!r}; use .mtx, .npy or .csv")
    try:
        handle: Any = io.BytesIO(content) if content is not None else path
        if suffix == ".mtx":
            return _read_mtx(handle if uploaded else str(path), uploaded, max_dof)
        if suffix == ".npy":
            return _read_npy(handle, uploaded, max_dof)
        size = len(content) if content is not None else path.stat().st_size
        if size > MAX_CSV_BYTES:
            raise _Unreadable(f"it holds {size} bytes, beyond the {MAX_CSV_BYTES} read from a .csv "
                              "(use a sparse .mtx for large models)")
        raw = content if content is not None else path.read_bytes()
        return _read_csv(raw.decode("utf-8-sig"), max_dof)
    except _Unreadable as exc:
        raise ValueError(f"{source}: {shown} cannot be read: {exc}") from None
    except UnicodeDecodeError:
        raise ValueError(f"{source}: {shown} cannot be read: it is not UTF-8 text") from None
    except (ValueError, OSError, EOFError) as exc:
        detail = f"it is not a valid {_KINDS[suffix]} file of real numbers" if uploaded else str(exc)
        raise ValueError(f"{source}: {shown} cannot be read: {detail}") from None


def _check_regular_file(path: Path, source: str) -> None:
    """Refuse a missing path, and anything that is not a regular file (a FIFO, a device, a
    folder), which could block the reader or never end."""
    import stat

    try:
        mode = path.stat().st_mode
    except FileNotFoundError:
        raise ValueError(f"{source}: file {str(path)!r} does not exist") from None
    except OSError as exc:
        raise ValueError(f"{source}: {str(path)!r} cannot be read: {exc.strerror or exc}") from None
    if not stat.S_ISREG(mode):
        raise ValueError(f"{source}: {str(path)!r} is not a regular file (a folder, FIFO or "
                         "device); name the matrix file itself")


def _check_mtx_size(rows: int, entries: int, fmt: str, symmetry: str, size: int) -> None:
    """Refuse a Matrix Market header that declares more entries than the file can hold."""
    if fmt == "array":
        needed = rows * rows if symmetry == "general" else rows * (rows + 1) // 2
    else:
        needed = entries
    most = size // MTX_MIN_ENTRY_BYTES.get(fmt, 2)
    if needed > most:
        raise _Unreadable(f"its header declares {needed} entries ({rows}x{rows}), but its "
                          f"{size} bytes hold at most {most}: the header does not match the data")


def _check_one_triangle(coo: Any, symmetry: str) -> None:
    """Refuse a symmetric coordinate file that gives a term in both triangles (or twice).

    Such a file holds one triangle (the lower, by the format; the upper alone is read the same
    way); the reader mirrors every off-diagonal entry and adds up repeated ones, so a file with
    both triangles would count each off-diagonal term twice: silently wrong frequencies.
    """
    keys = coo.row.astype(np.int64) * coo.shape[1] + coo.col
    unique, counts = np.unique(keys, return_counts=True)
    if np.any(counts > 1):
        key = int(unique[np.argmax(counts > 1)])
        i, j = sorted((key // coo.shape[1] + 1, key % coo.shape[1] + 1), reverse=True)
        raise _Unreadable(
            f"it is marked {symmetry} but gives the term ({i}, {j}) twice (in both triangles, "
            "or repeated): such a file holds one triangle, and the term would be counted "
            "twice; mark it general or keep the lower triangle only")


def _beyond(n: int, max_dof: int | None) -> None:
    """Refuse a model of ``n`` DOF above ``max_dof`` (before its entries are read)."""
    if max_dof is not None and n > max_dof:
        raise _Unreadable(f"it is {n}x{n}, a {n}-DOF model, beyond the {max_dof} DOF accepted here")


def _read_mtx(handle: Any, uploaded: bool, max_dof: int | None = None) -> Any:
    import scipy.io
    import scipy.sparse

    if uploaded:
        header = handle.readline().decode("ascii", "replace")
        handle.seek(0)
    else:
        with open(handle, "rb") as file:
            header = file.readline().decode("ascii", "replace")
    if not header.lower().startswith("%%matrixmarket"):
        raise _Unreadable("it has no %%MatrixMarket header")
    if " complex" in header.lower():
        raise _Unreadable("it holds complex numbers; the matrices must be real")
    rows, cols, entries, fmt, field, symmetry = scipy.io.mminfo(handle)
    if field == "pattern":
        raise _Unreadable("it is a pattern matrix (positions without values); a mass, damping "
                          "or stiffness matrix needs its values (field real)")
    if uploaded:
        size = handle.seek(0, io.SEEK_END)
        handle.seek(0)
    else:
        size = Path(handle).stat().st_size
    if rows != cols:
        raise _Unreadable(f"it is {rows}x{cols}, not square")
    if rows > MAX_SPARSE_DOF:
        raise _Unreadable(f"it has {rows} DOF, beyond the supported {MAX_SPARSE_DOF}")
    _beyond(rows, max_dof)
    if fmt == "array" and rows * cols > MAX_DENSE_ENTRIES:
        raise _Unreadable(f"it is a dense {rows}x{cols} array; store large models sparse "
                          "(coordinate format)")
    _check_mtx_size(rows, entries, fmt, symmetry, size)
    try:
        data = scipy.io.mmread(handle)
    except (RuntimeError, OverflowError, MemoryError) as exc:
        raise _Unreadable(f"its entries do not match its header ({exc})") from None
    if scipy.sparse.issparse(data):
        if symmetry != "general":
            _check_one_triangle(scipy.sparse.coo_matrix(data), symmetry)
        return scipy.sparse.csr_matrix(data, dtype=np.float64)
    return np.asarray(data, dtype=np.float64)


def _read_npy(handle: Any, uploaded: bool, max_dof: int | None = None) -> Any:
    """One array from a ``.npy`` file; its magic and header are checked before it is loaded
    (an empty file, a ``.npz`` archive or a pickle under that name, an object array, a size
    beyond :data:`MAX_DENSE_ENTRIES`)."""
    with open(handle, "rb") if not uploaded else contextlib.nullcontext(handle) as file:
        magic = file.read(len(NPY_MAGIC))
        if not magic:
            raise _Unreadable("it is empty (0 bytes)")
        if magic != NPY_MAGIC:
            kind = next((why for start, why in _NOT_NPY.items() if magic.startswith(start)),
                        "not a NumPy .npy file (it does not start as numpy.save writes one)")
            raise _Unreadable(f"it is {kind}")
        file.seek(0)
        try:
            version = np.lib.format.read_magic(file)
            shape, _order, dtype = (np.lib.format.read_array_header_1_0(file) if version == (1, 0)
                                    else np.lib.format.read_array_header_2_0(file))
        # numpy's text may quote parser objects; a header cut inside its dictionary is a
        # tokenizer's error (an audit: "EOF in multi-line statement")
        except (ValueError, SyntaxError, TypeError, tokenize.TokenError) as exc:
            raise _Unreadable("its .npy header is not valid (numpy.save writes a dictionary of "
                              "descr, fortran_order and shape)") from exc
        if dtype.hasobject:
            raise _Unreadable("it holds Python objects (pickled data), which are never loaded")
        if len(shape) == 2:
            _beyond(int(shape[0]), max_dof)
        entries = int(np.prod(shape, dtype=np.float64))
        if entries > MAX_DENSE_ENTRIES:
            raise _Unreadable(f"it holds {entries} entries, beyond {MAX_DENSE_ENTRIES} (use a "
                              "sparse .mtx for large models)")
        file.seek(0)
    data = np.load(handle, allow_pickle=False, mmap_mode=None if uploaded else "r")
    if not np.issubdtype(data.dtype, np.number) or np.issubdtype(data.dtype, np.complexfloating):
        raise _Unreadable(f"it holds {data.dtype} values, not real numbers")
    return np.array(data, dtype=np.float64)


def _read_csv(text: str, max_dof: int | None = None) -> Any:
    """Rows of numbers, comma or semicolon separated; a bad entry is named by row and column."""
    delimiter = ";" if ";" in text and "," not in text else ","
    # a structure matrix is square: so many rows as values in the first, counted before any
    # number is read (50 MB of one value per line took 44 s and 2.8 GB to refuse)
    start = len(text) - len(text.lstrip())
    end = text.find("\n", start)
    n_columns = text[start:end if end >= 0 else len(text)].count(delimiter) + 1
    _beyond(n_columns, max_dof)
    line_breaks = text.count("\n")  # no list of lines yet: a bound first
    if line_breaks > 4 * n_columns + 16:
        raise _Unreadable(f"it has {line_breaks} line breaks and {n_columns} values in its first "
                          "row: not a square matrix")
    n_rows = sum(1 for line in text.splitlines() if line.strip())
    if n_rows != n_columns:
        raise _Unreadable(f"it has {n_rows} rows and {n_columns} values in its first row: not a "
                          "square matrix")
    rows_out = []
    for row, line in enumerate(text.splitlines(), start=1):
        if not line.strip():
            continue
        values = []
        for column, item in enumerate(line.split(delimiter), start=1):
            try:
                values.append(float(item))
            except ValueError:
                raise _Unreadable(f"row {row}, column {column} is not a number") from None
        rows_out.append(values)
    try:
        return np.array(rows_out, dtype=np.float64)
    except ValueError:
        raise _Unreadable("its rows have different numbers of columns") from None


def read_matrix(spec: object, *, quantity: str, unit: object = None,
                base_dir: Path | None = None, source: str = "matrix",
                content: bytes | None = None, max_dof: int | None = None) -> Any:
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
    content : bytes, optional
        The bytes of the file ``spec`` names (an uploaded file, checked by the caller): then
        nothing is read from disk and messages never quote the file or a server path.
    max_dof : int, optional
        Refuse a file of a model above so many DOF before its entries are read.

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
        if content is None and base_dir is not None and not path.is_absolute():
            path = base_dir / path
        data = _read_file(path, f"{source} = {spec!r}", content, max_dof)
        where = f"{source} = {spec!r}"
    elif isinstance(spec, list):
        where = f"{source} (inline)"
        if _has_boolean(spec):
            raise ValueError(f"{where} has true/false entries; the matrix entries must be numbers")
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
    largest = float(np.max(np.abs(values))) * factor if values.size else 0.0
    if not largest <= MAX_SI:  # sums and eigenvalues of such entries overflow a double
        raise ValueError(f"{where} has an entry of magnitude {largest:.3g} in SI units, beyond the "
                         f"{MAX_SI:.0e} supported (check the unit)")
    return data * factor if factor != 1.0 else data


def _has_boolean(rows: list[Any]) -> bool:
    """True when a TOML array of rows holds a boolean (which numpy would read as 0 or 1)."""
    return any(isinstance(x, bool) or (isinstance(x, list) and _has_boolean(x)) for x in rows)
