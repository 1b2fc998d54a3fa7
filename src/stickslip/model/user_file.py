"""Reading a file a user names, bounded: one home for the checks every reader needs.

A path given on the command line or in a machine file may name a FIFO (reading it blocks until
someone writes), a device (``/dev/zero`` never ends) or a folder. Every text file the tool reads
for a user (machine files, friction tables, initial states, records) goes through
:func:`read_user_text`, which refuses anything that is not a regular file before opening it,
reads at most ``max_bytes + 1`` bytes, and decodes UTF-8 (a byte-order mark dropped), each
failure one ``ValueError`` line naming the file and why.
"""

from __future__ import annotations

import csv
import os
import stat
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path

#: Largest text file read for a user by default, bytes: 64 MiB. Machine files, friction tables
#: and initial-state lists are far smaller; records (:mod:`stickslip.io.record`) pass their own.
MAX_TEXT_BYTES = 64 * 1024**2

#: Every file read for the user by the running command (real paths): no output of the command
#: may replace one (``--csv machine.toml --overwrite`` turned the machine file into a table).
#: Recorded only within :func:`recording_inputs` (the command line runs each command in it): a
#: script using the Python API may rewrite a file it read.
_INPUTS: set[str] = set()
_RECORDING = [False]


def note_input(path: str | Path) -> None:
    """Remember ``path`` as an input of the current command (see :func:`is_input`).

    Parameters
    ----------
    path : str or Path
        A file read for the user.

    Returns
    -------
    None
        Nothing.
    """
    if _RECORDING[0]:
        _INPUTS.add(os.path.realpath(path))


def is_input(path: str | Path) -> bool:
    """True when ``path`` (followed through links) was read as an input of the current command.

    Parameters
    ----------
    path : str or Path
        A path about to be written.

    Returns
    -------
    bool
        Whether an output there would replace an input.
    """
    return os.path.realpath(path) in _INPUTS


@contextmanager
def recording_inputs() -> Iterator[None]:
    """Within: one command, whose files read are recorded (:func:`is_input`); after, none.

    Returns
    -------
    contextmanager
        Clears the record on entry and on exit.
    """
    _INPUTS.clear()
    _RECORDING[0] = True
    try:
        yield
    finally:
        _INPUTS.clear()
        _RECORDING[0] = False


def read_user_text(path: str | Path, label: str, *, max_bytes: int = MAX_TEXT_BYTES,
                   hint: str = "name the file itself") -> str:
    """The text of the regular file ``path``, or one ``ValueError`` line naming ``label``.

    Parameters
    ----------
    path : str or Path
        The file a user named.
    label : str
        How messages name it, e.g. ``--config 'machine.toml'``.
    max_bytes : int, optional
        The most bytes read; a larger file is refused (default :data:`MAX_TEXT_BYTES`).
    hint : str, optional
        What to do instead, appended when the path is not a regular file.

    Returns
    -------
    str
        The decoded text (UTF-8, a leading byte-order mark dropped).
    """
    p = Path(path)
    try:
        mode = p.stat().st_mode
        if not stat.S_ISREG(mode):
            raise ValueError(f"{label} is not a regular file (a folder, FIFO or device); {hint}")
        with p.open("rb") as handle:
            raw = handle.read(max_bytes + 1)
        note_input(p)
    except FileNotFoundError:
        raise ValueError(f"{label} does not exist") from None
    except OSError as exc:
        raise ValueError(f"{label} cannot be read: {exc.strerror or exc}") from None
    if len(raw) > max_bytes:
        raise ValueError(f"{label} is larger than {max_bytes} bytes, the most read")
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ValueError(f"{label} is not UTF-8 text ({exc.reason} at byte {exc.start}); "
                         "save it as UTF-8") from None


def csv_rows(lines: Iterable[str], label: str, delimiter: str = ",") -> list[list[str]]:
    """The rows of CSV lines; a row the csv module refuses is one ``ValueError`` naming ``label``.

    The module refuses, for one, a field longer than its limit (131,072 characters): an
    upload of one 200,000-digit number used to escape as a bare ``_csv.Error``.

    Parameters
    ----------
    lines : iterable of str
        The lines (comments and blank lines already dropped).
    label : str
        The source in messages (a file's name, an upload's).
    delimiter : str
        The separator.

    Returns
    -------
    list of list of str
        The fields of every row.
    """
    reader = csv.reader(lines, delimiter=delimiter)
    try:
        return list(reader)
    except csv.Error as exc:
        raise ValueError(f"{label}, row {reader.line_num}: not a readable CSV row ({exc})") from None
