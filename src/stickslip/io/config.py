"""The flat view of a machine's TOML file: its quantities and its friction law.

The file has one reader, :func:`stickslip.io.machine_file.read_machine_file` (the
``[structure]`` and ``[absorber]`` tables of section 10 as well); its quantities are parsed by
:mod:`stickslip.model.inputs`, the one parser the web app's fields go through too. This module
keeps the name ``stickslip design --config`` used before section 10: :func:`read_machine_config`
is that reader's answer for a file of the paper's slider (``m``, ``k``, ``c``; ``m_a``, ...).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from stickslip.model.physical import PhysicalFriction


@dataclass(frozen=True)
class MachineConfig:
    """The flat quantities and the friction law of a machine's TOML file.

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
    """Read and check a machine's TOML file (:func:`~stickslip.io.machine_file.read_machine_file`).

    Parameters
    ----------
    path : path
        The TOML file; a friction curve it names (``table = "curve.csv"``) is relative to it.
    label : str, optional
        How messages name the file; default ``--config 'PATH'``.

    Returns
    -------
    MachineConfig
        Its flat quantities and friction law (a ``[structure]`` is read by
        :meth:`~stickslip.io.machine_file.MachineFile.structure_matrices`).

    Raises
    ------
    ValueError
        One line: the file does not exist or is not valid TOML, a table is not a table, it has
        unknown keys, or the ``[friction]`` table is bad.
    """
    from stickslip.io.machine_file import read_machine_file

    machine_file = read_machine_file(Path(path), label=label)
    return MachineConfig(dict(machine_file.raw), machine_file.friction())
