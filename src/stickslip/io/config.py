"""Reading a machine's TOML file: the ``[system]`` and ``[friction]`` tables (DESIGN.md section 8).

``stickslip design --config`` and ``stickslip basin --config`` read the same file through
:func:`read_machine_config`; the values are parsed by :mod:`stickslip.model.inputs`, the one
parser the web app's fields go through as well. This module only reads files (the TOML file
and the friction curve it names).
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from stickslip.model.physical import PhysicalFriction, physical_friction_from_config
from stickslip.model.units import QUANTITIES


@dataclass(frozen=True)
class MachineConfig:
    """The tables of a machine's TOML file.

    Attributes
    ----------
    system : dict
        The ``[system]`` table (or the top-level keys when there is none): quantity name ->
        value as written (numbers in SI or text with units), not yet converted.
    friction : PhysicalFriction
        The ``[friction]`` table in SI units (Coulomb without one), its curve read.
    """

    system: dict[str, Any]
    friction: PhysicalFriction = field(default_factory=PhysicalFriction)


def read_machine_config(path: str | Path, label: str | None = None) -> MachineConfig:
    """Read and check a machine's TOML file.

    Parameters
    ----------
    path : path
        The TOML file; a friction curve it names (``table = "curve.csv"``) is relative to it.
    label : str, optional
        How messages name the file (the command line passes ``"--config 'machine.toml'"``);
        default the quoted path.

    Raises
    ------
    ValueError
        One line: the file does not exist or is not valid TOML, ``system`` is not a table, it
        has unknown keys, or the ``[friction]`` table is bad
        (:func:`stickslip.model.physical.physical_friction_from_config`).
    """
    path = Path(path)
    name = label or repr(str(path))
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise ValueError(f"{name} does not exist") from None
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{name} is not valid TOML: {exc}") from None
    section = data.get("system", {k: v for k, v in data.items() if k != "friction"})
    if not isinstance(section, dict):
        raise ValueError(f"{name}: 'system' must be a table of quantities, not {section!r}")
    unknown = sorted(set(section) - set(QUANTITIES))
    if unknown:
        raise ValueError(f"{name}: unknown keys {', '.join(unknown)}")
    if "friction" not in data:
        return MachineConfig(dict(section))
    return MachineConfig(dict(section), physical_friction_from_config(
        data["friction"], base_dir=path.parent, source=f"{name}: [friction]"))

