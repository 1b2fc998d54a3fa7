"""Reading a user's TOML file with one-line errors (machine files, record column specifications)."""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

from stickslip.model.user_file import read_user_text


def read_toml_file(path: str | Path, label: str, content: bytes | None = None) -> dict[str, Any]:
    """The tables of the TOML file ``path``, or one ``ValueError`` line naming ``label`` and why.

    Parameters
    ----------
    path : str or Path
        The file (UTF-8, with or without a byte-order mark).
    label : str
        How messages name the file, e.g. ``--config 'machine.toml'``.
    content : bytes, optional
        The file's bytes (an uploaded file): then nothing is read from disk.

    Returns
    -------
    dict
        The parsed document.
    """
    try:
        if content is not None:
            text = content.decode("utf-8-sig")
        else:
            text = read_user_text(Path(path), label, hint="name the TOML file itself")
        _check_key_depth(text, label)
        document = tomllib.loads(text)
        _check_integers(document, label, "")
        return document
    except UnicodeDecodeError:
        raise ValueError(f"{label} is not a UTF-8 text file") from None
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{label} is not valid TOML: {exc}") from None
    except RecursionError:  # arrays or inline tables nested thousands deep
        raise ValueError(f"{label} is not valid TOML here: its arrays or tables nest too "
                         "deeply") from None


#: Most parts of a dotted key or table header (``a.b.c`` has three). ``tomllib`` takes memory
#: that grows with the square of a dotted key's length: a 200 kB line ``a.a.a...a = 1`` took
#: 22 GB (an independent audit of the web app), so longer keys are refused before parsing. A
#: machine file nests two or three deep.
MAX_KEY_PARTS = 32


def _check_key_depth(text: str, label: str) -> None:
    """Refuse a key or table header of more than :data:`MAX_KEY_PARTS` parts, read from the
    text before parsing: the dots before each line's ``=`` (or inside its ``[...]`` header)
    that lie outside quotes."""
    for number, line in enumerate(text.splitlines(), start=1):
        stripped = line.lstrip()
        if stripped.startswith("["):
            head = stripped.split("]", 1)[0]
        elif "=" in stripped:
            head = stripped.split("=", 1)[0]
        else:
            continue
        if head.count(".") < MAX_KEY_PARTS:
            continue  # cheap: no key can be longer than its dots
        dots, quote = 0, ""
        for ch in head:
            if quote:
                quote = "" if ch == quote else quote
            elif ch in "\"'":
                quote = ch
            elif ch == ".":
                dots += 1
        if dots >= MAX_KEY_PARTS:
            raise ValueError(f"{label}: line {number} has a key of {dots + 1} dotted parts, more "
                             f"than {MAX_KEY_PARTS}: tables do not nest that deeply here")


def _check_integers(value: Any, label: str, where: str) -> None:
    """Refuse an integer beyond the range of a float (every number here becomes one)."""
    if isinstance(value, dict):
        for key, item in value.items():
            _check_integers(item, label, f"{where}.{key}" if where else str(key))
    elif isinstance(value, list):
        for item in value:
            _check_integers(item, label, where)
    elif isinstance(value, int) and not isinstance(value, bool) and abs(value) > 1e308:
        raise ValueError(f"{label}: {where} is an integer of {len(str(abs(value)))} digits, "
                         "beyond the range of a floating-point number")
