"""The crank-rocker synthesis (``studies.pose.crank_rocker.CrankRocker``) as the JSON document and
the text summary of `flexlink synth`."""

from __future__ import annotations

import math

from flexlink.studies.pose.crank_rocker import CrankRocker


def crank_rocker_document(result: CrankRocker) -> dict:
    """The JSON document of `flexlink synth`: method, targets as given, link lengths [m], ratios
    to the ground link, transmission angle limits [deg] and rocker swing [deg]."""
    return {"command": "synth", "method": result.method, "inputs": result.inputs,
            "lengths_m": dict(zip(("ground", "crank", "coupler", "rocker"),
                                  result.lengths.tolist())),
            "ratios": dict(zip(("R2", "R3", "R4"), result.ratios.tolist())),
            "mu_min_deg": math.degrees(result.transmission[0]),
            "mu_max_deg": math.degrees(result.transmission[1]),
            "rocker_swing_deg": math.degrees(result.swing)}


def crank_rocker_text(document: dict) -> str:
    """The text summary of `flexlink synth` from its ``document`` (``crank_rocker_document``)."""
    return "\n".join([
        f"{document['method']} {document['inputs']}",
        "  lengths: " + ", ".join(f"{k} {v:.6g} m" for k, v in document["lengths_m"].items()),
        "  R2 = {R2:.4f}, R3 = {R3:.4f}, R4 = {R4:.4f}".format(**document["ratios"]),
        f"  transmission angle {document['mu_min_deg']:.3f} .. {document['mu_max_deg']:.3f} deg, "
        f"rocker swing {document['rocker_swing_deg']:.3f} deg"])
