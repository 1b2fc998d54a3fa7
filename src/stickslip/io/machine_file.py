"""The machine TOML file: the one reader, for every command and the app.

Layout::

    mu_s = 0.5            # top level (or in a [system] table, the old layout)
    mu_k = 0.3
    load = "500 N"
    speed = "5 cm/s"
    m = "2 kg"            # the paper's slider ... (m, k, c; m_a, k_a, c_a for a foundation)

    [structure]           # ... or any linear structure instead of m, k, c, m_a, k_a, c_a
    mass = "M.mtx"        # .mtx / .npy / .csv path (relative to the file) or inline rows
    stiffness = "K.mtx"
    damping = "C.mtx"     # or rayleigh = [alpha, beta], or modal_damping = 0.02 (or a list)
    mass_unit = "kg"      # stiffness_unit = "N/m", damping_unit = "N*s/m" (SI by default)
    contact_dof = 2       # 0-based DOF the belt rubs
    # normal_dof = 3      # 0-based DOF normal to the belt, positive away from it ([contact])
    # or modes from a modal test, the structure seen from the contact:
    # modes = {frequencies = [12.0, 40.0], damping_ratios = [0.02, 0.03], shapes = [0.5, 0.2]}
    # (Hz, -, mass-normalised values at the contact in 1/sqrt(kg))
    # cutoff = "500 Hz"   # reduction of models above 60 DOF (default: analysis.reduction);
    #                       smaller models are run whole, the value still checked

    [absorber]            # the absorber to tune on this machine
    mass = "3 kg"
    attach_dof = 2        # or attach = "foundation": the whole machine mounted on it

    [friction]            # a friction law: coulomb, linear, table, stribeck, ...

    [contact]             # the contact spring(s): stickslip.model.contact
    normal_stiffness = "4e7 N/m"

Every problem is one ``ValueError`` line naming the file, the key, the value and why. This
module reads; the flat quantities and the ``[friction]`` table are parsed by
:mod:`stickslip.model.inputs` (through :func:`stickslip.model.inputs.quantities_to_si` and
:func:`stickslip.model.physical.physical_friction_from_config`), the structure is checked and
built in :mod:`stickslip.model.machine`. :mod:`stickslip.io.config` is its flat view.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath, PureWindowsPath
from typing import Any

import numpy as np

from stickslip.io.toml_file import read_toml_file
from stickslip.model.inputs import law_name
from stickslip.model.physical import si_input
from stickslip.model.units import QUANTITIES, to_si

#: The paper's slider and foundation keys, replaced by ``[structure]``.
PAPER_STRUCTURE_KEYS = ("m", "k", "c", "m_a", "k_a", "c_a")
#: Keys of the ``[structure]`` table.
STRUCTURE_KEYS = frozenset({"mass", "stiffness", "damping", "rayleigh", "modal_damping", "mass_unit",
                            "stiffness_unit", "damping_unit", "contact_dof", "modes", "name",
                            "cutoff", "normal_dof"})
MODE_KEYS = frozenset({"frequencies", "damping_ratios", "shapes"})
ABSORBER_KEYS = frozenset({"mass", "attach_dof", "attach"})
#: Limits of a machine file read from uploads (``files=``, the web app): all its files
#: together (MB) and the largest structure (DOF; its reduction and design take about a
#: minute at this size on a 2-core machine). The command line has no such limit.
UPLOAD_MAX_MB = 50
UPLOAD_MAX_DOF = 1000
#: The uploaded machine file itself (MB): inline rows are for small matrices.
UPLOAD_MAX_TOML_MB = 2
#: Longest ``[structure] name`` (characters): it titles printouts and figures.
MAX_NAME_LENGTH = 200


@dataclass(frozen=True)
class AbsorberSpec:
    """The ``[absorber]`` table: a mass (kg) on DOF ``attach_dof``, or under the whole machine.

    ``attach_dof`` None means ``attach = "foundation"``: the machine is mounted on the
    absorber mass (the paper's elastic foundation, generalised).
    """

    mass: float
    attach_dof: int | None


def memory_law_refusal(source: str, law: str) -> str:
    """The one line of a command that takes only the curve laws, given a law with memory."""
    return (f"{source} law = {law!r} is a friction law with memory: `stickslip simulate "
            "--config`, `stability`, `map`, `design`, `cycles`, `basin` and `continue --config` run "
            "it; this command takes the curve laws (coulomb, linear, table, stribeck)")


@dataclass(frozen=True)
class MachineFile:
    """A parsed machine file.

    Attributes
    ----------
    path : Path
        The file.
    raw : dict
        The flat quantities as written (``mu_s``, ``load``, ``m``, ...), converted later by
        the caller (flags may override them).
    friction_table, structure_table, absorber_table, contact_table : dict or None
        The ``[friction]``, ``[structure]``, ``[absorber]`` and ``[contact]`` tables.
    files : mapping or None
        Uploaded files by base name (the web app): the only files this one may name
        (:func:`uploaded_file`); None reads the files it names from disk, relative to ``path``.
    max_dof : int or None
        The largest structure accepted (DOF), or None for no limit but the readers'.
    """

    path: Path
    raw: dict[str, Any]
    friction_table: dict[str, Any] | None = None
    structure_table: dict[str, Any] | None = field(default=None)
    absorber_table: dict[str, Any] | None = None
    contact_table: dict[str, Any] | None = None
    shown_as: str | None = field(default=None, compare=False)
    files: Mapping[str, bytes] | None = field(default=None, compare=False, repr=False)
    max_dof: int | None = field(default=None, compare=False)

    @property
    def label(self) -> str:
        """How messages name the file: ``--config 'machine.toml'`` unless told otherwise."""
        return self.shown_as or f"--config {str(self.path)!r}"

    @property
    def has_structure(self) -> bool:
        """True when the file gives a ``[structure]`` table."""
        return self.structure_table is not None

    @property
    def has_contact(self) -> bool:
        """True when the file gives a ``[contact]`` table or ``[structure] normal_dof``."""
        return self.contact_table is not None or "normal_dof" in (self.structure_table or {})

    def contact(self) -> Any:
        """The :class:`~stickslip.model.contact.Contact` of ``[contact]`` and ``normal_dof``, or None."""
        from stickslip.model.contact import contact_from_table

        return contact_from_table(self.contact_table,
                                  (self.structure_table or {}).get("normal_dof"), source=self.label)

    def friction(self) -> Any:
        """The ``[friction]`` table as :class:`PhysicalFriction` (Coulomb without one)."""
        from stickslip.model.physical import PhysicalFriction, physical_friction_from_config

        if self.friction_table is None:
            return PhysicalFriction()
        source = f"{self.label}: [friction]"
        if self.has_memory_law:
            raise ValueError(memory_law_refusal(source, self.friction_table['law']))
        columns = None
        if self.files is not None and "table" in self.friction_table:
            from stickslip.model.friction_input import friction_csv_columns

            spec = self.friction_table["table"]
            content = uploaded_file(spec, self.files, f"{source} table")
            try:
                text = content.decode("utf-8-sig")
            except UnicodeDecodeError:
                raise ValueError(f"{source} table = {spec!r} is not UTF-8 text") from None
            columns = friction_csv_columns(text, repr(spec))
        try:
            return physical_friction_from_config(self.friction_table, base_dir=self.path.parent,
                                                 source=source, table_columns=columns)
        except ValueError as exc:  # every message names the file and the table once
            message = str(exc)
            if message.startswith(self.label):
                raise
            raise ValueError(f"{source}: {message}") from None

    @property
    def has_memory_law(self) -> bool:
        """True when ``[friction]`` names a law with memory (``rate-state`` or ``lugre``)."""
        from stickslip.model.state_friction_input import is_memory_law

        return is_memory_law(self.friction_table)

    def memory_system(self) -> Any:
        """The :class:`~stickslip.model.state_friction.MemorySystem` of a file with a memory law.

        The paper's slider (``m``, ``k``, ``c``; ``m = "0 kg"`` the quasi-static slider;
        ``m_a``, ``k_a``, ``c_a`` a foundation) or a ``[structure]`` (at most
        :data:`~stickslip.model.machine.MAX_DIRECT_DOF` DOF, or with a ``cutoff``).
        """
        from stickslip.model.state_friction_input import memory_system_from_config

        assert self.friction_table is not None
        structure = None
        if self.structure_table is not None:
            m, c, k, contact, _name, _reduction = build_structure(
                self.structure_table, base_dir=self.path.parent, source=f"{self.label}: [structure]",
                absorber=None, operating_point=None, files=self.files, max_dof=self.max_dof)
            structure = (m, c, k, contact)
        return memory_system_from_config(self.raw, self.friction_table, label=self.label,
                                         structure=structure)

    def absorber(self) -> AbsorberSpec | None:
        """The ``[absorber]`` table, checked (mass in kg; ``attach_dof`` or ``attach``)."""
        table = self.absorber_table
        if table is None:
            return None
        src = f"{self.label}: [absorber]"
        unknown = sorted(set(table) - ABSORBER_KEYS)
        if unknown:
            raise ValueError(f"{src}: unknown keys {', '.join(unknown)} (allowed: "
                             f"{', '.join(sorted(ABSORBER_KEYS))})")
        if "mass" not in table:
            raise ValueError(f"{src}: mass is missing (the absorber mass, e.g. mass = \"3 kg\")")
        mass = si_input(f"{src} mass", to_si("absorber_mass", table["mass"], source=f"{src} mass ="),
                        "kg")
        if ("attach_dof" in table) == ("attach" in table):
            raise ValueError(f"{src}: give either attach_dof (the DOF it hangs on) or "
                             "attach = \"foundation\" (the machine mounted on it)")
        if "attach" in table:
            if table["attach"] != "foundation":
                raise ValueError(f"{src} attach = {table['attach']!r}: the only placement by name is "
                                 "\"foundation\" (else give attach_dof)")
            return AbsorberSpec(mass, None)
        return AbsorberSpec(mass, _whole(table["attach_dof"], f"{src} attach_dof"))

    def structure_matrices(self, *, speed: float, load: float, mu_s: float, mu_k: float) -> Any:
        """Mass, damping, stiffness (SI), contact DOF, name and the reduction (or None).

        Models above :data:`stickslip.model.machine.MAX_DIRECT_DOF` are reduced
        (:mod:`stickslip.analysis.reduction`) to the contact and absorber DOFs plus the
        fixed-interface modes below ``cutoff`` (default from the operating point).
        """
        return build_structure(self.structure_table or {}, base_dir=self.path.parent,
                               source=f"{self.label}: [structure]", absorber=self.absorber(),
                               operating_point=(speed, load, mu_s, mu_k), files=self.files,
                               max_dof=self.max_dof)


#: How many uploaded names a refusal lists.
_NAMES_LISTED = 8


def uploaded_file(spec: object, files: Mapping[str, bytes], source: str) -> bytes:
    """The bytes of the uploaded file that ``spec`` names: a plain base name among ``files``.

    The sandbox of an uploaded machine file: anything else (an absolute path, ``..``, a
    subfolder, a name that was not uploaded, not a string) is refused with one line that is
    the same whether or not such a file exists anywhere: the disk is never looked at.

    Parameters
    ----------
    spec : object
        The value of a file-valued key (``[structure] mass``, ``[friction] table``, ...).
    files : mapping
        The uploaded files: base name -> content.
    source : str
        How the message names the key (file and key).

    Returns
    -------
    bytes
        The file's content.
    """
    if (isinstance(spec, str) and spec in files and spec not in ("", ".", "..")
            and spec == PurePosixPath(spec).name == PureWindowsPath(spec).name):
        return files[spec]
    names = sorted(files)
    listed = ", ".join(names[:_NAMES_LISTED]) + (", ..." if len(names) > _NAMES_LISTED else "")
    raise ValueError(f"{source} = {spec!r} is not one of the files uploaded with it: an uploaded "
                     f"machine file may name only those, by base name (uploaded: {listed})")


def _whole(value: object, src: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        raise ValueError(f"{src} = {value!r} must be a whole number >= 0 (a 0-based DOF index)")
    return int(value)


def _numbers(value: object, src: str) -> list[float]:
    items = value if isinstance(value, list) else [value]
    out = []
    for item in items:
        if isinstance(item, bool) or not isinstance(item, (int, float)) or not math.isfinite(item):
            raise ValueError(f"{src} = {value!r} must be a number or a list of numbers")
        out.append(float(item))
    return out


def read_machine_file(path: Path, *, label: str | None = None,
                      files: Mapping[str, bytes] | None = None,
                      max_dof: int | None = None) -> MachineFile:
    """Parse the machine TOML file; the structure's files are read by :meth:`structure_matrices`.

    Refused with one line: a missing or invalid file, unknown keys, ``[structure]`` together
    with ``m``, ``k``, ``c``, ``m_a``, ``k_a`` or ``c_a``, a table that is not a table.

    Parameters
    ----------
    path : Path
        The TOML file; the files it names are relative to it.
    label : str, optional
        How messages name the file (default ``--config 'PATH'``).
    files : mapping, optional
        Uploaded files, base name -> content (the web app). Then the machine file is
        ``files[path.name]``, nothing is read from disk, and every file it names must be one
        of these, by base name (:func:`uploaded_file`).
    max_dof : int, optional
        The largest structure accepted (DOF): a larger one is refused before it is reduced.
        With ``files``: :data:`UPLOAD_MAX_DOF` unless given, and the files may hold
        :data:`UPLOAD_MAX_MB` in all.
    """
    path = Path(path)
    label = label or f"--config {str(path)!r}"
    content = None
    if files is not None:
        size = sum(len(data) for data in files.values())
        if size > UPLOAD_MAX_MB * 1024**2:
            raise ValueError(f"{label}: the uploaded files hold {size / 1024**2:.1f} MB, beyond "
                             f"the {UPLOAD_MAX_MB} MB accepted")
        max_dof = UPLOAD_MAX_DOF if max_dof is None else max_dof
        content = uploaded_file(path.name, files, f"{label}: the file")
        if len(content) > UPLOAD_MAX_TOML_MB * 1024**2:  # parsing 46 MB of TOML took a minute
            raise ValueError(f"{label}: the machine file holds {len(content) / 1024**2:.1f} MB, "
                             f"beyond the {UPLOAD_MAX_TOML_MB} MB accepted; give large matrices "
                             "as .mtx, .npy or .csv files")
    data = read_toml_file(path, label, content)
    tables = {name: data.get(name) for name in ("friction", "structure", "absorber", "contact")}
    for name, table in tables.items():
        if table is not None and not isinstance(table, dict):
            raise ValueError(f"{label}: {name} = {table!r} must be a table ([{name}])")
    top_level = sorted(k for k in data if k not in tables and k != "system")
    if "system" in data and not isinstance(data["system"], dict):
        raise ValueError(f"{label}: system = {data['system']!r} must be a table ([system]) of "
                         "quantities")
    if "system" in data and top_level:
        raise ValueError(f"{label}: {', '.join(top_level)} at the top level and a [system] table "
                         "both give the quantities; give them in one place (the top level)")
    section = data.get("system", {k: v for k, v in data.items() if k not in tables})
    if not isinstance(section, dict):
        raise ValueError(f"{label}: 'system' must be a table of quantities, not {section!r}")
    unknown = sorted(set(section) - set(QUANTITIES))
    if unknown:
        raise ValueError(f"{label}: unknown keys {', '.join(unknown)}")
    blank = sorted(k for k, v in section.items() if isinstance(v, str) and not v.strip())
    if blank:  # written but empty: not the same as a key left out
        raise ValueError(f"{label}: {blank[0]} = {section[blank[0]]!r} is empty; give a value with "
                         f"its unit (e.g. m = \"2 kg\") or leave the key out")
    if tables["structure"] is not None:
        both = [k for k in PAPER_STRUCTURE_KEYS if k in section]
        if both:
            raise ValueError(f"{label}: {', '.join(both)} and [structure] both describe the "
                             "structure; give one of them")
    if tables["absorber"] is not None and tables["structure"] is None:
        raise ValueError(f"{label}: [absorber] needs a [structure] (for the paper's slider, the "
                         "foundation is m_a, k_a, c_a)")
    if tables["friction"] is not None:  # a law it does not have, before what its keys lack
        law_name(tables["friction"], f"{label}: [friction]")
    return MachineFile(path, dict(section), tables["friction"], tables["structure"],
                       tables["absorber"], tables["contact"], shown_as=label, files=files,
                       max_dof=max_dof)


def _modal_table(table: dict[str, Any], source: str) -> tuple[Any, Any, Any]:
    """``(mass, damping, stiffness)`` of a ``[structure]`` table given as ``modes`` (contact first)."""
    from stickslip.model.machine import MAX_DIRECT_DOF, modal_structure

    extra = sorted(set(table) - {"modes", "name"})
    if extra:
        raise ValueError(f"{source}: modes describe the structure as seen from the contact; "
                         f"{', '.join(extra)} cannot be given with them")
    modes = table["modes"]
    if not isinstance(modes, dict) or set(modes) != MODE_KEYS:
        raise ValueError(f"{source}: modes = {modes!r} must be a table with exactly "
                         f"{', '.join(sorted(MODE_KEYS))}")
    freqs = [to_si("frequency", f, source=f"{source} modes.frequencies =")
             for f in (modes["frequencies"] if isinstance(modes["frequencies"], list)
                       else [modes["frequencies"]])]
    if len(freqs) > MAX_DIRECT_DOF:
        raise ValueError(f"{source}: modes has {len(freqs)} modes; at most {MAX_DIRECT_DOF} are "
                         "run (modal tables are not reduced): give the modes of the frequency "
                         "range the contact excites, the lowest first")
    m: Any
    c: Any
    k: Any
    ratios = _numbers(modes["damping_ratios"], f"{source} modes.damping_ratios")
    shapes = _numbers(modes["shapes"], f"{source} modes.shapes")  # each names itself once
    try:
        with np.errstate(over="raise", invalid="raise", under="raise"):
            m, c, k = modal_structure(freqs, ratios, shapes)
    except FloatingPointError:
        raise ValueError(f"{source} modes: frequencies {modes['frequencies']!r} and shapes "
                         f"{modes['shapes']!r} give matrices beyond the range of floating-point "
                         "numbers (check their units)") from None
    except ValueError as exc:
        raise ValueError(f"{source} {exc}") from None
    return m, c, k


def _table_damping(table: dict[str, Any], m: Any, k: Any, c: Any, names: tuple[str, str, str],
                   source: str, full_dof: int) -> Any:
    """The damping matrix a ``[structure]`` table asks for: ``rayleigh``, ``modal_damping``, the
    matrix read (``c``) or none (zeros).

    ``modal_damping`` as a list gives one ratio per mode of the user's model (``full_dof``
    of them at most), in ascending frequency. A reduced model (``m`` smaller than
    ``full_dof``) takes the first ``m.shape[0]`` ratios for its modes, which approximate the
    model's lowest ones; the rest belong to modes above the cut-off, which it does not have.
    """
    from stickslip.model.machine import modal_damping, rayleigh_damping
    from stickslip.model.structure import checked_matrices

    if "rayleigh" in table:
        alpha_beta = _numbers(table["rayleigh"], f"{source} rayleigh")
        if len(alpha_beta) != 2:
            raise ValueError(f"{source} rayleigh = {table['rayleigh']!r} must be [alpha, beta] "
                             "(C = alpha M + beta K; 1/s and s)")
        try:
            c = rayleigh_damping(m, k, *alpha_beta)
        except ValueError as exc:
            raise ValueError(f"{source} rayleigh: {exc}") from None
    elif "modal_damping" in table:
        ratios = _numbers(table["modal_damping"], f"{source} modal_damping")
        try:
            checked_matrices(m, np.zeros_like(m), k, names=names, limit=None)
            if isinstance(table["modal_damping"], list):
                ratios = _modal_ratios(ratios, m.shape[0], full_dof)
                c = modal_damping(m, k, ratios)
            else:
                c = modal_damping(m, k, ratios[0])
        except ValueError as exc:
            raise ValueError(f"{source} modal_damping: {exc}") from None
    elif c is None:
        c = np.zeros_like(m)
    return c


def _modal_ratios(ratios: list[float], modes: int, full_dof: int) -> list[float]:
    """The ratios of a ``modal_damping`` list for a model of ``modes`` DOF reduced from
    ``full_dof`` (equal when not reduced): the first ``modes`` of at most ``full_dof``."""
    if modes == full_dof:
        return ratios  # modal_damping names the count it needs
    if len(ratios) > full_dof:
        raise ValueError(f"has {len(ratios)} ratios for the {full_dof} modes of the "
                         f"{full_dof}-DOF model (give one, or one per mode)")
    if len(ratios) < modes:
        raise ValueError(f"has {len(ratios)} ratios; the {full_dof}-DOF model is reduced to "
                         f"{modes} DOF, whose modes take the first {modes} of one ratio per mode "
                         f"of the model (ascending frequency, up to {full_dof}), or give one "
                         "ratio for every mode")
    return ratios[:modes]


def build_structure(table: dict[str, Any], *, base_dir: Path | None, source: str,
                    absorber: AbsorberSpec | None = None,
                    operating_point: tuple[float, float, float, float] | None = None,
                    files: Mapping[str, bytes] | None = None, max_dof: int | None = None,
                    ) -> tuple[Any, Any, Any, int, str, Any]:
    """``(mass, damping, stiffness, contact_dof, name, reduction)`` of a ``[structure]`` table.

    Matrices in SI, checked by :class:`stickslip.model.machine.Machine` next; ``reduction``
    is the :class:`~stickslip.analysis.reduction.ReducedStructure` when the model was larger
    than :data:`~stickslip.model.machine.MAX_DIRECT_DOF`, else None. With ``files`` (uploads
    by base name) the matrix files are those only (:func:`uploaded_file`); a model above
    ``max_dof`` DOF is refused.
    """
    import scipy.sparse

    from stickslip.io.structure_files import read_matrix
    from stickslip.model.machine import MAX_DIRECT_DOF
    from stickslip.model.structure import checked_matrices

    unknown = sorted(set(table) - STRUCTURE_KEYS)
    if unknown:
        raise ValueError(f"{source}: unknown keys {', '.join(unknown)} (allowed: "
                         f"{', '.join(sorted(STRUCTURE_KEYS))})")
    if not isinstance(table.get("name", ""), str):
        raise ValueError(f"{source}: name = {table['name']!r} must be a text in quotes, e.g. "
                         "name = \"slideway\"")
    name = str(table.get("name", "machine"))
    if len(name) > MAX_NAME_LENGTH:  # it titles figures: a 1 MB name took minutes to draw
        raise ValueError(f"{source}: name is {len(name)} characters long; at most "
                         f"{MAX_NAME_LENGTH}")
    if "modes" in table:
        m, c, k = _modal_table(table, source)
        if absorber is not None and absorber.attach_dof not in (None, 0):
            # the coordinates after the contact are modal amplitudes, not points of the machine
            raise ValueError(f"{source.replace('[structure]', '[absorber]')} attach_dof = "
                             f"{absorber.attach_dof}: a structure given by modes has one point, "
                             "the contact (attach_dof = 0), or attach = \"foundation\"; its other "
                             "coordinates are modal amplitudes, where no absorber can hang")
        return m, c, k, 0, name, None
    for key in ("mass", "stiffness"):
        if key not in table:
            raise ValueError(f"{source}: {key} is missing (a .mtx/.npy/.csv path or inline rows)")
    given = [key for key in ("damping", "rayleigh", "modal_damping") if key in table]
    if len(given) > 1:
        raise ValueError(f"{source}: {' and '.join(given)} both give the damping; give one")
    if "contact_dof" not in table:
        raise ValueError(f"{source}: contact_dof is missing (the 0-based DOF the belt rubs)")
    contact = _whole(table["contact_dof"], f"{source} contact_dof")
    normal = (_whole(table["normal_dof"], f"{source} normal_dof") if "normal_dof" in table
              else None)
    mats = {key: read_matrix(table[key], quantity=key, unit=table.get(f"{key}_unit"),
                             base_dir=base_dir, source=f"{source} {key}",
                             content=None if files is None or not isinstance(table[key], str)
                             else uploaded_file(table[key], files, f"{source} {key}"),
                             max_dof=max_dof)
            for key in ("mass", "stiffness", "damping") if key in table}
    if "damping_unit" in table and "damping" not in table:
        raise ValueError(f"{source}: damping_unit is given but no damping matrix")
    n = mats["mass"].shape[0]
    for key, mat in mats.items():
        if mat.shape[0] != n:
            raise ValueError(f"{source} {key} = {table[key]!r} is {mat.shape[0]}x{mat.shape[0]}, "
                             f"but mass is {n}x{n}")
    if max_dof is not None and n > max_dof:
        raise ValueError(f"{source}: the matrices are {n}x{n}, a {n}-DOF model, beyond the "
                         f"{max_dof} DOF accepted here")
    if contact >= n:
        raise ValueError(f"{source} contact_dof = {contact} is beyond the {n} DOF of the matrices "
                         f"(0 to {n - 1})")
    if normal is not None and (normal >= n or normal == contact):
        raise ValueError(f"{source} normal_dof = {normal} " + (
            f"is beyond the {n} DOF of the matrices (0 to {n - 1})" if normal >= n else
            "is the contact_dof: the normal DOF moves across the belt, the contact DOF along it"))
    if absorber is not None and absorber.attach_dof is not None and absorber.attach_dof >= n:
        raise ValueError(f"{source.replace('[structure]', '[absorber]')} attach_dof = "
                         f"{absorber.attach_dof} is beyond the {n} DOF of the structure")
    reduction = None
    label = {key: f"{source} {key} = {table[key]!r}" if key in table else f"{source} {key}"
             for key in ("mass", "damping", "stiffness")}
    names = (label["mass"], label["damping"], label["stiffness"])
    given_cutoff = None
    if "cutoff" in table:  # checked at any size; a model of <= MAX_DIRECT_DOF DOF is run whole
        from stickslip.analysis.reduction import check_cutoff

        given_cutoff = check_cutoff(to_si("frequency", table["cutoff"], source=f"{source} cutoff ="),
                                    source=f"{source} cutoff = {table['cutoff']!r}")
    if n > MAX_DIRECT_DOF:
        from stickslip.analysis.reduction import reduce_at_operating_point
        from stickslip.model.structure import check_large_matrices

        check_large_matrices(mats["mass"], mats.get("damping"), mats["stiffness"], names=names)
        kept = [contact] + ([absorber.attach_dof] if absorber is not None
                            and absorber.attach_dof is not None else [])
        kept += [normal] if normal is not None and normal not in kept else []
        if given_cutoff is None and operating_point is None:
            raise ValueError(f"{source}: a {n}-DOF model needs cutoff (or the operating point)")
        reduction = reduce_at_operating_point(mats["mass"], mats["stiffness"], kept,
                                              cutoff_hz=given_cutoff, operating_point=operating_point)
        m, k = reduction.mass, reduction.stiffness
        c = reduction.project(mats["damping"]) if "damping" in mats else None
        contact = 0
    else:
        dense = {key: mat.toarray() if scipy.sparse.issparse(mat) else mat for key, mat in mats.items()}
        m, k = dense["mass"], dense["stiffness"]
        c = dense.get("damping")
    c = _table_damping(table, m, k, c, names, source, n)
    try:
        m, c, k = checked_matrices(m, c, k, names=names, limit=None)
    except ValueError as exc:
        message = str(exc)
        raise ValueError(message if message.startswith(source) else f"{source}: {message}") from None
    if reduction is not None and absorber is not None and absorber.attach_dof is not None:
        absorber_index = reduction.kept_dofs.index(absorber.attach_dof)
        name = f"{name} (absorber DOF {absorber.attach_dof} is reduced DOF {absorber_index})"
    return m, c, k, contact, name, reduction


def machine_from_file(machine_file: MachineFile, values: dict[str, float], *,
                      normal_coupling: bool = False) -> Any:
    """The :class:`~stickslip.model.machine.Machine` of a file with a ``[structure]``.

    ``values`` are the flat quantities in SI (``mu_s``, ``mu_k``, ``load``, ``speed``),
    after flags and file are merged. Returns ``(machine, reduction)``. A file with a
    ``[contact]`` or ``normal_dof`` is refused in one line unless ``normal_coupling`` (the
    caller reads :meth:`MachineFile.contact` itself: ``stickslip stability``).
    """
    from stickslip.model.contact import NOT_SUPPORTED
    from stickslip.model.machine import Machine

    if machine_file.has_contact and not normal_coupling:
        raise ValueError(f"{machine_file.label}: {NOT_SUPPORTED}")
    op = (values["speed"], values["load"], values["mu_s"], values["mu_k"])
    m, c, k, contact, name, reduction = machine_file.structure_matrices(
        speed=op[0], load=op[1], mu_s=op[2], mu_k=op[3])
    friction = machine_file.friction()  # its messages name the file and [friction] already
    try:
        machine = Machine(m, c, k, contact, values["mu_s"], values["mu_k"], values["load"],
                          values["speed"], friction, name=name)
    except ValueError as exc:
        raise ValueError(f"{machine_file.label}: {exc}") from None
    return machine, reduction
