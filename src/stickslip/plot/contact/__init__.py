"""Figures of a machine with its contact: time history, map and continuation.

* :mod:`~stickslip.plot.contact.history`: displacements and normal force, phases marked.
* :mod:`~stickslip.plot.contact.maps`: the map over belt speed and load.
* :mod:`~stickslip.plot.contact.continuation`: period and amplitude of the attractors.

The modules load on first use; this package imports nothing.
"""
