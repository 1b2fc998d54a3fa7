"""The contact itself: a normal degree of freedom, a contact spring and tangential compliance.

The paper's contact is rigid and its normal load ``W`` is a constant. A machine file may
instead name the DOF that moves normal to the belt and the contact's own springs::

    [structure]
    contact_dof = 0              # the tangential DOF, along the belt (as before)
    normal_dof = 1               # 0-based, positive AWAY from the belt

    [contact]
    normal_stiffness = "4e7 N/m" # the contact spring k_n, active while in contact
    normal_damping = "20 N*s/m"  # optional, c_n (a Kelvin-Voigt contact)
    # tangential_stiffness = "1e8 N/m"  # a Jenkins element between slider and belt,
    # tangential_damping = "5 N*s/m"    # with optional damping and a contact mass
    # mass = "1 g"

The structure's matrices hold the machine's own springs only; the contact adds its spring.
``load`` is the preload that pushes ``normal_dof`` towards the belt, so the normal force is

    N = load - k_n q[normal_dof] - c_n q'[normal_dof]        (while N > 0)

with ``q`` measured from the position where the contact spring carries exactly the preload
(``q = 0``: ``N = load``). Friction is ``mu N`` while sliding and ``|F| <= mu_s N`` in stick.

While in contact the contact is unilateral: it lifts off when ``N`` reaches zero (then no
friction and no contact spring: **separation**) and re-engages, without impact (the contact
is a spring: velocities are continuous), when the spring is compressed again. The Jenkins
element (``tangential_stiffness``) puts a contact point between the slider and the belt: it
sticks to the belt while the element's force is within ``mu_s N`` and slips at ``mu_k N``.

This module holds the :class:`Contact` object (SI, checked at construction) and its reader
from a TOML table, :func:`contact_from_table` (units as everywhere in machine files).
Which commands use it: ``stickslip simulate`` (time histories with stick, slip and
separation on the exact contact engine, :mod:`stickslip.analysis.contact.engine`; the
Jenkins element too), ``stickslip stability`` (the complex-eigenvalue analysis of steady
sliding, :mod:`stickslip.analysis.contact.eigenvalues`; the Jenkins element too,
:func:`stickslip.analysis.contact.friction_coupling.jenkins_state_matrix`) and
``stickslip cycles``, ``basin`` and ``continue`` (runs of the contact engine:
:mod:`stickslip.analysis.contact.cycles`, :mod:`stickslip.sweep.contact.basin`,
:mod:`stickslip.analysis.contact.continuation`). Every other command refuses such a machine in
one line (:data:`NOT_SUPPORTED`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from stickslip.model.physical import MAX_SI, MIN_SI
from stickslip.model.units import to_si

#: Keys of the ``[contact]`` table and their quantity (:data:`stickslip.model.units.STRUCTURE_QUANTITIES`).
CONTACT_KEYS: dict[str, str] = {
    "normal_stiffness": "stiffness",
    "normal_damping": "damping",
    "tangential_stiffness": "stiffness",
    "tangential_damping": "damping",
    "mass": "mass",
}

#: The one line every command but ``simulate`` and ``stability`` gives for a machine with a contact.
NOT_SUPPORTED = ("a machine with its contact ([structure] normal_dof and the [contact] table) runs "
                 "in `stickslip simulate`, `stability`, `design`, `map`, `boundary`, `cycles`, "
                 "`basin` and `continue`; this command (absorber tuning) assumes a rigid contact: "
                 "remove them to run it")

@dataclass(frozen=True)
class Contact:
    """The contact of a machine in SI units (see the module docstring for the layout).

    Parameters
    ----------
    normal_dof : int or None
        0-based DOF that moves normal to the belt, positive away from it; None: the normal
        load is the constant ``load`` (the paper's contact).
    normal_stiffness : float or None
        Contact spring ``k_n``, N/m (> 0); required with ``normal_dof`` and only with it.
    normal_damping : float
        Contact damper ``c_n``, N s/m (>= 0), acting with the spring.
    tangential_stiffness : float or None
        Stiffness of the Jenkins element between the slider and the belt, N/m (> 0); None: a
        rigid tangential contact.
    tangential_damping : float
        Damping of the Jenkins element, N s/m (>= 0); only with ``tangential_stiffness``.
    mass : float or None
        Mass of the contact point, kg (> 0); None: massless. Only with ``tangential_stiffness``.

    Raises
    ------
    ValueError
        One line naming the value and why.
    """

    normal_dof: int | None = None
    normal_stiffness: float | None = None
    normal_damping: float = 0.0
    tangential_stiffness: float | None = None
    tangential_damping: float = 0.0
    mass: float | None = None

    def __post_init__(self) -> None:
        dof = self.normal_dof
        if dof is not None and (isinstance(dof, bool) or not isinstance(dof, int) or dof < 0):
            raise ValueError(f"normal_dof = {dof!r} must be a whole number >= 0 (a 0-based DOF index)")
        if (dof is None) != (self.normal_stiffness is None):
            raise ValueError("normal_dof and [contact] normal_stiffness go together: the normal force "
                             "N = load - normal_stiffness * q[normal_dof] needs both"
                             if dof is None else
                             f"normal_dof = {dof} needs [contact] normal_stiffness (the contact "
                             "spring of N = load - normal_stiffness * q[normal_dof])")
        _check("normal_stiffness", self.normal_stiffness, positive=True)
        _check("normal_damping", self.normal_damping, positive=False)
        _check("tangential_stiffness", self.tangential_stiffness, positive=True)
        _check("tangential_damping", self.tangential_damping, positive=False)
        _check("mass", self.mass, positive=True)
        if self.tangential_stiffness is None:
            extra = [k for k, v in (("tangential_damping", self.tangential_damping != 0.0),
                                    ("mass", self.mass is not None)) if v]
            if extra:
                verb, who = ("need", "they belong") if len(extra) > 1 else ("needs", "it belongs")
                raise ValueError(f"[contact] {' and '.join(extra)} {verb} tangential_stiffness (the "
                                 f"spring of the Jenkins element {who} to)")

    @property
    def has_normal_dof(self) -> bool:
        """True when the normal load follows the motion of :attr:`normal_dof`."""
        return self.normal_dof is not None

    @property
    def has_tangential_compliance(self) -> bool:
        """True when a Jenkins element joins the slider to the belt."""
        return self.tangential_stiffness is not None

    def check_dofs(self, n_dof: int, contact_dof: int) -> None:
        """Check :attr:`normal_dof` against a structure of ``n_dof`` DOF rubbed on ``contact_dof``.

        Parameters
        ----------
        n_dof : int
            Number of DOF of the structure.
        contact_dof : int
            The tangential DOF.

        Raises
        ------
        ValueError
            ``normal_dof`` beyond the structure or equal to ``contact_dof``.
        """
        dof = self.normal_dof
        if dof is None:
            return
        if dof >= n_dof:
            raise ValueError(f"normal_dof = {dof} is beyond the {n_dof} DOF of the matrices "
                             f"(0 to {n_dof - 1})")
        if dof == contact_dof:
            raise ValueError(f"normal_dof = {dof} is the contact_dof: the normal DOF moves across "
                             "the belt, the contact DOF along it; they must differ")


#: Largest contact stiffness (``k_n``, ``k_t``) accepted, relative to the structure's stiffest
#: diagonal entry: a time scale ``1e-6`` of the structure's (at ``1e30`` N/m on a 1 N/m slider
#: the states of the 1e-15 s element repeated to rounding and were called a period, and the
#: eigenvalues of steady sliding lose every digit of the structure's own).
MAX_CONTACT_STIFFNESS = 1e12


def check_contact_stiffness(normal_stiffness: float | None, tangential_stiffness: float | None,
                            stiffness: Any) -> None:
    """Refuse a contact spring beyond :data:`MAX_CONTACT_STIFFNESS` times the structure's.

    One rule for every engine that takes a contact (simulation, cycles, eigenvalues).

    Parameters
    ----------
    normal_stiffness, tangential_stiffness : float or None
        The contact springs, N/m (None: absent).
    stiffness : array_like
        The structure's stiffness matrix, N/m.

    Returns
    -------
    None
        Nothing: the springs are within the bound.

    Raises
    ------
    ValueError
        One line naming the spring, the structure's stiffest spring and why.
    """
    import numpy as np

    structure = float(np.max(np.abs(np.diag(np.atleast_2d(stiffness)))))
    for name, value in (("normal_stiffness", normal_stiffness),
                        ("tangential_stiffness", tangential_stiffness)):
        if value is not None and structure > 0.0 and value > MAX_CONTACT_STIFFNESS * structure:
            raise ValueError(
                f"{name} = {value:.4g} N/m is beyond {MAX_CONTACT_STIFFNESS:g} times the "
                f"structure's stiffest spring ({structure:.4g} N/m): its time scale is below "
                "what double precision resolves beside the structure's; for a rigid contact "
                "leave the element out")


def _check(name: str, value: float | None, *, positive: bool) -> None:
    if value is None:
        return
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"[contact] {name} = {value!r} must be a finite number")
    if positive and value <= 0.0:
        raise ValueError(f"[contact] {name} = {value!r} must be positive")
    if not positive and value < 0.0:
        raise ValueError(f"[contact] {name} = {value!r} must not be negative")
    if value != 0.0 and not MIN_SI <= value <= MAX_SI:
        raise ValueError(f"[contact] {name} = {value!r} is outside the supported range "
                         f"[{MIN_SI:g}, {MAX_SI:g}] in SI units (beyond it the contact's terms "
                         "overflow double precision)")


def contact_from_table(table: Mapping[str, Any] | None, normal_dof: object, *,
                       source: str) -> Contact | None:
    """The :class:`Contact` of a machine file's ``[contact]`` table and ``[structure] normal_dof``.

    Parameters
    ----------
    table : mapping or None
        The ``[contact]`` table as read (quantities as numbers in SI or strings with units).
    normal_dof : object
        ``[structure] normal_dof`` as read, or None when absent.
    source : str
        How messages name the file (``--config 'machine.toml'``).

    Returns
    -------
    Contact or None
        None when the file has neither: the paper's rigid contact under a constant load.

    Raises
    ------
    ValueError
        One line naming the file, the key, the value and why.
    """
    if table is None and normal_dof is None:
        return None
    table = dict(table or {})
    unknown = sorted(set(table) - set(CONTACT_KEYS))
    if unknown:
        raise ValueError(f"{source}: [contact]: unknown keys {', '.join(unknown)} (allowed: "
                         f"{', '.join(sorted(CONTACT_KEYS))})")
    values = {key: to_si(CONTACT_KEYS[key], value, source=f"{source}: [contact] {key} =")
              for key, value in table.items()}
    try:
        return Contact(normal_dof=normal_dof, **values)  # type: ignore[arg-type]
    except ValueError as exc:
        message = str(exc)
        if message.startswith("normal_dof"):
            message = f"[structure] {message}"
        raise ValueError(f"{source}: {message}") from None
