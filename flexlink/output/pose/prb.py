"""The pseudo-rigid-body comparison (``studies.pose.prb.PrbComparison``) as the JSON document and the
text summary of `flexlink prb`."""

from __future__ import annotations

import math

from flexlink.output.pose.synthesis_text import synthesis_line
from flexlink.studies.pose.prb import PrbComparison


def prb_document(scene, result: PrbComparison) -> dict:
    """The JSON document of `flexlink prb` (without its ``files``): the pose [deg] and joints
    [m], the FE frequencies [Hz], the PRB model's spring, generalized stiffness and mass and
    first frequency, and its error against the first FE frequency [%]."""
    prb = result.prb
    return {
        "command": "prb", "scene": scene.name, "synthesis": scene.synthesis,
        "pose_crank_deg": math.degrees(result.crank_angle),
        "points_m": result.points,
        "fe_Hz": list(result.fe),
        "prb": {"spring_N_m_per_rad": prb.spring, "generalized_stiffness_N_m": prb.stiffness,
                "generalized_mass_kg_m2": prb.mass, "first_Hz": prb.frequency},
        "prb_vs_fe_pct": result.prb_vs_fe_pct,
        "assumptions": [f"{a.field}: {a.note}" for a in scene.assumptions],
    }


def prb_text(document: dict) -> str:
    """The text summary of `flexlink prb` from its ``document`` (``prb_document``)."""
    s, prb, fe = document["synthesis"], document["prb"], document["fe_Hz"]
    out = [document["scene"]]
    if s:
        out.append("  " + synthesis_line(s))
    out.append(f"  pose: crank {document['pose_crank_deg']:.3f} deg (strip straight)")
    out.append("  FE modes [Hz]: " + ", ".join(f"{f:.3f}" for f in fe))
    out.append(f"  PRB: K = {prb['spring_N_m_per_rad']:.4f} N m/rad, k_q = "
               f"{prb['generalized_stiffness_N_m']:.4f} N m, m_q = "
               f"{prb['generalized_mass_kg_m2']:.5g} kg m^2, first frequency "
               f"{prb['first_Hz']:.3f} Hz ({document['prb_vs_fe_pct']:+.1f} % vs FE "
               f"{fe[0]:.3f} Hz)")
    return "\n".join(out)
