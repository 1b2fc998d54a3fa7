"""Nominal data of one phase of a cycle tube (:mod:`stickslip.analysis._cycle_tube`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis._band_variation import BandVariation

FloatArray = NDArray[np.float64]


@dataclass
class Phase:
    """Nominal data of one phase of the run behind ``P^q`` (see :func:`phases`)."""

    mode: int
    duration: float
    a: FloatArray  # A of z' = A z + c
    c: FloatArray
    norm_a: float
    functions: list[tuple[FloatArray, float]]  # (normal n, level g0): g = n.z - g0
    ending: int  # index into functions of the event that ends the phase
    start_zero: list[bool]  # functions that vanish at the start (left from their surface)
    tangential: list[bool]  # ... and leave it tangentially: rate 0 on the whole start section
    g: FloatArray  # (samples, functions) nominal g at the samples
    rate: FloatArray  # (samples, functions) nominal n.f
    curv: FloatArray  # (samples, functions) nominal n.A f, the second derivative of g
    flow_norm: FloatArray  # ||f(z*(s_j))||_2 at the samples
    m_norm: FloatArray  # bounds of ||expm(A s_j)||_2 at the samples (sampled_flow)
    hs: FloatArray  # the sample intervals' lengths
    z_end: FloatArray
    f_minus: FloatArray  # field of this mode at z_end
    f_plus: FloatArray  # field of the next mode at z_end (0 at the map's final section)
    a_plus: FloatArray
    belt_decision: bool  # ends at the belt speed: the next mode is chosen by the stick force
    e_nominal: FloatArray  # expm(A t)
    breakaway: bool  # ends with a breakaway (counted for the minimal-period check)
    engine_norm_a: float  # ||A||_F in the engine's coordinates (its step size: the rounding)
    # the equal-time variant (stickslip.analysis._band_variation): a slip phase of a law
    # continuous at its band edges; the surface u = 0 (the belt speed) among the functions
    bands: BandVariation | None = None
    kind: int = -1
    band: int = 0
    zero_surface: int = -1  # the index of u = 0 in functions (-1: none)
    edge_end: bool = False  # ends at a band edge into the neighbouring band, same slip kind
    m_two: FloatArray | None = None  # tighter bounds of ||expm(A s_j)||_2 (sampled_flow's two_norm)
    #: per-phase bounds that depend on no radius, kept across a proof's radii (see
    #: :func:`stickslip.analysis._cycle_tube._equal_time_growth`)
    cache: dict[Any, Any] = field(default_factory=dict, init=False, repr=False, compare=False)
    salt: FloatArray = field(init=False)  # the nominal saltation matrix at the end
    salt_norm: float = field(init=False)
    e_norm: float = field(init=False)

    def __post_init__(self) -> None:
        nv = self.functions[self.ending][0]
        self.salt = (np.eye(self.f_minus.size)
                     + np.outer(self.f_plus - self.f_minus, nv) / float(nv @ self.f_minus))
        self.salt_norm = float(np.linalg.norm(self.salt, 2))
        self.e_norm = float(np.linalg.norm(self.e_nominal, 2))

    @cached_property
    def salt_off(self) -> float:
        """``||S - I||_2 ||expm(A t)||_2``: the nominal saltation's distance from the identity
        (rounding for a band edge of a continuous law), times the propagator's norm."""
        return float(np.linalg.norm(self.salt - np.eye(self.salt.shape[0]), 2)) * self.e_norm

    def is_equal_time_edge(self, e: int) -> bool:
        """Function ``e`` is a band edge the equal-time variant does not treat as an event."""
        return self.bands is not None and e != self.zero_surface
