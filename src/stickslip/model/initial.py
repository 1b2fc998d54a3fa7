"""Initial conditions in the shifted coordinates of Eqs. (15)-(16)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure

#: Largest magnitude of an initial position or velocity (units ``V / omega_n`` and ``V``):
#: the engine squares the state in its Lyapunov bound and multiplies it by matrices of
#: entries up to 1e13, which stays finite below this. The startup state of the largest
#: accepted parameters (``gamma lambda / K**2`` <= 1e24) is far inside it.
MAX_STATE = 1e100

STARTUP_DESCRIPTION = (
    "startup: the belt starts moving at tau = 0 with every spring at its natural length, "
    "the slider stuck to the belt (xi' = 1) and the foundation at rest"
)


@dataclass(frozen=True)
class InitialState:
    """Positions and velocities of every DOF in shifted dimensionless coordinates.

    Parameters
    ----------
    position : array_like, shape (n,)
        ``xi, xi_a, ...`` measured from the kinetic-friction equilibrium (Eqs. 15-16).
    velocity : array_like, shape (n,)
        ``xi', xi_a', ...`` in units of the belt speed.
    description : str
        Recorded in every output file.
    """

    position: NDArray[np.float64]
    velocity: NDArray[np.float64]
    description: str = "user-defined initial state"

    def __post_init__(self) -> None:
        if np.asarray(self.position).dtype == np.bool_ or np.asarray(self.velocity).dtype == np.bool_:
            raise ValueError("initial state has boolean entries; give numbers")
        pos = np.array(self.position, dtype=np.float64).reshape(-1)
        vel = np.array(self.velocity, dtype=np.float64).reshape(-1)
        if pos.shape != vel.shape:
            raise ValueError(
                f"initial position has {pos.size} entries but velocity has {vel.size}"
            )
        if not (np.all(np.isfinite(pos)) and np.all(np.isfinite(vel))):
            raise ValueError("initial state has NaN or infinite entries")
        big = max(float(np.abs(pos).max(initial=0.0)), float(np.abs(vel).max(initial=0.0)))
        if big > MAX_STATE:
            raise ValueError(
                f"initial state has an entry of magnitude {big:.3g}, beyond the supported "
                f"{MAX_STATE:g} (its energy would overflow)"
            )
        object.__setattr__(self, "position", pos)
        object.__setattr__(self, "velocity", vel)

    def as_vector(self, n_dof: int) -> NDArray[np.float64]:
        """Concatenated ``(positions, velocities)``, checked against ``n_dof``."""
        if self.position.size != n_dof:
            raise ValueError(
                f"initial state has {self.position.size} DOF but the structure has {n_dof}"
            )
        return np.concatenate([self.position, self.velocity])


def startup_state(structure: Structure, slider: Slider) -> InitialState:
    """The default initial condition ("startup").

    All springs at their natural length (``x = 0`` in Eq. 1), so in shifted coordinates
    ``q = -gamma lambda Stiffness^-1 e_0``: for the 2DOF system
    ``xi = -gamma lambda (1 + 1/K^2)``, ``xi_a = -gamma lambda / K^2``; for the rigid base
    ``xi = -gamma lambda``. The slider moves with the belt (``xi' = 1``), the foundation is
    at rest.

    Parameters
    ----------
    structure : Structure
        Dimensionless mass, damping and stiffness matrices, contact on DOF 0.
    slider : Slider
        The frictional contact: ``lambda``, ``gamma`` and the friction law.

    Returns
    -------
    InitialState
        Springs relaxed, slider stuck to the belt, foundation at rest.
    """
    from stickslip.model._validate import friction_range

    friction_range(slider.lam, slider.gamma)
    position = -slider.gamma * slider.lam * structure.kinetic_equilibrium_offset()
    if not np.all(np.isfinite(position)):
        raise ValueError(
            f"the startup state overflows: gamma * lambda = {slider.gamma * slider.lam:.3g} "
            "times the structure's static deflection is not finite"
        )
    velocity = np.zeros(structure.n_dof)
    velocity[structure.contact_dof] = 1.0
    return InitialState(position, velocity, STARTUP_DESCRIPTION)
