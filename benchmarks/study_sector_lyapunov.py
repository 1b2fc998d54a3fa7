"""Study: would a common quadratic Lyapunov function certify bench_basin's steady states sooner?

    .venv/bin/python benchmarks/study_sector_lyapunov.py [--states 400] [--steady 40]

The 2-DOF "foundation weak" case of bench_basin.py. In slip-I, relative to steady sliding,
``z' = A(s) z`` with ``s(t)`` the friction law's secant slope ``(F(u) - F(1)) / (u - 1)``
(the band table's law, continuous), and ``A(s)`` affine in ``s``: a quadratic ``V = z' P z``
with ``A(s)' P + P A(s)`` negative definite at both ends of the secant range over
``|u - 1| <= R`` decreases for every slope between them, so ``sqrt(kappa V) < R``
(``kappa = (P^-1)_vv``) certifies steady sliding. For ``R`` in a ladder it tries ``P`` from
``A(s)' P + P A(s) = -Q`` at slopes across the range (three ``Q``) and prints whether one
holds at both ends. Then, for the first ``--steady`` steady-sliding states of the benchmark's
box (labelled by :func:`stickslip.basin_stability`), it integrates the motion (scipy
``solve_ivp`` with the band table's law; no engine) and prints the mean time at which each
function certifies: the energy (valid where the damping stays positive semi-definite, margin
0.11 here) against the common functions, and against the function whose region is shaped for
it (:func:`largest_region`: the ellipsoid of largest volume inside ``|v_0| <= R`` on which
the condition holds at both ends, a max-det problem solved by SLSQP and then checked as the
others are).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import scipy.linalg
from scipy.integrate import solve_ivp
from scipy.optimize import minimize

sys.path.insert(0, str(Path(__file__).resolve().parent))  # bench_basin's case

from bench_basin import foundation_weak_case

from stickslip import Verdict, basin_stability
from stickslip.sweep.basin import sample_box


def largest_region(ends: tuple[np.ndarray, np.ndarray], starts: list[np.ndarray],
                   v_index: int) -> tuple[np.ndarray, float] | None:
    """``(P, kappa)`` of the largest-volume ellipsoid on which ``A' P + P A < 0`` at both ends.

    With ``Q = P^-1 = L L'`` the condition reads ``A Q + Q A' < 0`` (a congruence), linear in
    ``Q``; the volume at a fixed ``kappa = Q_vv`` is ``det Q`` up to scale, so SLSQP maximises
    the scale-free ``log det Q - m log Q_vv`` over ``L`` from each of ``starts`` (matrices
    ``Q``). The optimiser only proposes: the result is returned only when ``A' P + P A`` is
    negative definite at both ends, as every function of the study is checked.
    """
    m = ends[0].shape[0]
    lower = np.tril_indices(m)

    def q_of(x: np.ndarray) -> np.ndarray:
        root = np.zeros((m, m))
        root[lower] = x
        return root @ root.T

    def volume(x: np.ndarray) -> float:
        q = q_of(x)
        sign, logdet = np.linalg.slogdet(q)
        return -(logdet - m * np.log(q[v_index, v_index])) if sign > 0 else 1e9

    def decrease(x: np.ndarray) -> np.ndarray:
        q = q_of(x)
        return np.array([-np.max(np.linalg.eigvalsh(a @ q + q @ a.T)) / np.trace(q) - 1e-7 for a in ends])

    best = None
    for start in starts:
        res = minimize(volume, np.linalg.cholesky(start)[lower], method="SLSQP",
                       constraints=[{"type": "ineq", "fun": decrease}], options={"maxiter": 500})
        if np.all(decrease(res.x) > 0.0) and (best is None or res.fun < best.fun):
            best = res
    if best is None:
        return None
    q = q_of(best.x)
    p = np.linalg.inv(q)
    if not all(np.max(np.linalg.eigvalsh(a.T @ p + p @ a)) < 0 for a in ends):
        return None
    return p, float(q[v_index, v_index])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--states", type=int, default=400)
    parser.add_argument("--steady", type=int, default=40)
    args = parser.parse_args()
    if args.states < 1 or args.steady < 1:
        parser.error("--states and --steady must be at least 1")
    structure, slider, box = foundation_weak_case()
    mass, damping, stiffness = (np.asarray(x, dtype=float) for x in
                                (structure.mass, structure.damping, structure.stiffness))
    n = mass.shape[0]
    minv = np.linalg.inv(mass)
    edges, intercepts, slopes = (np.asarray(x) for x in slider.friction.bands(slider.lam, slider.gamma))

    def law(u: np.ndarray | float) -> np.ndarray:
        b = np.searchsorted(edges, u, side="right") - 1
        return intercepts[b] + slopes[b] * u

    def a_of(s: float) -> np.ndarray:
        c = damping.copy()
        c[0, 0] += s
        return np.block([[np.zeros((n, n)), np.eye(n)], [-minv @ stiffness, -minv @ c]])

    f_one = float(law(1.0))
    s_eq = float(slopes[np.searchsorted(edges, 1.0, side="right") - 1])

    def secant_range(r: float) -> tuple[float, float]:
        u = np.concatenate([np.linspace(1 - r, 1 + r, 4001), edges[(edges > 1 - r) & (edges < 1 + r)]])
        u = u[u != 1.0]
        sig = (law(u) - f_one) / (u - 1.0)
        return min(float(sig.min()), s_eq), max(float(sig.max()), s_eq)

    def common(lo: float, hi: float) -> tuple[np.ndarray, float] | None:
        for t in np.linspace(0.0, 1.0, 21):
            a = a_of(lo + t * (hi - lo))
            if np.max(np.linalg.eigvals(a).real) >= 0.0:
                continue
            for q in (np.eye(2 * n), np.diag([1, 1, 1e-2, 1e-2]), np.diag([1e-2, 1e-2, 1, 1])):
                p = scipy.linalg.solve_continuous_lyapunov(a.T, -q)
                if all(np.max(np.linalg.eigvalsh(e.T @ p + p @ e)) < 0 for e in (a_of(lo), a_of(hi))):
                    return p, float(np.linalg.inv(p)[n, n])
        return None

    energy = np.block([[stiffness / 2, np.zeros((n, n))], [np.zeros((n, n)), mass / 2]])
    functions = []
    functions.append(("energy", energy, float(np.linalg.inv(energy)[n, n]), 0.11))
    for r in (0.05, 0.1, 0.15, 0.2, 0.25):
        lo, hi = secant_range(r)
        found = common(lo, hi)
        print(f"|u - 1| <= {r:4.2f}: secant slopes [{lo:.4f}, {hi:.4f}]: "
              f"{'a common function holds' if found else 'none of the candidates holds'}")
        if found is not None:
            functions.append((f"common, R = {r}", found[0], found[1], r))
        shaped = None
        if all(np.max(np.linalg.eigvals(a_of(s)).real) < 0.0 for s in (lo, hi)):
            shaped = largest_region((a_of(lo), a_of(hi)), [np.linalg.inv(energy), np.eye(2 * n)], n)
        print(f"{'':17s}the largest region: {'holds' if shaped else 'none found'}")
        if shaped is not None:
            functions.append((f"largest, R = {r}", shaped[0], shaped[1], r))
    states = sample_box(structure, slider, args.states, box, seed=1)
    labels = basin_stability(structure, slider, states).verdict
    steady = states[labels == Verdict.STEADY_SLIDING.code][: args.steady]
    z_eq = np.zeros(2 * n)
    z_eq[:n] = (f_one - slider.gamma * slider.lam) * np.linalg.solve(stiffness, np.eye(n)[0])

    def rhs(_t: float, z: np.ndarray) -> np.ndarray:
        u = 1.0 - z[n]
        force = float(law(u)) if u > 0 else -float(law(-u))
        f = np.zeros(n)
        f[0] = force - slider.gamma * slider.lam
        return np.concatenate([z[n:], minv @ (f - damping @ z[n:] - stiffness @ z[:n])])

    times = np.linspace(0.0, 400.0, 8001)
    certified: dict[str, list[float]] = {name: [] for name, *_ in functions}
    for state in steady:
        sol = solve_ivp(rhs, (0.0, 400.0), state, t_eval=times, rtol=1e-8, atol=1e-10, max_step=0.05)
        dz = sol.y.T - z_eq
        for name, p, kappa, margin in functions:
            bound = np.sqrt(np.maximum(np.einsum("ti,ij,tj->t", dz, p, dz), 0.0) * kappa)
            hit = np.flatnonzero(bound < margin)
            certified[name].append(float(times[hit[0]]) if hit.size else np.inf)
    print(f"{len(steady)} steady states; mean time at which each function certifies:")
    for name, ts in certified.items():
        print(f"  {name:19s} tau {np.mean(ts):7.2f} (median {np.median(ts):.2f})")


if __name__ == "__main__":
    main()
