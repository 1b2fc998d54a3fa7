"""Proven contraction balls of stick-slip cycles: a run that enters one has its verdict.

:mod:`stickslip.analysis.cycle_proof` proves, for a stable stick-slip cycle of ``q`` stick
phases on a structure of ``n >= 2`` degrees of freedom, a ball on the breakaway section

    ``B = {b : ||C (b - b_hat)||_2 <= rho}``

(``b`` the foundation coordinates of a breakaway state: the state without the slider's
position and velocity, indices ``0`` and ``n``) that the ``q``-th return map sends into itself
and contracts: every breakaway state in ``B`` (on the same piece of the section, onto slip-I
or onto slip-II) converges to the cycle's fixed point, and the cycle's minimal period is
``q``. So a run whose breakaway state lies in a proven ball is certified stick-slip there,
with that cycle, without running on until its breakaway states repeat to ``cycle_tol``
(for a basin of the 2-DOF foundation with multipliers of modulus 0.31 that is 20 stick phases
instead of 8).

Layout, one row per ball: ``ball_data[p]`` holds ``rho``, the section piece (0: onto slip-I,
1: onto slip-II), ``q``, the cycle's period, amplitude, ``xi`` range, stick ratio and largest
velocity (from a run on the fixed point), ``||C||_2``, then ``b_hat`` (``2 n - 2`` numbers);
``ball_norm[p]`` is ``C``. A state is taken to be in the ball when
``||C (b - b_hat)|| + ||C|| STATE_ROUNDING max(1, max |w|) <= rho``: the located breakaway state
carries the rounding of its event, which the membership must not rest on (balls range from
1e-9 to 1e-1). No rows: no ball (every map and 1-DOF run), and the run loop is the one before.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stickslip.kernel import _cache  # noqa: F401  (first: every cached kernel is stamped with the whole kernel folder)

B_RHO = 0
B_ONTO = 1
B_STICK_PHASES = 2
B_PERIOD = 3
B_AMPLITUDE = 4
B_XI_MIN = 5
B_XI_MAX = 6
B_STICK_RATIO = 7
B_CYCLE_MAX_VELOCITY = 8
B_C_NORM = 9
B_CENTER = 10
#: Relative rounding allowed on a located breakaway state (its scale ``max(1, max |w|)``): ten
#: times the round-off allowance of the proof's tube (``_cycle_tube.ROUNDING``).
STATE_ROUNDING = 1e-12


@njit(cache=True)
def no_balls(n):
    """Empty ``(ball_data, ball_norm)`` for a structure of ``n`` degrees of freedom."""
    d = max(2 * n - 2, 0)
    return np.zeros((0, B_CENTER + d)), np.zeros((0, d, d))


@njit(cache=True)
def ball_holding(w, n, onto, ball_data, ball_norm):
    """Row of the first proven ball holding the breakaway state ``w`` (onto ``onto``: 0 slip-I,
    1 slip-II), and its ``||C (b - b_hat)|| / rho``; ``(-1, inf)`` when none does."""
    d = 2 * n - 2
    scale = 1.0
    for c in range(2 * n):
        scale = max(scale, abs(w[c]))
    for p in range(ball_data.shape[0]):
        if ball_data[p, B_ONTO] != onto:
            continue
        acc = 0.0
        for i in range(d):
            row = 0.0
            for j in range(d):
                c = j + 1 if j < n - 1 else j + 2  # b_j: w without indices 0 and n
                row += ball_norm[p, i, j] * (w[c] - ball_data[p, B_CENTER + j])
            acc += row * row
        rho = ball_data[p, B_RHO]
        distance = np.sqrt(acc)
        if distance + ball_data[p, B_C_NORM] * STATE_ROUNDING * scale <= rho:
            return p, distance / rho
    return -1, np.inf


def with_balls(prepared, ball_data, ball_norm):
    """``prepared`` (:func:`stickslip.kernel.system.prepare_point`'s tuple) with these balls."""
    return (*prepared[:23], np.ascontiguousarray(ball_data, dtype=np.float64),
            np.ascontiguousarray(ball_norm, dtype=np.float64))
