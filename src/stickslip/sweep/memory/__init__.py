"""Sweeps of a machine whose friction has memory (rate-and-state, LuGre).

* :mod:`~stickslip.sweep.memory.maps`: linear stability of steady sliding over speed and load.
* :mod:`~stickslip.sweep.memory.basin`: a verdict for each disturbed start.

The modules load on first use; this package imports nothing.
"""
