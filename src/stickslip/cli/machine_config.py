"""``--config machine.toml`` on every command: the user's machine, in SI.

The machine file is read by :func:`stickslip.io.machine_file.read_machine_file` (the one
reader); its flat quantities are parsed by :mod:`stickslip.model.inputs` (the one parser, the
web app's too). This module is the command line's side of it: messages that name the file,
flags that may override the file's operating point (``design``), the refusal of dimensionless
flags next to a machine file (issue 22 point 2: ``--config`` is the whole system, so a
``--lam``, ``--zeta``, ``--gamma``, ``--dva`` or ``--friction`` beside it would be silently
ignored or silently mixed) and the machine as the engine sees it, :class:`ConfiguredMachine`.

A file describes its structure either with the paper's slider (``m``, ``k``, ``c``, and
``m_a``, ``k_a``, ``c_a`` for a foundation) or with a ``[structure]`` table (any linear
structure, the contact on ``contact_dof``). Both become a :class:`ConfiguredMachine`: the
dimensionless structure and slider the engine runs, and the contact's reference system
(:meth:`stickslip.model.machine.Machine.reference_system`, ``m_ref = M[c, c]``,
``k_ref = K[c, c]``), whose time and length scales turn dimensionless answers into seconds and
metres. For the paper's slider that reference is the slider itself, and the structure is
built exactly as ``--dva M,K,ZETA_A`` builds it (:meth:`PhysicalSystem.structure`), so the
answers are those of the dimensionless commands bit for bit.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from stickslip.cli.console import BadInput, warn

if TYPE_CHECKING:
    import typer

    from stickslip.analysis.reduction import ReducedStructure
    from stickslip.io.machine_file import MachineFile
    from stickslip.model.machine import Machine
    from stickslip.model.parameters import Slider
    from stickslip.model.physical import PhysicalSystem
    from stickslip.model.structure import Structure

#: Options of the dimensionless commands that a machine file replaces: given with ``--config``
#: they are refused (the file's structure, friction law and coefficients are the system).
DIMENSIONLESS_OPTIONS = ("lam", "zeta", "gamma", "dva", "k_scale", "friction", "delta")


def load_machine_file(config: Path, *, normal_coupling: bool = False) -> MachineFile:
    """The machine file, read and checked; a bad file is one :class:`BadInput` line naming it.

    Every ``--config`` command passes here, so here a ``[contact]`` table or a ``[structure]
    normal_dof`` is refused (:data:`stickslip.model.contact.NOT_SUPPORTED`) unless the command
    says it uses them (``normal_coupling=True``: ``stickslip stability``, ``simulate``,
    ``cycles``, ``basin`` and ``continue``), rather than ignored.
    """
    from stickslip.io.machine_file import read_machine_file
    from stickslip.model.contact import NOT_SUPPORTED

    try:
        machine_file = read_machine_file(Path(config))
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    if machine_file.has_contact and not normal_coupling:
        raise BadInput(f"{machine_file.label}: {NOT_SUPPORTED}")
    return machine_file


def refuse_memory_law(machine_file: MachineFile) -> None:
    """Commands that take only the curve laws say so in one line."""
    from stickslip.io.machine_file import memory_law_refusal

    if machine_file.has_memory_law:
        assert machine_file.friction_table is not None
        raise BadInput(memory_law_refusal(f"{machine_file.label}: [friction]",
                                          machine_file.friction_table["law"]))


def refuse_contact_with_memory(machine_file: MachineFile) -> None:
    """A ``[contact]`` and a law with memory in one file: one line (no engine has both)."""
    if machine_file.has_memory_law and machine_file.has_contact:
        raise BadInput(f"{machine_file.label}: a [contact] (normal_dof, Jenkins element) "
                       "runs with the Coulomb law (mu_s, mu_k) only, not with a friction "
                       "law with memory; remove one of them")


def refuse_mix(ctx: typer.Context, config: Path | None,
               names: Sequence[str] = DIMENSIONLESS_OPTIONS) -> None:
    """Refuse options of ``names`` given on the command line together with ``--config``.

    Only options the user typed count (a default is not a choice), so ``--gamma 2`` next to
    ``--config`` is refused although 2 is the default.

    Raises
    ------
    BadInput
        ``--lam, --dva cannot be given with --config 'machine.toml': ...``.
    """
    if config is None:
        return
    # by name: Typer ships its own copy of click, whose ParameterSource is another enum
    typed = [name for name in names if name in ctx.params
             and getattr(ctx.get_parameter_source(name), "name", None) == "COMMANDLINE"]
    if typed:
        flags = ", ".join(f"--{name.replace('_', '-')}" for name in typed)
        raise BadInput(f"{flags} cannot be given with --config {str(config)!r}: the machine file "
                       "is the whole system (structure, friction law, load and speed); change it "
                       "there, or drop --config and give the dimensionless system")


def require_dimensionless(**given: object) -> None:
    """Without ``--config`` the dimensionless options are required: name the first missing one.

    The message starts as click's own (``Missing option '--zeta'``) and says the alternative.
    """
    for name, value in given.items():
        if value is None:
            flags = " and ".join(f"--{key.replace('_', '-')}" for key in given)
            raise BadInput(f"Missing option '--{name.replace('_', '-')}' (give {flags}, or "
                           "--config machine.toml)")


def collect_inputs(flags: Mapping[str, Any], config: Path | None, *,
                   normal_coupling: bool = False) -> dict[str, float]:
    """Merge the machine file (if any) and the flags (flags win), convert to SI, check presence.

    The rules are :mod:`stickslip.model.inputs`' (the web app's too); a value from the file is
    named ``--config 'FILE': KEY =`` in messages, a flag by its name. With a ``[structure]``
    in the file the slider and foundation keys are not needed, and giving them as flags too is
    refused (one structure per run). ``normal_coupling`` as :func:`load_machine_file`'s.
    """
    from stickslip.io.machine_file import PAPER_STRUCTURE_KEYS
    from stickslip.model.inputs import (
        FOUNDATION_QUANTITIES,
        is_given,
        missing_system_quantities,
        quantities_to_si,
    )

    machine_file = (load_machine_file(config, normal_coupling=normal_coupling)
                    if config is not None else None)
    if machine_file is not None:
        refuse_memory_law(machine_file)
    merged: dict[str, Any] = dict(machine_file.raw) if machine_file is not None else {}
    blank = [key for key, value in flags.items() if isinstance(value, str) and not value.strip()]
    if blank:  # typed, but with nothing in it: not the same as leaving the flag out
        name = f"--{blank[0].replace('_', '-')}"
        raise BadInput(f"{name} {flags[blank[0]]!r} is empty: give a value (units allowed) or "
                       f"leave {name} out")
    given_flags = {key: value for key, value in flags.items() if is_given(value)}
    from_file = set(merged) - set(given_flags)
    has_structure = machine_file is not None and machine_file.has_structure
    if has_structure:
        mixed = [f"--{key.replace('_', '-')}" for key in PAPER_STRUCTURE_KEYS if key in given_flags]
        if mixed:
            raise BadInput(f"{', '.join(mixed)} cannot be given with --config {str(config)!r}: its "
                           "[structure] is the structure")
    merged.update(given_flags)
    missing, partial = missing_system_quantities(merged)
    if has_structure:
        missing = [key for key in missing if key not in PAPER_STRUCTURE_KEYS]
        partial = [key for key in partial if key not in FOUNDATION_QUANTITIES]
    if missing and not flags and machine_file is not None:  # a command without these flags
        raise BadInput(f"{machine_file.label} lacks {', '.join(missing)} (keys of the machine "
                       "file, e.g. speed = \"5 cm/s\")")
    if missing:
        flags_missing = ", ".join(f"--{key.replace('_', '-')}" for key in missing)
        raise BadInput(f"missing {flags_missing} (give them as flags or in --config)")
    if partial:
        raise BadInput("an existing foundation needs all of --m-a, --k-a and --c-a")
    label = None if machine_file is None else machine_file.label
    try:
        values = quantities_to_si(
            merged, source=lambda key: f"{label}: {key} =" if key in from_file else None)
    except ValueError as exc:  # it names the file and key, or the flag: no prefix to add
        raise BadInput(str(exc)) from None
    if not has_structure:
        values.setdefault("c", 0.0)
    return values


def config_system(config: Path, flags: Mapping[str, Any] | None = None, *,
                  normal_coupling: bool = False) -> PhysicalSystem:
    """The paper's slider (rigid base or foundation) of a flat machine file, in SI.

    A file with a ``[structure]`` is refused with one line (its machine is
    :func:`config_machine`'s): a caller that needs the slider's ``m``, ``k``, ``c`` says so
    instead of failing on a missing key. ``normal_coupling`` as :func:`load_machine_file`'s.
    """
    from stickslip.model.physical import PhysicalFoundation, PhysicalSystem

    if load_machine_file(config, normal_coupling=normal_coupling).has_structure:
        raise BadInput(f"--config {str(config)!r} has a [structure]: this needs the paper's slider "
                       "(m, k, c; m_a, k_a, c_a)")

    values = collect_inputs(flags or {}, config, normal_coupling=normal_coupling)
    foundation = (PhysicalFoundation(values["m_a"], values["k_a"], values["c_a"])
                  if "m_a" in values else None)
    try:
        return PhysicalSystem(mass=values["m"], stiffness=values["k"], damping=values["c"],
                              mu_s=values["mu_s"], mu_k=values["mu_k"], load=values["load"],
                              speed=values["speed"], foundation=foundation,
                              friction=load_machine_file(
                                  config, normal_coupling=normal_coupling).friction())
    except ValueError as exc:
        label = f"--config {str(config)!r}"  # named once: the [friction] message names it already
        raise BadInput(str(exc) if str(exc).startswith(label) else f"{label}: {exc}") from None


def config_machine(config: Path, flags: Mapping[str, Any] | None = None,
                   ) -> tuple[Machine, ReducedStructure | None]:
    """The :class:`~stickslip.model.machine.Machine` of a machine file, and its reduction.

    A ``[structure]`` file gives its matrices (reduced above
    :data:`~stickslip.model.machine.MAX_DIRECT_DOF`, then the reduction is returned); a flat
    file gives the paper's slider as a machine (:func:`machine_from_physical_system`,
    contact on DOF 0). ``flags`` may override the file's flat quantities (``design``).
    """
    from stickslip.io.machine_file import machine_from_file
    from stickslip.model.machine import machine_from_physical_system

    machine_file = load_machine_file(config)
    if not machine_file.has_structure:
        return machine_from_physical_system(config_system(config, flags)), None
    values = collect_inputs(flags or {}, config)
    try:
        machine, reduction = machine_from_file(machine_file, values)
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    warn_truncated(reduction)
    return machine, reduction


def warn_truncated(reduction: ReducedStructure | None) -> None:
    """A warning line on stderr when a reduction kept fewer modes than lie below its cut-off
    (:meth:`~stickslip.analysis.reduction.ReducedStructure.truncation_warning`), and one when
    the file's cut-off lies below the operating point's default
    (:meth:`~stickslip.analysis.reduction.ReducedStructure.cutoff_warning`)."""
    if reduction is None:
        return
    for text in (reduction.cutoff_warning(), reduction.truncation_warning()):
        if text is not None:
            warn(text)


@dataclass(frozen=True)
class ConfiguredMachine:
    """A machine file as the engine runs it: dimensionless structure and slider, and the scales.

    Attributes
    ----------
    structure : Structure
        Dimensionless, contact on ``structure.contact_dof``.
    slider : Slider
        ``lambda``, ``gamma`` and the dimensionless friction law of the contact.
    reference : PhysicalSystem
        The contact's own 1DOF system (``m_ref``, ``k_ref``, ``c_ref``, ``mu_s``, ``mu_k``,
        ``W``, ``V``): ``time_scale`` [s] and ``length_scale`` [m] of the answers.
    machine : Machine
        The machine in SI.
    system : PhysicalSystem or None
        The paper's slider when the file gives ``m``, ``k``, ``c`` (...), else None.
    reduction : ReducedStructure or None
        The reduction of a model above :data:`~stickslip.model.machine.MAX_DIRECT_DOF`.
    """

    structure: Structure
    slider: Slider
    reference: PhysicalSystem
    machine: Machine
    system: PhysicalSystem | None = None
    reduction: ReducedStructure | None = None

    def groups(self) -> dict[str, float]:
        """The dimensionless numbers of the run: ``lambda``, ``zeta``, ``gamma``."""
        return {"lambda": self.slider.lam, "zeta": self.structure.zeta, "gamma": self.slider.gamma}

    def scales(self) -> dict[str, float]:
        """SI scales: ``time_scale_s`` (1/omega_n), ``length_scale_m`` (V/omega_n), m_ref, k_ref."""
        return {"time_scale_s": self.reference.time_scale,
                "length_scale_m": self.reference.length_scale,
                "reference_mass_kg": self.reference.mass,
                "reference_stiffness_N_per_m": self.reference.stiffness}


def out_of_scale(speed: float, load: float, exc: Exception) -> str:
    """The message for a dimensionless group beyond range, said with its operating point.

    Parameters
    ----------
    speed, load : float
        The belt speed [m/s] and normal load [N] the group comes from.
    exc : Exception
        The model's refusal (it names the group and its range).

    Returns
    -------
    str
        One line: the operating point, the refusal, and what it means (a friction table's
        own fault, :class:`~stickslip.model.friction.TableInputError`, is said alone).
    """
    from stickslip.model.friction import TableInputError

    if isinstance(exc, TableInputError):  # the table's own fault, at any operating point
        return str(exc)
    return (f"at the belt speed {speed:g} m/s and load {load:g} N, {exc}; the speed or the "
            "load is far outside the machine's scales")


def configured_machine(config: Path) -> ConfiguredMachine:
    """The machine of ``config`` ready to run (see :class:`ConfiguredMachine`)."""
    from stickslip.model.machine import machine_from_physical_system

    machine_file = load_machine_file(config)
    refuse_memory_law(machine_file)
    from stickslip.model._validate import friction_range

    try:
        if not machine_file.has_structure:
            system = config_system(config)
            configured = ConfiguredMachine(system.structure(), system.slider(), system,
                                           machine_from_physical_system(system), system=system)
        else:
            machine, reduction = config_machine(config)
            structure, slider = machine.to_dimensionless()
            configured = ConfiguredMachine(structure, slider, machine.reference_system(), machine,
                                           reduction=reduction)
        try:  # what simulate checks, said with the operating point it comes from
            friction_range(configured.slider.lam, configured.slider.gamma)
        except ValueError as exc:
            raise ValueError(out_of_scale(configured.machine.speed, configured.machine.load,
                                          exc)) from None
        return configured
    except BadInput:
        raise
    except ValueError as exc:
        message = str(exc)  # named once: a model message may name the file already
        raise BadInput(message if message.startswith(f"{machine_file.label}:")
                       else f"{machine_file.label}: {message}") from None
