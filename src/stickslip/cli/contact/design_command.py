"""``stickslip design --config`` for a machine with its contact (normal DOF, Jenkins element).

The variants assessed (:func:`~stickslip.analysis.contact.design.design_contact`): a machine
with a ``[structure]`` as given; the paper's slider (flat ``m``, ``k``, ``c``) on the rigid base
and on a foundation, the file's ``m_a``, ``k_a``, ``c_a`` or else the one Eqs. 28-30 recommend
for the rigid contact (then assessed with the contact). With a normal DOF, steady sliding's
complex-eigenvalue analysis is given too (``stickslip stability``'s).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import typer

from stickslip.cli.console import BadInput, print_json, show_progress

#: The sentence the report gives for a [structure] file's [absorber].
NO_ABSORBER = ("the [absorber] is not tuned with a contact in this version (its H-infinity and "
               "stick-slip tunings assume a rigid contact); put the tuned absorber into the "
               "[structure] matrices to assess it here")


def contact_variants(config: Path, machine_file: Any
                     ) -> tuple[dict[str, Any], list[str], dict[str, Any] | None]:
    """The contact systems to assess, by name, the report's notes and the foundation (SI)."""
    from dataclasses import replace

    from stickslip.analysis.contact.engine import contact_system
    from stickslip.analysis.theory import optimal_foundation_fit
    from stickslip.cli.contact.simulation import contact_run_system
    from stickslip.cli.machine_config import config_system
    from stickslip.model.machine import machine_from_physical_system
    from stickslip.model.physical import foundation_to_physical

    if machine_file.has_structure:
        system, _ = contact_run_system(config, machine_file)
        notes = [NO_ABSORBER] if machine_file.absorber_table is not None else []
        return {"machine": system}, notes, None
    physical = config_system(config, normal_coupling=True)
    contact = machine_file.contact()

    def with_contact(p: Any) -> Any:
        try:
            return contact_system(machine_from_physical_system(p), contact)
        except ValueError as exc:
            raise BadInput(f"{machine_file.label}: {exc}") from None

    rigid = replace(physical, foundation=None)
    if physical.foundation is not None:
        f = physical.foundation
        return ({"rigid base": with_contact(rigid), "given foundation": with_contact(physical)},
                [], {"source": "given", "m_a": f.m_a, "k_a": f.k_a, "c_a": f.c_a})
    zeta = rigid.damping / (2.0 * (rigid.mass * rigid.stiffness) ** 0.5)
    recommended = foundation_to_physical(optimal_foundation_fit(zeta), rigid.mass, rigid.stiffness)
    note = (f"recommended foundation: m_a={recommended.m_a:.4g} kg, k_a={recommended.k_a:.4g} N/m, "
            f"c_a={recommended.c_a:.4g} N s/m, tuned by Eqs. 28-30 for the rigid contact and "
            "assessed here with the contact")
    foundation = {"source": "recommended: Eqs. 28-30 for the rigid contact",
                  "m_a": recommended.m_a, "k_a": recommended.k_a, "c_a": recommended.c_a}
    return ({"rigid base": with_contact(rigid),
             "recommended foundation": with_contact(replace(physical, foundation=recommended))},
            [note], foundation)


def contact_design_command(config: Path, machine_file: Any, given: list[str], *,
                           json: bool) -> None:
    """Print (or ``--json``) the contact machine's design report."""
    from stickslip.analysis.contact.design import design_contact
    from stickslip.cli.progress import DesignProgress

    if given:
        raise BadInput(f"{machine_file.label}: {', '.join(given)} cannot be given with a "
                       "[contact]: change the machine file")
    systems, notes, foundation = contact_variants(config, machine_file)
    stability = _stability(config, machine_file)
    with DesignProgress(show_progress()) as bar:
        report = design_contact(systems, notes=tuple(notes), progress=bar)
    payload = report.to_dict()
    payload.update({"config": str(config), "machine": machine_file.label,
                    "stability": stability, "foundation": foundation})
    if json:
        print_json(payload)
        return
    lines = [f"machine     {config}: a machine with its contact (start-up runs of the contact "
             "engine; periodic verdicts observed, not proven)"]
    if stability.get("verdict"):
        crit = stability.get("critical_mu")
        lines.append(f"steady      {stability['verdict']} (complex eigenvalues); critical mu "
                     + (f"{crit:.8g}" if crit is not None else "none found"))
    elif stability.get("note"):
        lines.append(f"steady      {stability['note']}")
    typer.echo("\n".join(lines) + "\n" + report.summary())


def _stability(config: Path, machine_file: Any) -> dict[str, Any]:
    """Steady sliding's complex-eigenvalue verdict and critical mu, or why there is none."""
    from stickslip.cli.stability_command import _analyse

    contact = machine_file.contact()
    if contact is None or contact.normal_dof is None:
        return {"note": "no normal DOF: steady sliding has no friction coupling to analyse "
                        "(stickslip stability)"}
    try:
        result = _analyse(config, 2.0)[0]
    except BadInput as exc:
        return {"note": str(exc)}
    p = result.to_dict()
    return {"verdict": p["verdict"], "stable": p["stable"], "critical_mu": p["critical_mu"],
            "critical_mu_undamped": p["critical_mu_undamped"]}
