"""Sweeps of a machine with its contact (normal-load coupling, separation, a Jenkins element).

* :mod:`~stickslip.sweep.contact.maps`: one contact-engine run per (belt speed, load) cell.
* :mod:`~stickslip.sweep.contact.basin`: a verdict of the contact engine per disturbed start.

The modules load on first use; this package imports nothing.
"""
