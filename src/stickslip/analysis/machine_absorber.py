"""Which absorber fixes my machine: tuning an absorber of given mass on any structure (issue 18.4).

An absorber of mass ``m_a`` (kg) is placed on the machine in one of two ways
(:meth:`stickslip.model.machine.Machine.with_absorber` / :func:`mounted_on_foundation`):

* on DOF ``attach_dof`` (a tuned-mass damper hanging from that DOF by ``k_a``, ``c_a``);
* as the machine's foundation (``attach_dof = None``): every spring and dashpot the structure
  has to the ground now ends on the absorber mass, which sits on ``k_a``, ``c_a`` to the
  ground. For the paper's slider this *is* the paper's elastic foundation (Fig. 1), so on
  the 1DOF machine both objectives below are today's tuning problems.

Two objectives over ``(k_a, c_a)`` (searched in the dimensionless ``k_a / k_ref`` and
``c_a / sqrt(m_ref k_ref)`` of the machine's contact scaling, :mod:`stickslip.model.machine`):

(a) ``hinf``: minimise the peak receptance at the contact, ``max_w |H_cc(w)|`` (the paper's
    H-infinity criterion, Section 3.1, generalised), with the exact peak search of
    :mod:`stickslip.analysis.frequency_response` and the minimax optimiser of
    :func:`stickslip.analysis.tuning.minimise_peak`. Starts: Den Hartog's tuning on the mode
    with the largest receptance peak at the contact (``phi_c^2 / (2 zeta_r w_r^2)``), i.e. the
    mode that stick-slips, seen from the absorber's DOF.
(b) ``stick-slip``: maximise the simulated onset ``lambda_c`` of stick-slip (Coulomb law, from
    the start-up state, :func:`stickslip.analysis.critical.lowest_onset`): the critical belt
    speed ``V_c`` below which the machine stick-slips is then the lowest (the stick-slip-free
    range of speeds the widest), and the critical load ``W_c`` above which it stick-slips
    the highest. Nelder-Mead from the H-infinity optimum (the objective is piecewise
    constant at the scale of the onset's tolerance: a good design, not a certified optimum).
    With another friction law the tuning still uses the Coulomb onset (one search by the
    machine's own law per candidate is too slow for the optimiser; see
    :mod:`stickslip.analysis.stick_slip_tuning`); the critical speed and load reported for
    the result are the machine's own law, and the report says the tuning assumes Coulomb.

Each result reports the critical speed and load without and with the absorber.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.critical import ONSET_GROWTH, lowest_onset, speed_and_load_onsets
from stickslip.analysis.frequency_response import response_peak
from stickslip.analysis.simulation import EngineOptions, SimulationResult, simulate
from stickslip.analysis.verdict import RunStatus, Verdict
from stickslip.model._validate import MAX_PARAMETER, MIN_RATIO
from stickslip.model.machine import Machine

FloatArray = NDArray[np.float64]

#: Scan limits of the onset search, dimensionless lambda.
LAM_MIN, LAM_MAX = 0.01, 200.0

#: What ``V_c`` and ``W_c`` of a machine are, and what they are not. On the gallery's
#: slideway the start-up verdict changes five times between 0.5 and 2 mm/s (steady sliding at
#: 0.61-0.66 mm/s, stick-slip again at 0.93-1.02 mm/s, both confirmed by an independent
#: solve_ivp integration): one onset cannot say that.
ONSET_NOTE = (f"V_c and W_c are where a scan from steady sliding (lambda in "
              f"{(ONSET_GROWTH - 1.0) * 100:.0f} % steps, then bisected) first meets stick-slip; "
              "beyond them a machine of several DOF can change verdict again (`stickslip boundary "
              "--config FILE --range A:B` lists every change along the speed or the load)")


def mounted_on_foundation(machine: Machine, mass: float, stiffness: float, damping: float) -> Machine:
    """The machine on a foundation mass (kg) with ``stiffness`` (N/m), ``damping`` (N s/m) to ground.

    The ground springs of the structure are the row sums ``g = K 1`` (for a lumped model, the
    spring from each DOF to the ground); they now join each DOF to the new last DOF ``x_f``:
    ``K' = [[K, -g], [-g', 1'K1 + k_f]]`` (and the same for the damping). For the paper's
    slider (``K = [k]``) this is Fig. 1: ``[[k, -k], [-k, k + k_a]]``.

    Parameters
    ----------
    machine : Machine
        The structure in SI.
    mass, stiffness, damping : float
        Foundation mass (kg), its spring (N/m) and dashpot (N s/m) to the ground.

    Returns
    -------
    Machine
        The machine with the foundation as its last DOF.
    """
    from stickslip.model._validate import non_negative, positive

    n = machine.n_dof
    mats = []
    for matrix, value in ((machine.stiffness, positive("absorber stiffness", stiffness)),
                          (machine.damping, non_negative("absorber damping", damping))):
        g = matrix.sum(axis=1)
        big = np.zeros((n + 1, n + 1))
        big[:n, :n] = matrix
        big[:n, n] = -g
        big[n, :n] = -g
        big[n, n] = g.sum() + value
        mats.append(big)
    mass_matrix = np.zeros((n + 1, n + 1))
    mass_matrix[:n, :n] = machine.mass
    mass_matrix[n, n] = positive("absorber mass", mass)
    return replace(machine, mass=mass_matrix, stiffness=mats[0], damping=mats[1],
                   name=f"{machine.name} on a foundation")


def with_absorber(machine: Machine, mass: float, stiffness: float, damping: float,
                  attach_dof: int | None) -> Machine:
    """The machine with the absorber on ``attach_dof``, or mounted on it (``None``).

    Parameters
    ----------
    machine : Machine
        The structure in SI.
    mass, stiffness, damping : float
        Absorber mass (kg), spring (N/m) and dashpot (N s/m).
    attach_dof : int or None
        The DOF it hangs on (:meth:`Machine.with_absorber`); None mounts the machine on it
        (:func:`mounted_on_foundation`).

    Returns
    -------
    Machine
        The machine with the absorber as its last DOF.
    """
    if attach_dof is None:
        return mounted_on_foundation(machine, mass, stiffness, damping)
    return machine.with_absorber(mass, stiffness, damping, attach_dof)


@dataclass(frozen=True)
class CriticalPoint:
    """Critical ``lambda`` (dimensionless), belt speed (m/s) and load (N) of one machine."""

    lam: float
    speed: float
    load: float
    #: runs of the two searches that ended undetermined, counted where steady sliding is not
    #: proven (:func:`~stickslip.analysis.critical.find_onset`)
    undetermined: int = 0
    #: the run just past the speed onset ended undetermined, not proven stick-slip
    undetermined_above: bool = False
    #: the same for the load onset (None: the speed's; with a law that moves with V and W the
    #: two searches are separate, and one can end undetermined while the other does not)
    load_undetermined_above: bool | None = None

    def describe(self, with_lambda: bool = False) -> str:
        """``stick-slip below V_c=... m/s / above W_c=... N``, with what the searches left open.

        When the run just past the onset is undetermined, the onset is where steady sliding
        stops being proven, and the text says so instead of claiming stick-slip beyond it.
        ``with_lambda`` adds ``(lambda_c=...)`` after the values.
        """
        speed, load = f"V_c={self.speed:.4g} m/s", f"W_c={self.load:.4g} N"
        lam = f" (lambda_c={self.lam:.4g})" if with_lambda else ""
        load_open = (self.undetermined_above if self.load_undetermined_above is None
                     else self.load_undetermined_above)
        if load_open != self.undetermined_above:
            open_note = "(the run just past it is undetermined, not proven stick-slip)"
            text = (f"steady sliding proven at the runs above {speed} {open_note}"
                    if self.undetermined_above else f"stick-slip below {speed}")
            text += (f" / steady sliding proven at the runs below {load} {open_note}"
                     if load_open else f" / stick-slip above {load}") + lam
        elif self.undetermined_above:
            # the searches prove steady sliding at their runs, not at every speed between them
            text = (f"steady sliding proven at the runs above {speed} / below {load}{lam}, the "
                    "onset searched (the run just past it is undetermined, not proven stick-slip)")
        else:
            text = f"stick-slip below {speed} / above {load}{lam}"
        if self.undetermined:
            text += (f" ({self.undetermined} run(s) undetermined: counted as not proven steady; "
                     "a longer horizon, --t-max, may decide them)")
        return text

    @classmethod
    def of(cls, machine: Machine, options: EngineOptions | None = None,
           on_run: Callable[[str, float, SimulationResult], None] | None = None,
           scale_of: Machine | None = None) -> CriticalPoint:
        """Onset of stick-slip of ``machine``: ``lambda_c`` and the SI values.

        The verdict at a belt speed does not depend on the scaling, so ``V_c`` and ``W_c``
        of machines with different ``m_ref``, ``k_ref`` (an absorber on the contact DOF) are
        comparable; their ``lambda_c`` are only in one scaling: ``lambda_c`` is given in the
        scaling of ``scale_of`` (the bare machine, for an absorber's onset), else in the
        machine's own. At the same ``V_c``, ``lambda = dmu W / (V sqrt(m_ref k_ref))`` gives
        ``lambda_c(scale_of) = lambda_c(own) sqrt(m_ref k_ref / (m_ref' k_ref'))`` (an
        audit found an absorber's 0.3568 beside the bare machine's scale, 0.3713 in it).
        With the machine's own friction law
        (:func:`~stickslip.analysis.critical.speed_and_load_onsets`): under a law that moves
        with the belt speed or the load, ``V_c`` and ``W_c`` come from one search each and
        ``lam`` is the one at ``V_c``.
        """
        onsets = speed_and_load_onsets(machine.structure(), machine.reference_system(),
                                       lam_min=LAM_MIN, lam_max=LAM_MAX, rtol=1e-6,
                                       options=options, on_run=on_run)
        lam = onsets.speed.lam
        speed = 0.0 if not math.isfinite(lam) else machine.speed_for_lambda(lam)
        lam_load = onsets.load.lam
        load = math.inf if not math.isfinite(lam_load) else machine.load_for_lambda(lam_load)
        undetermined = onsets.speed.n_undetermined + (
            onsets.load.n_undetermined if onsets.own_law else 0)  # Coulomb: one search for both
        if scale_of is not None:
            lam *= math.sqrt(machine.reference_mass * machine.reference_stiffness
                             / (scale_of.reference_mass * scale_of.reference_stiffness))
        return cls(lam, speed, load, undetermined, onsets.speed.undetermined_above,
                   onsets.load.undetermined_above if onsets.own_law else None)

    def to_dict(self) -> dict[str, Any]:
        """``lambda_c``, ``critical_speed_m_per_s``, ``critical_load_N`` (None when infinite)."""
        def num(x: float) -> float | None:
            return float(x) if math.isfinite(x) else None

        return {"lambda_c": num(self.lam), "critical_speed_m_per_s": num(self.speed),
                "critical_load_N": num(self.load), "undetermined_runs": self.undetermined,
                "undetermined_past_onset": self.undetermined_above,
                "load_undetermined_past_onset": (self.undetermined_above
                                                 if self.load_undetermined_above is None
                                                 else self.load_undetermined_above),
                "onset_search": ONSET_NOTE}


@dataclass(frozen=True)
class AbsorberDesign:
    """One tuned absorber: parameters (SI and dimensionless), its objective and critical point."""

    objective: str
    mass: float
    stiffness: float
    damping: float
    attach_dof: int | None
    peak_receptance: float
    critical: CriticalPoint

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready with units in the key names."""
        return {"objective": self.objective, "mass_kg": self.mass, "stiffness_N_per_m": self.stiffness,
                "damping_N_s_per_m": self.damping,
                "attach": "foundation" if self.attach_dof is None else self.attach_dof,
                "peak_receptance_m_per_N": self.peak_receptance, **self.critical.to_dict()}


@dataclass(frozen=True)
class MachineDesign:
    """Verdict at the operating point, critical speed and load, and the absorbers (issue 18).

    Attributes
    ----------
    machine : Machine
    verdict : str
        Certified verdict of one run at the operating point (file's friction law).
    period_s, amplitude_m : float
        Of the stick-slip cycle (NaN otherwise); amplitude = half the peak-to-peak of the
        contact DOF over one cycle, in metres.
    peak_receptance : float
        ``max |H_cc|`` of the bare machine, m/N.
    critical : CriticalPoint
        Onset of stick-slip without absorber (the machine's friction law).
    absorbers : tuple of AbsorberDesign
        The H-infinity and the stick-slip optimum (empty without ``[absorber]``).
    status : RunStatus or None
        How the run at the operating point ended (why an undetermined verdict is one).
    t_max : float
        Its dimensionless horizon.
    stability : dict or None
        Linear stability of steady sliding with a friction law that is not Coulomb's (growth
        rate in 1/s, tolerated slope, Hopf boundaries along speed and load:
        :func:`~stickslip.analysis.stability_boundaries.steady_sliding_report`); None for
        the Coulomb law, whose slope is zero at every speed.
    """

    machine: Machine
    verdict: str
    period_s: float
    amplitude_m: float
    certificate: str
    peak_receptance: float
    critical: CriticalPoint
    absorbers: tuple[AbsorberDesign, ...] = field(default=())
    status: RunStatus | None = None
    t_max: float = EngineOptions().t_max
    stability: dict[str, Any] | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready report (SI units in the key names, dimensionless numbers beside them)."""
        def num(x: float) -> float | None:
            return float(x) if math.isfinite(x) else None

        sl = self.machine.slider()
        return {"machine": self.machine.to_dict(), "verdict": self.verdict,
                "certificate": self.certificate, "period_s": num(self.period_s),
                "amplitude_m": num(self.amplitude_m), "lambda": sl.lam, "gamma": sl.gamma,
                "zeta": self.machine.structure().zeta,
                "peak_receptance_m_per_N": self.peak_receptance,
                "critical": self.critical.to_dict(),
                "critical_speed": num(self.critical.speed), "critical_load": num(self.critical.load),
                "status": None if self.status is None else self.status.label, "t_max": self.t_max,
                "absorbers": [{**a.to_dict(), **({"assumption": self.tuning_note}
                                                 if a.objective == "stick-slip" else {})}
                              for a in self.absorbers],
                **({} if self.stability is None else {"stability": self.stability})}

    def _critical_text(self) -> str:
        """The critical point, or what its search found at a bound of its range."""
        c = self.critical
        if math.isinf(c.lam):
            return (f"no stick-slip certified up to lambda = {LAM_MAX:g}, the search's upper bound "
                    f"({_bound_text(self.machine, LAM_MAX)}): no critical speed or load inside it")
        if c.lam <= LAM_MIN:
            return (f"stick-slip already at lambda = {LAM_MIN:g}, the search's lower bound "
                    f"({_bound_text(self.machine, LAM_MIN)}): V_c and W_c lie beyond it")
        return c.describe(with_lambda=True)

    def summary(self) -> str:
        """Plain-text report."""
        lines = [self.machine.summary(),
                 f"at V={self.machine.speed:.4g} m/s, W={self.machine.load:.4g} N: {self.verdict}"
                 + (f" (period {self.period_s:.4g} s, amplitude {self.amplitude_m:.4g} m)"
                    if math.isfinite(self.period_s) else ""),
                 f"{self._critical_text()}; peak receptance {self.peak_receptance:.4g} m/N"]
        if self.verdict == Verdict.UNDETERMINED.value and self.status is not None:
            why = (f"{self.status.message.split(';')[0]}; rerun with a longer horizon, --t-max "
                   f"{10 * self.t_max:g} (now {self.t_max:g})" if self.status is RunStatus.T_MAX
                   else self.status.message)
            lines.insert(2, f"undetermined because: {why}")
        for a in self.absorbers:
            lines.append(f"absorber ({a.objective}): m_a={a.mass:.4g} kg, k_a={a.stiffness:.4g} N/m, "
                         f"c_a={a.damping:.4g} N s/m -> {a.critical.describe()}, "
                         f"peak {a.peak_receptance:.4g} m/N")
            if a.objective == "stick-slip" and self.tuning_note is not None:
                lines.append(f"  (this absorber {self.tuning_note})")
        if self.machine.n_dof > 1:
            lines.append(f"note: {ONSET_NOTE}")
        if self.stability is not None:
            s = self.stability
            word = "stable" if s["stable"] else "neutral" if s["neutral"] else "UNSTABLE"
            lines += [f"steady sliding with the friction law ({self.machine.friction.law}): {word}, "
                      f"growth rate {s['growth_rate']:.4g} 1/s; the slope d mu/d v_r at V is "
                      f"{-s['sigma_local']:.4g} s/m, down to {-s['sigma_crit']:.4g} s/m is "
                      "stable (the structure's damping)",
                      f"  {s['boundaries']['sentence']}"]
        return "\n".join(lines)

    @property
    def tuning_note(self) -> str | None:
        """The stick-slip absorber's Coulomb assumption in one sentence; None for a Coulomb machine."""
        from stickslip.analysis.design import coulomb_tuning_note

        return coulomb_tuning_note(self.machine.friction.law, onset_own_law=True)


def _bound_text(machine: Machine, lam: float) -> str:
    """``V`` (m/s) and ``W`` (N) at ``lambda = lam`` of ``machine``'s contact."""
    return f"V = {machine.speed_for_lambda(lam):.4g} m/s, W = {machine.load_for_lambda(lam):.4g} N"


def _peak_si(machine: Machine) -> float:
    """``max |H_cc|`` in m/N: the dimensionless peak over ``k_ref``."""
    return float(response_peak(machine.structure()).h_max) / machine.reference_stiffness


def _den_hartog_start(machine: Machine, mass: float, attach_dof: int | None) -> tuple[float, float]:
    """Den Hartog's ``(k_a, c_a)`` (SI) on the mode with the largest receptance peak at the contact.

    Mode ``r`` (mass-normalised ``phi``) seen from the absorber's DOF has the modal mass
    ``1 / phi_a^2`` (for the foundation placement: the mass of the whole machine); with
    ``mu = m_a / m_r``: ``f = 1 / (1 + mu)``, ``zeta_a = sqrt(3 mu / (8 (1 + mu)^3))``.
    """
    from scipy.linalg import eigh

    w2, phi = eigh(machine.stiffness, machine.mass)
    w = np.sqrt(np.maximum(w2, 0.0))
    modal_c = np.einsum("ir,ij,jr->r", phi, machine.damping, phi)
    zeta = np.maximum(modal_c / (2.0 * np.maximum(w, 1e-300)), 1e-6)
    c = machine.contact_dof
    r = int(np.argmax(phi[c] ** 2 / (2.0 * zeta * w2)))
    m_r = float(np.trace(machine.mass)) if attach_dof is None else 1.0 / max(phi[attach_dof, r] ** 2, 1e-300)
    mu = mass / m_r
    f = 1.0 / (1.0 + mu)
    zeta_a = math.sqrt(3.0 * mu / (8.0 * (1.0 + mu) ** 3))
    w_a = f * float(w[r])
    return mass * w_a**2, 2.0 * zeta_a * mass * w_a


def tune_machine_absorber(machine: Machine, mass: float, attach_dof: int | None, *,
                          stick_slip: bool = True, maxiter: int = 40) -> tuple[AbsorberDesign, ...]:
    """The H-infinity optimum and (if ``stick_slip``) the stick-slip optimum, module docstring.

    Parameters
    ----------
    machine : Machine
        The structure in SI with its contact and operating point.
    mass : float
        Absorber mass, kg.
    attach_dof : int or None
        The DOF the absorber hangs on; None mounts the machine on it.
    stick_slip : bool
        Also search the absorber that maximises the critical speed (many simulations).
    maxiter : int
        Iterations of the stick-slip search.

    Returns
    -------
    tuple of AbsorberDesign
        ``hinf`` first, then (with ``stick_slip``) the stick-slip optimum.
    """
    from scipy.optimize import minimize

    from stickslip.analysis.peak_minimiser import minimise_peak

    m_ref, k_ref = machine.reference_mass, machine.reference_stiffness
    if not MIN_RATIO <= mass / m_ref <= MAX_PARAMETER:  # the paper's mass ratio M, bounded
        raise ValueError(f"[absorber] mass = {mass:g} kg is {mass / m_ref:.3g} times the contact "
                         f"DOF's mass ({m_ref:g} kg), outside the supported ratio range "
                         f"[{MIN_RATIO:g}, {MAX_PARAMETER:g}]")
    c_scale = math.sqrt(m_ref * k_ref)

    def build_si(x: FloatArray) -> Machine:
        return with_absorber(machine, mass, float(x[0]) * k_ref, float(x[1]) * c_scale, attach_dof)

    k0, c0 = _den_hartog_start(machine, mass, attach_dof)
    x0 = np.array([k0 / k_ref, c0 / c_scale])
    starts = [x0, x0 * np.array([1.0, 3.0]), x0 * np.array([1.0, 1.0 / 3.0])]
    bounds = [(x0[0] * 1e-3, x0[0] * 1e3), (x0[1] * 1e-3, x0[1] * 1e3)]
    scale = (m_ref, k_ref)  # one unit of receptance for every candidate: 1 / k_ref of the bare machine
    best = minimise_peak(lambda x: build_si(x).structure(scale), starts, bounds)
    x_h = np.asarray(best.params, dtype=np.float64)
    hinf_machine = build_si(x_h)
    designs = [AbsorberDesign("hinf", mass, float(x_h[0]) * k_ref, float(x_h[1]) * c_scale, attach_dof,
                              _peak_si(hinf_machine),
                              CriticalPoint.of(hinf_machine, scale_of=machine))]
    if stick_slip:
        def objective(y: FloatArray) -> float:
            x = np.exp(np.clip(y, np.log([b[0] for b in bounds]), np.log([b[1] for b in bounds])))
            m = build_si(x)
            lam = lowest_onset(m.structure(scale), gamma=m.slider().gamma, lam_min=LAM_MIN,
                               lam_max=LAM_MAX, rtol=1e-4)
            return -lam  # lambda_c in the bare machine's scaling: V_c = dmu W / (lam sqrt(m k))

        y0 = np.log(x_h)
        res = minimize(objective, y0, method="Nelder-Mead",
                       options={"maxiter": maxiter, "xatol": 1e-3, "fatol": 1e-5,
                                "initial_simplex": [y0, y0 + np.array([0.2, 0.0]),
                                                    y0 + np.array([0.0, 0.4])]})
        y = res.x if res.fun <= objective(y0) else y0
        x_s = np.exp(y)
        ss_machine = build_si(x_s)
        designs.append(AbsorberDesign("stick-slip", mass, float(x_s[0]) * k_ref,
                                      float(x_s[1]) * c_scale, attach_dof, _peak_si(ss_machine),
                                      CriticalPoint.of(ss_machine, scale_of=machine)))
    return tuple(designs)


def design_machine(machine: Machine, absorber_mass: float | None = None,
                   attach_dof: int | None = None, *, stick_slip: bool = True,
                   options: EngineOptions | None = None,
                   progress: Callable[[str, int], None] | None = None) -> MachineDesign:
    """Verdict at the operating point, critical speed and load, and the tuned absorbers.

    Parameters
    ----------
    machine : Machine
        The structure in SI with its contact and operating point.
    absorber_mass : float, optional
        Absorber mass, kg; no absorber design without it.
    attach_dof : int or None
        The DOF the absorber hangs on; None mounts the machine on it (the paper's foundation).
    stick_slip : bool
        Also find the stick-slip optimum (many simulations).
    options : EngineOptions, optional
        Engine limits of the run at the operating point and of the onset searches.
    progress : callable, optional
        ``progress(stage, runs)`` when a stage starts and after every run of the searches.

    Returns
    -------
    MachineDesign
        Verdict, period and amplitude in SI, critical point and absorbers.
    """
    runs = 0

    def tell(stage: str) -> Callable[..., None]:
        def count(*_: object) -> None:
            nonlocal runs
            runs += 1
            if progress is not None:
                progress(stage, runs)

        if progress is not None:
            progress(stage, runs)
        return count

    structure, slider = machine.to_dimensionless()
    tell("verdict at the operating point")
    run = simulate(structure, slider, options=options, record=False)
    ref = machine.reference_system()
    period = run.period * ref.time_scale
    amplitude = run.amplitude * ref.length_scale
    absorbers: tuple[AbsorberDesign, ...] = ()
    critical = CriticalPoint.of(machine, options, tell("critical speed and load"))
    if absorber_mass is not None:
        tell("absorber tuning")
        absorbers = tune_machine_absorber(machine, absorber_mass, attach_dof, stick_slip=stick_slip)
    return MachineDesign(machine, run.verdict.value, period, amplitude, run.certificate,
                         _peak_si(machine), critical, absorbers, run.status,
                         (options or EngineOptions()).t_max, _steady_sliding(machine))


def _steady_sliding(machine: Machine) -> dict[str, Any] | None:
    """:func:`~stickslip.analysis.stability_boundaries.steady_sliding_report` of a machine whose
    law is not Coulomb's (None for the Coulomb law: zero slope at every speed)."""
    from stickslip.analysis.stability_boundaries import (
        machine_stability_boundaries,
        steady_sliding_report,
    )

    if machine.friction.law == "coulomb":
        return None
    structure, slider = machine.to_dimensionless()
    ref = machine.reference_system()
    return steady_sliding_report(
        structure.contact_first()[0], slider, machine_stability_boundaries(machine),
        natural_frequency=ref.natural_frequency,
        per_slope=2.0 * math.sqrt(machine.reference_mass * machine.reference_stiffness) / machine.load)
