"""One run of the exact engine as a result object: the types every simulation shares.

:func:`run_engine` runs :func:`stickslip.kernel.engine.run` once and wraps its summaries in a
:class:`SimulationResult` (verdict, certificate, cycle data, the recorded phases for dense
output); :class:`EngineOptions` holds the engine's limits and tolerances. A stick-slip verdict
of a run is the engine's *candidate* (a breakaway state repeated to ``cycle_tol``):
:func:`stickslip.analysis.simulation.simulate` proves it
(:mod:`stickslip.analysis.cycle_proof`), and the return map of
:mod:`stickslip.analysis.return_map` evaluates itself with bare runs.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from stickslip.analysis.interpolant_margin import interpolant_mismatch
from stickslip.analysis.stability import steady_sliding_stability
from stickslip.analysis.verdict import Mode, RunStatus, Verdict
from stickslip.kernel import dense_output, engine
from stickslip.kernel.system import mode_kind_band
from stickslip.model._validate import positive
from stickslip.model.initial import InitialState, startup_state
from stickslip.model.parameters import Slider
from stickslip.model.structure import Structure, state_permutation, to_user_order

if TYPE_CHECKING:
    import xarray as xr

    from stickslip.analysis.disturbance import SafeDisturbance

FloatArray = NDArray[np.float64]

DEFAULT_T_MAX = 5000.0
DEFAULT_MAX_EVENTS = 100_000
DEFAULT_CYCLE_TOL = 1e-9
DEFAULT_MAX_PERIOD = 8


@dataclass(frozen=True)
class SimulationResult:
    """Outcome of :func:`simulate`: verdict, certificate, cycle data and the trajectory.

    Times are dimensionless (``tau = omega_n t``), displacements in units of
    ``V / omega_n``, velocities in units of the belt speed ``V``.

    Attributes
    ----------
    verdict : Verdict
        ``stick-slip``, ``steady-sliding`` or ``undetermined``.
    status : RunStatus
        How the run ended.
    certificate : str
        What proves the verdict (empty when undetermined).
    n_stick : int
        Number of stick phases in the run, including the initial one of the startup state.
    cycle_length : int
        Number of stick phases (for a slip oscillation: Poincare-section crossings) in one
        period of the certified cycle; 0 without a cycle. ``cycle_k`` is its former name
        (deprecated, one release); datasets and JSON keep the key ``cycle_k``.
    period, amplitude, stick_ratio : float
        Of the certified cycle: period in ``tau``, half the peak-to-peak of ``xi``, and the
        fraction of the period spent stuck. NaN without a cycle.
    max_velocity : float
        Largest slider velocity ``xi'`` reached in the run.
    friction_description : str
        The friction law and how it was computed (exact, or piecewise linear with its
        law approximation tolerance).
    growth_rate : float
        Largest real part of the eigenvalues of the linearisation about steady sliding
        (per unit ``tau``); positive: steady sliding is linearly unstable.
    steady_sliding_stable : bool
        ``growth_rate`` below minus its round-off bound.
    steady_sliding_neutral : bool
        ``|growth_rate|`` within its round-off bound: marginally stable (see
        :class:`~stickslip.analysis.stability.SteadySlidingStability`).
    """

    structure: Structure
    slider: Slider
    initial: InitialState
    t_max: float
    verdict: Verdict
    status: RunStatus
    certificate: str
    n_stick: int
    n_breakaway: int
    cycle_length: int
    period: float
    amplitude: float
    xi_range: tuple[float, float]
    stick_ratio: float
    max_velocity: float
    cycle_max_velocity: float
    cycle_mismatch: float
    lyapunov_bound: float
    t_end: float
    t_certified: float
    n_steps: int
    segment_times: FloatArray = field(repr=False)
    segment_modes: NDArray[np.int64] = field(repr=False)
    segment_states: FloatArray = field(repr=False)
    breakaway_times: FloatArray = field(repr=False)
    final_state: FloatArray = field(repr=False)
    friction_description: str = "coulomb, exact"
    growth_rate: float = math.nan
    steady_sliding_stable: bool = False
    friction_bands: tuple[FloatArray, FloatArray, FloatArray] | None = field(default=None, repr=False)
    #: the proof of a stick-slip cycle (a :class:`~stickslip.analysis.cycle_proof.CycleProof`,
    #: set by :func:`~stickslip.analysis.simulation.simulate`; typed loosely here, below it)
    cycle_proof: Any = field(default=None, repr=False)
    steady_sliding_neutral: bool = False

    @property
    def cycle_k(self) -> int:
        """Deprecated name of :attr:`cycle_length`."""
        warnings.warn("SimulationResult.cycle_k is deprecated: use cycle_length",
                      DeprecationWarning, stacklevel=2)
        return self.cycle_length

    @property
    def event_times(self) -> FloatArray:
        """Times of the mode switches after ``tau = 0``."""
        return self.segment_times[1:]

    @property
    def event_modes(self) -> NDArray[np.int64]:
        """Mode entered at each switch (codes of :class:`Mode`; with a velocity-dependent
        friction law a band change is a switch too, and band ``b >= 1`` has the codes
        ``1 + 2b`` (slip-I) and ``2 + 2b`` (slip-II), see
        :func:`stickslip.kernel.system.mode_kind_band`)."""
        return self.segment_modes[1:]

    def stick_intervals(self, t_start: float = 0.0) -> FloatArray:
        """``(start, end)`` of every stick phase that ends after ``t_start`` (dimensionless
        ``tau``), cut at ``t_start``; shape ``(n, 2)``. The shading of the time histories."""
        times = np.append(self.segment_times, self.t_end)
        rows = [(max(float(times[i]), t_start), float(times[i + 1]))
                for i, mode in enumerate(self.segment_modes)
                if mode == Mode.STICK and times[i + 1] > t_start]
        return np.array(rows, dtype=np.float64).reshape(-1, 2)

    @property
    def initial_mode(self) -> Mode:
        """Friction state at ``tau = 0``."""
        return Mode(mode_kind_band(int(self.segment_modes[0]))[0])

    def _bands(self) -> tuple[FloatArray, FloatArray, FloatArray]:
        if self.friction_bands is not None:
            return self.friction_bands
        return self.slider.friction.bands(self.slider.lam, self.slider.gamma)

    def state_at(self, times: ArrayLikeFloat) -> tuple[FloatArray, FloatArray, NDArray[np.int64]]:
        """Exact positions, velocities and modes at the given times (dense output).

        Parameters
        ----------
        times : array_like
            Dimensionless times in ``[0, t_end]``, any order.

        Returns
        -------
        positions, velocities : ndarray, shape (len(times), n_dof)
        modes : ndarray of int, shape (len(times),)
            Friction state (codes of :class:`Mode`; the friction band is not reported).
        """
        t = np.asarray(times, dtype=np.float64).reshape(-1)
        if t.size and (not np.all(np.isfinite(t)) or t.min() < 0.0 or t.max() > self.t_end):
            raise ValueError(f"times must lie in [0, t_end={self.t_end:g}]")
        order = np.argsort(t, kind="stable")
        st, perm = self.structure.contact_first()
        seg_states = self.segment_states
        if self.structure.contact_dof != 0:
            seg_states = np.ascontiguousarray(seg_states[:, state_permutation(perm)])
        states, modes = dense_output.evaluate(
            st.mass,
            st.damping,
            st.stiffness,
            self.slider.lam,
            self.slider.gamma,
            *self._bands(),
            self.segment_times,
            self.segment_modes,
            seg_states,
            t[order],
        )
        if self.structure.contact_dof != 0:
            states = to_user_order(states, perm, axis=1)
        out = np.empty_like(states)
        out[order] = states
        out_modes = np.empty_like(modes)
        out_modes[order] = modes
        kinds = np.where(out_modes <= engine.STICK, out_modes, (out_modes - 3) % 2)
        out_modes = kinds.astype(out_modes.dtype)
        n = st.n_dof
        return out[:, :n], out[:, n:], out_modes

    def time_history(self, n_points: int = 4000, t_start: float = 0.0) -> TimeHistory:
        """Trajectory sampled on a uniform grid plus every mode switch (for plotting)."""
        if n_points < 2:
            raise ValueError(f"n_points={n_points} must be at least 2")
        t_start = min(max(0.0, t_start), self.t_end)
        grid = np.linspace(t_start, self.t_end, n_points)
        switches = self.segment_times[(self.segment_times >= t_start)]
        t = np.unique(np.concatenate([grid, switches]))
        q, v, modes = self.state_at(t)
        return TimeHistory(t, q, v, modes)

    @property
    def safe_disturbance(self) -> SafeDisturbance:
        """Certified harmless disturbances of steady sliding for this system (no simulation).

        See :func:`stickslip.analysis.disturbance.safe_disturbance`: the largest energy,
        velocity kick and displacement about steady sliding from which the Lyapunov
        certificate proves that the slider never sticks again.
        """
        from stickslip.analysis.disturbance import safe_disturbance

        return safe_disturbance(self.structure, self.slider)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary: the keys ``simulate --json`` prints (``docs/cli.md``)."""
        def num(x: float) -> float | None:
            return None if not math.isfinite(x) else float(x)

        foundation = None
        st = self.structure
        if st.n_dof >= 2:
            foundation = {
                "mass_matrix": st.mass.tolist(),
                "damping_matrix": st.damping.tolist(),
                "stiffness_matrix": st.stiffness.tolist(),
            }
        coulomb = self.slider.friction.to_dict()["law"] == "coulomb"

        def event(t: float, md: int) -> dict[str, Any]:
            kind, band = mode_kind_band(md)
            out: dict[str, Any] = {"t": float(t), "mode": Mode(kind).label}
            if not coulomb:
                out["band"] = band
            return out

        return {
            "contact_dof": st.contact_dof,
            "verdict": self.verdict.value,
            "certificate": self.certificate,
            "status": self.status.label,
            "status_message": self.status.message,
            "n_stick": self.n_stick,
            "n_breakaway": self.n_breakaway,
            "period": num(self.period),
            "amplitude": num(self.amplitude),
            "stick_ratio": num(self.stick_ratio),
            "cycle_k": self.cycle_length if self.cycle_length > 0 else None,
            "cycle_mismatch": num(self.cycle_mismatch),
            "lyapunov_bound": num(self.lyapunov_bound),
            "max_velocity": num(self.max_velocity),
            "t_end": float(self.t_end),
            "t_certified": num(self.t_certified),
            "t_max": float(self.t_max),
            "lambda": self.slider.lam,
            "zeta": self.structure.zeta,
            "gamma": self.slider.gamma,
            "structure": st.name,
            "n_dof": st.n_dof,
            "structure_matrices": foundation,
            "initial_condition": self.initial.description,
            "initial_position": self.initial.position.tolist(),
            "initial_velocity": self.initial.velocity.tolist(),
            "n_events": int(self.event_times.size),
            "events": [
                event(t, int(md)) for t, md in zip(self.event_times, self.event_modes, strict=True)
            ],
            "friction": {**self.slider.friction.to_dict(), "description": self.friction_description},
            "growth_rate": num(self.growth_rate),
            "steady_sliding_stable": bool(self.steady_sliding_stable),
            "steady_sliding_neutral": bool(self.steady_sliding_neutral),
            "safe_disturbance": self.safe_disturbance.to_dict(),
            "cycle_proof": None if self.cycle_proof is None else self.cycle_proof.to_dict(),
        }

    def plot(self, **kwargs: Any) -> Any:
        """Time histories and phase portrait, a ``PlotResult``.

        Delegates to :func:`stickslip.plot.simulation.simulation_plot` (its keywords).
        """
        from stickslip.plot.simulation import simulation_plot

        return simulation_plot(self, **kwargs)


ArrayLikeFloat = Any


@dataclass(frozen=True)
class TimeHistory:
    """Sampled trajectory: ``t`` (n,), ``position``/``velocity`` (n, n_dof), ``mode`` (n,).

    Unpacks as ``t, position, velocity, mode = history``.
    """

    t: FloatArray
    position: FloatArray
    velocity: FloatArray
    mode: NDArray[np.int64]

    def __iter__(self):
        return iter((self.t, self.position, self.velocity, self.mode))

    def to_xarray(self) -> xr.Dataset:
        """As an ``xarray.Dataset`` with dimensions ``tau`` and ``dof``."""
        import xarray as xr

        dof = np.arange(self.position.shape[1])
        return xr.Dataset(
            {
                "position": (("tau", "dof"), self.position, {"units": "V/omega_n"}),
                "velocity": (("tau", "dof"), self.velocity, {"units": "V"}),
                "mode": (
                    ("tau",),
                    self.mode,
                    {"flag_values": [0, 1, 2], "flag_meanings": "slip-I slip-II stick"},
                ),
            },
            coords={"tau": self.t, "dof": dof},
        )


@dataclass(frozen=True)
class EngineOptions:
    """Limits and tolerances of the engine: one object for :func:`simulate` and every sweep.

    Parameters
    ----------
    t_max : float
        Dimensionless time horizon ``tau`` of a run.
    max_events : int
        Bound on the number of mode switches per run (guards against chattering).
    cycle_tol : float
        Relative tolerance for a breakaway state to count as repeated.
    max_period : int
        Longest cycle, in stick phases, that is looked for (period-k cycles).
    """

    t_max: float = DEFAULT_T_MAX
    max_events: int = DEFAULT_MAX_EVENTS
    cycle_tol: float = DEFAULT_CYCLE_TOL
    max_period: int = DEFAULT_MAX_PERIOD

    def __post_init__(self) -> None:
        object.__setattr__(self, "t_max", positive("t_max", self.t_max))
        object.__setattr__(self, "cycle_tol", positive("cycle_tol", self.cycle_tol))
        for name in ("max_events", "max_period"):
            value = getattr(self, name)
            if isinstance(value, bool) or int(value) != value or int(value) < 1:
                raise ValueError(f"{name}={value!r} must be a whole number of at least 1")
            object.__setattr__(self, name, int(value))
        if self.max_events > engine.MAX_STEPS:  # every event ends a step: more never happen
            raise ValueError(f"max_events={self.max_events} exceeds the engine's {engine.MAX_STEPS} steps")

    def with_t_max(self, t_max: float | None) -> EngineOptions:
        """The same options with another horizon (unchanged when ``t_max`` is None)."""
        return self if t_max is None else replace(self, t_max=t_max)

    def to_dict(self) -> dict[str, float | int]:
        """The options as a JSON-ready dictionary (recorded in datasets)."""
        return {
            "t_max": self.t_max,
            "max_events": self.max_events,
            "cycle_tol": self.cycle_tol,
            "max_period": self.max_period,
        }


def _certificate_text(status: RunStatus, n_bands: int, fsum: FloatArray,
                      isum: NDArray[np.int64]) -> str:
    """What proves the verdict of a run, in words (empty for an undetermined run)."""
    if status is RunStatus.CERTIFIED_STEADY and n_bands == 1:
        return (
            f"Lyapunov bound: |xi'| <= {fsum[engine.F_LYAPUNOV_BOUND]:.6g} < 1 for all "
            f"tau >= {fsum[engine.F_T_CERTIFIED]:.6g} in slip-I, so the slider never sticks again"
        )
    if status is RunStatus.CERTIFIED_STEADY:
        return (
            f"Lyapunov bound about steady sliding: |xi'| <= {fsum[engine.F_LYAPUNOV_BOUND]:.6g} "
            f"for all tau >= {fsum[engine.F_T_CERTIFIED]:.6g}, so the sliding speed u = 1 - xi' "
            f"stays inside the friction bands where the Lyapunov function holds and the slider "
            f"never sticks again"
        )
    if status is RunStatus.CERTIFIED_OSCILLATION:
        return (
            f"Poincare-section state repeats after {int(isum[engine.I_CYCLE_K])} crossing(s) "
            f"to {fsum[engine.F_CYCLE_MISMATCH]:.1e} (relative) with no stick phase; period "
            f"{fsum[engine.F_PERIOD]:.6g}, amplitude {fsum[engine.F_AMPLITUDE]:.6g}"
        )
    if status is RunStatus.CERTIFIED_CYCLE:
        return (
            f"breakaway state repeats after {int(isum[engine.I_CYCLE_K])} stick phase(s) "
            f"to {fsum[engine.F_CYCLE_MISMATCH]:.1e} (relative)"
        )
    return ""


def run_engine(structure: Structure, slider: Slider, initial: InitialState | None,
               opts: EngineOptions, record: bool, run_to_t_max: bool) -> SimulationResult:
    """One run of the engine (contact on DOF 0) as a :class:`SimulationResult`.

    Parameters
    ----------
    structure, slider : Structure, Slider
        The system, dimensionless, contact on DOF 0.
    initial : InitialState or None
        The start (``None``: the startup state).
    opts : EngineOptions
        Horizon, event budget, cycle tolerance and longest period.
    record : bool
        Keep the phase list (dense output).
    run_to_t_max : bool
        Go on after the verdict up to ``t_max``.

    Returns
    -------
    SimulationResult
        The run, its stick-slip verdict a candidate (see below).

    A stick-slip verdict here is the engine's *candidate* (a breakaway state repeated to
    ``cycle_tol``); :func:`simulate` proves it
    (:func:`~stickslip.analysis.simulation.prove_run`). :func:`find_cycles` starts runs on
    fixed points it proves itself.
    """
    if initial is None:
        initial = startup_state(structure, slider)
    z0 = initial.as_vector(structure.n_dof)
    bands = slider.friction.bands(float(slider.lam), float(slider.gamma))
    seg_t, seg_mode, seg_state, bk_t, fsum, isum, z_end = engine.run(
        structure.mass,
        structure.damping,
        structure.stiffness,
        float(slider.lam),
        float(slider.gamma),
        *bands,
        z0,
        float(opts.t_max),
        int(opts.max_events),
        float(opts.cycle_tol),
        int(opts.max_period),
        bool(record),
        bool(run_to_t_max),
    )
    status = RunStatus.from_code(int(isum[engine.I_STATUS]))
    n_bands = bands[1].size
    description = slider.friction.describe() + (f" ({n_bands} bands)" if n_bands > 1 else "")
    stability = steady_sliding_stability(structure, slider)
    certificate = _certificate_text(status, n_bands, fsum, isum)
    if status in (RunStatus.CERTIFIED_STEADY, RunStatus.CERTIFIED_OSCILLATION):
        mismatch = interpolant_mismatch(structure, slider)
        withheld = {"steady": RunStatus.CERTIFIED_STEADY,
                    "oscillation": RunStatus.CERTIFIED_OSCILLATION}
        if mismatch is not None and withheld[mismatch[0]] is status:
            status = (RunStatus.INTERPOLANT_STEADY if mismatch[0] == "steady"
                      else RunStatus.INTERPOLANT_OSCILLATION)
            certificate = f"undetermined ({mismatch[1]}); the interpolant's: {certificate}"
    verdict = status.verdict
    return SimulationResult(
        structure=structure,
        slider=slider,
        initial=initial,
        t_max=opts.t_max,
        verdict=verdict,
        status=status,
        certificate=certificate,
        n_stick=int(isum[engine.I_N_STICK]),
        n_breakaway=int(isum[engine.I_N_BREAKAWAY]),
        cycle_length=int(isum[engine.I_CYCLE_K]),
        period=float(fsum[engine.F_PERIOD]),
        amplitude=float(fsum[engine.F_AMPLITUDE]),
        xi_range=(float(fsum[engine.F_XI_MIN]), float(fsum[engine.F_XI_MAX])),
        stick_ratio=float(fsum[engine.F_STICK_RATIO]),
        max_velocity=float(fsum[engine.F_MAX_VELOCITY]),
        cycle_max_velocity=float(fsum[engine.F_CYCLE_MAX_VELOCITY]),
        cycle_mismatch=float(fsum[engine.F_CYCLE_MISMATCH]),
        lyapunov_bound=float(fsum[engine.F_LYAPUNOV_BOUND]),
        t_end=float(fsum[engine.F_T_END]),
        t_certified=float(fsum[engine.F_T_CERTIFIED]),
        n_steps=int(isum[engine.I_N_STEPS]),
        segment_times=seg_t,
        segment_modes=seg_mode,
        segment_states=seg_state,
        breakaway_times=bk_t,
        final_state=z_end,
        friction_description=description,
        growth_rate=stability.growth_rate,
        steady_sliding_stable=stability.stable,
        steady_sliding_neutral=stability.neutral,
        friction_bands=bands,
    )
