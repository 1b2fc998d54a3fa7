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
            return tomllib.loads(content.decode("utf-8-sig"))
        text = read_user_text(Path(path), label, hint="name the TOML file itself")
        return tomllib.loads(text)
    except UnicodeDecodeError:
        raise ValueError(f"{label} is not a UTF-8 text file") from None
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{label} is not valid TOML: {exc}") from None
    except RecursionError:  # arrays or inline tables nested thousands deep
        raise ValueError(f"{label} is not valid TOML here: its arrays or tables nest too "
                         "deeply") from None
