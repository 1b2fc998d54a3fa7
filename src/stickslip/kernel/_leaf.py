"""How the kernels of the hot event search compile: without reference counts.

numba gives every array a reference count, changed with an atomic instruction. A callee
counts its own array arguments up on entry and down on exit where it cannot prove the pairs
redundant, and a caller counts each array argument around a call it does not inline. In the
run loop of :mod:`stickslip.kernel.engine` these counts were 17 % of a 2-DOF basin's time (a
profile of the "foundation weak" basin, whose tabulated law has an event at every band edge).
A *leaf kernel* allocates nothing, so it compiles with ``_nrt=False``: no counts inside it
(its views of the per-mode tables are free, where the run loop's slices cost two counts
each). The counts at the call site remain (measured: numba emits them for any call it does
not inline), which is why the run loop indexes its tables and slices nothing per step. The
arithmetic is unchanged, bit for bit.
"""

from __future__ import annotations

from typing import Any

from numba import njit


def leaf_kernel(**options: Any) -> Any:
    """``njit(cache=True, _nrt=False, **options)``: see the module notes.

    A leaf kernel may call only leaf kernels (numba compiles a callee with its caller's
    flags, and an allocation without reference counts is refused at compile time).
    """
    flags: dict[str, Any] = {"cache": True, "_nrt": False, **options}  # _nrt: numba's own option
    return njit(**flags)
