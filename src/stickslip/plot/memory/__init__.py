"""Figures of a machine whose friction has memory.

* :mod:`~stickslip.plot.memory.history`: displacement, slip speed and friction of a run.

The modules load on first use; this package imports nothing.
"""
