"""Reproduction steps for the design side: Fig. 16 worked example, stick-slip-optimal foundation."""

from __future__ import annotations

import json
import math
from pathlib import Path

from stickslip.analysis.design import design_foundation
from stickslip.analysis.stick_slip_tuning import optimal_foundation_stick_slip
from stickslip.model.physical import PhysicalSystem
from stickslip.reproduction.claims import Claim
from stickslip.reproduction.outputs import save_figure
from stickslip.reproduction.report import FigureRecord

#: The worked example: a 2 kg slider on 50 kN/m, 20 N s/m, mu_s 0.5, mu_k 0.3, 150 N, 5 cm/s.
EXAMPLE = PhysicalSystem(mass=2.0, stiffness=50e3, damping=20.0, mu_s=0.5, mu_k=0.3, load=150.0, speed=0.05)


def design_example(out_dir: Path) -> tuple[list[FigureRecord], list[Claim]]:
    """Fig. 16: the design procedure applied to :data:`EXAMPLE`, as a figure and JSON."""
    design = design_foundation(EXAMPLE)
    report = design.to_dict()
    data = out_dir / "data" / "fig16-design.json"
    data.parent.mkdir(parents=True, exist_ok=True)
    data.write_text(json.dumps(report, indent=2), encoding="utf-8")
    drawn = design.plot(title="Fig. 16: design procedure, worked example")
    record = save_figure(drawn, out_dir, "fig16", "Fig. 16: design procedure (worked example)", [data])
    rigid_sim = report["verdict"]["rigid"]["simulation"]
    found_sim = report["verdict"]["foundation"]["simulation"]
    claim = Claim(
        "fig16", "Fig. 16, Section 4",
        "Following the procedure, the optimally tuned foundation suppresses stick-slip where "
        "Eq. (38) holds.",
        f"example lambda = {report['lambda']:.3g}: rigid base {rigid_sim}, tuned foundation "
        f"{found_sim}; Eq. (38) says {report['verdict']['foundation']['theory']}",
        "confirmed" if (found_sim == report["verdict"]["foundation"]["theory"] == "steady-sliding"
                        and rigid_sim == "stick-slip") else "differs",
        {"design": report},
    )
    return [record], [claim]


def stick_slip_optimum_claim(zetas: tuple[float, ...] = (0.01, 0.1), lam_max: float = 100.0) -> Claim:
    """Section 4 (Fig. 11a): a detuned, softer foundation beats the absorber optimum."""
    rows = []
    data = {}
    for zeta in zetas:
        r = optimal_foundation_stick_slip(zeta, lam_max=lam_max)
        data[f"{zeta:g}"] = r.to_dict()
        best = (f"no stick-slip onset up to lambda = {lam_max:g} (lambda_c > {lam_max:g})"
                if math.isinf(r.lambda_crit) else f"lambda_c = {r.lambda_crit:.3g}")
        rows.append(
            f"zeta={zeta:g}: absorber optimum lambda_c = {r.reference_lambda_crit:.3g}; best "
            f"foundation (M={r.foundation.mass_ratio:.3g}, K={r.foundation.stiffness_ratio:.3g} = "
            f"{r.foundation.stiffness_ratio / r.reference.stiffness_ratio:.2f} K_opt, "
            f"zeta_a={r.foundation.damping_ratio:.3g}): {best}"
        )
    better = all(
        (d["lambda_crit"] is None) or d["lambda_crit"] > d["absorber_optimum"]["lambda_crit"]
        for d in data.values()
    )
    softer = all(d["K"] < d["absorber_optimum"]["K"] for d in data.values())
    return Claim(
        "beyond-absorber", "Section 4 (Figs. 11a, 12-15)",
        "Setting the phases of the two masses well (K = K_opt/2) suppresses stick-slip beyond "
        "the absorber optimum.",
        "; ".join(rows),
        "confirmed" if better and softer else "differs",
        data,
    )


def disturbed_starts_claim(optimum: Claim, lams: tuple[float, ...] = (10.0, 30.0, 100.0),
                           seeds: int = 8) -> Claim:
    """Issue 13, point 5: does "no stick-slip up to lambda = 100" hold for disturbed starts too?

    The stick-slip-optimal foundation of :func:`stick_slip_optimum_claim` was judged from the
    start-up state. Here, at each ``lambda`` of ``lams``, stick-slip cycles are searched
    whatever the start (:func:`stickslip.analysis.cycles.find_cycles`, the breakaway return
    map seeded from ``seeds`` random starts): none found means the search, from its seeds and
    up to its period, met no cycle a disturbance could lead to (a search, not a proof); one
    found means a knock can.
    """
    from stickslip.analysis.cycles import find_cycles
    from stickslip.model.parameters import Foundation, Slider
    from stickslip.model.structure import elastic_foundation

    rows, data, holds = [], {}, True
    for zeta_text, d in optimum.data.items():
        zeta = float(zeta_text)
        structure = elastic_foundation(zeta, Foundation(d["M"], d["K"], d["zeta_a"]))
        found = {}
        for lam in lams:
            cycles = find_cycles(structure, Slider(lam, gamma=d["gamma"]), seeds=seeds, max_period=2)
            found[f"{lam:g}"] = [c.to_dict() for c in cycles.cycles]
        ref = d["absorber_optimum"]
        reference = elastic_foundation(zeta, Foundation(ref["M"], ref["K"], ref["zeta_a"]))
        ref_found = [f"{lam:g}" for lam in lams
                     if find_cycles(reference, Slider(lam, gamma=d["gamma"]), seeds=seeds).cycles]
        data[zeta_text] = {"stick_slip_optimum": found, "absorber_optimum_lambdas_with_cycles": ref_found}
        with_cycles = [lam for lam, cs in found.items() if cs]
        holds = holds and not with_cycles
        rows.append(f"zeta={zeta_text}: stick-slip cycles of the stick-slip-optimal foundation at "
                    f"lambda = {', '.join(with_cycles) or 'none'} (searched at "
                    f"{', '.join(f'{lam:g}' for lam in lams)}); the absorber optimum has one at "
                    f"lambda = {', '.join(ref_found) or 'none'}")
    return Claim(
        "beyond-absorber-disturbed", "Section 4, beyond the paper (issue 13)",
        "The stick-slip-optimal foundation also suppresses stick-slip after disturbances: the "
        "cycle search (Newton's method on the exact return map, seeded from random starts) finds "
        "no stick-slip cycle where the absorber optimum has one (a search, not a proof that none "
        "exists).",
        "; ".join(rows),
        "confirmed" if holds else "differs",
        data,
    )
