"""Judging an identification: its residuals against the record's own noise, the stated mass
against the mass the record implies, the drive speed against its stick phases.

A fit's warnings, or its refusal (:class:`~stickslip.analysis.identification.estimates.RecordError`),
come from here; :mod:`stickslip.analysis.identification.record_fit` fits.
"""

from __future__ import annotations

import math

import numpy as np

from stickslip.analysis.identification.estimates import (
    MISMATCH_CHI2,
    NOISE_FLOOR,
    STICK_SPEED_NOTE,
    MeasuredRecord,
    RecordError,
    RecordEstimates,
    uneven_steps_note,
)

#: Above this reduced chi-square (residuals ten times the noise) the fit is refused: no motion
#: of the law describes the record (no stick-slip, a wrong mass or drive speed). Only when the
#: record's noise is measurable (above :data:`NOISE_FLOOR` of its range): a noise-free record
#: has no yardstick.
REFUSE_CHI2 = 100.0
#: A stated mass beyond this factor of the mass the record's slip phases imply
#: (``k / omega^2``, :class:`~stickslip.analysis.identification.estimates.RecordEstimates`) is
#: flagged: the slip phases of a 1 kg slider last 1000**0.5 times less than those of 1000 kg.
MASS_FACTOR = 10.0


def mass_note(est: RecordEstimates, mass: float) -> str:
    """What is wrong with a stated mass beyond :data:`MASS_FACTOR` of the record's.

    Parameters
    ----------
    est : RecordEstimates
        The record's estimates (its implied mass ``k / omega^2``, kg).
    mass : float
        The stated mass, kg.

    Returns
    -------
    str
        The note, or ``""`` when the mass is within the factor.
    """
    ratio = mass / est.implied_mass if math.isfinite(est.implied_mass) and est.implied_mass > 0 else 1.0
    if 1.0 / MASS_FACTOR <= ratio <= MASS_FACTOR:
        return ""
    return (f"the stated mass {mass:.4g} kg is {ratio:.3g} times the {est.implied_mass:.3g} kg "
            "that the record's slip phases imply (k / omega^2)")


def judge(record: MeasuredRecord, est: RecordEstimates, chi2: float, dof: int, *,
           mass: float, speed: float) -> tuple[str, ...]:
    """Warnings on a fit (or a refusal): residuals against the record's noise, the mass, the
    drive speed against the stick phases' (when x is recorded).

    Parameters
    ----------
    record : MeasuredRecord
        The record fitted.
    est : RecordEstimates
        Its estimates (noise levels, implied mass, stick speed).
    chi2 : float
        The fit's weighted sum of squared residuals.
    dof : int
        Its degrees of freedom (residuals less free parameters).
    mass, speed : float
        The stated mass (kg) and drive speed (m/s).

    Returns
    -------
    tuple of str
        The warnings.

    Raises
    ------
    RecordError
        When the residuals exceed ``sqrt(REFUSE_CHI2)`` times a measurable noise.
    """
    reduced = chi2 / max(dof, 1)
    mass_text = mass_note(est, mass)
    noisy = all(est.noise[n] > NOISE_FLOOR * float(np.ptp(getattr(record, n))) for n in record.channels)
    verdict = (f"the model does not describe the record: its residuals are {math.sqrt(reduced):.3g} "
               f"times the record's own noise (reduced chi-square {reduced:.3g})")
    if reduced > REFUSE_CHI2 and noisy:
        why = mass_text or ("is it stick-slip, and are the mass, load and drive speed right?")
        raise RecordError(f"{verdict}, beyond {math.sqrt(REFUSE_CHI2):g} times: no fit is reported; {why}")
    out = []
    if reduced > MISMATCH_CHI2:
        out.append(f"{verdict}, above {math.sqrt(MISMATCH_CHI2):g} times: the values are those of the "
                   "closest model, not of the record")
    if mass_text:
        out.append(mass_text + ": check --mass")
    uneven = uneven_steps_note(record.t)
    if uneven is not None:
        out.append(uneven)
    ratio_v = est.stick_speed / speed  # NaN without x: no note
    if (abs(ratio_v - 1.0) > STICK_SPEED_NOTE
            and abs(est.stick_speed - speed) > 5.0 * est.stick_speed_error):
        out.append(f"the record's stick phases move at {est.stick_speed:.4g} m/s, {ratio_v:.4g} "
                   f"times the stated drive speed V = {speed:.4g} m/s (a sticking slider moves "
                   "with the belt); the fit takes V as stated: check --speed")
    return tuple(out)
