"""Rendering of ``studies.life.compliant_cycle.CompliantCycle`` (with its ``StripLife``
verdicts): the JSON document, the text summary, the CSV of the strip's
stress and the driving torque over the turn, and the plot of both, FE against PRB (PNG bytes;
the caller writes them)."""

from __future__ import annotations

import io
import math

import numpy as np

MODEL = (
    "quasi-static: no inertia; the crank's rotation prescribed at its ground pivot",
    "every link a chain of co-rotational Euler-Bernoulli frame elements (large rotation, "
    "small strain); joints as the scene declares them",
    "the strip straight and unstressed at the scene's start pose",
    "stress: sigma = N/A -+ M c/I at the extreme fibres; no stress concentration at the clamp",
    "PRB: Howell's fixed-pinned segment (K = gamma K_Theta E I / l) on the rigid four-bar; its "
    "clamp stress from the statics of its rigid links",
)
LIFE_NOTE = ("life: the fatigue chain of 'flexlink life' (rainflow over the turn, mean-stress "
             "correction, the part's S-N line from the strip's material file with Marin "
             "factors) on the FE stress at every node and the PRB stress at the clamp")


def _at(angle) -> float:
    return float(math.degrees(angle) % 360.0)


def _life(verdict, required: float) -> dict:
    f = verdict.fatigue
    return {"model": verdict.model, "material": verdict.material,
            "at_arc_length_m": verdict.arc_length, "fibre": verdict.fibre,
            "life_turns": None if math.isinf(f.life) else f.life,
            "infinite_life": math.isinf(f.life),
            "meets_required": bool(f.life >= required), "safety_factor": f.safety,
            "endurance_limit_Pa": verdict.endurance, "amplitude_Pa": f.amplitude,
            "mean_Pa": f.mean, "equivalent_Pa": f.equivalent, "yield_safety": f.yield_safety,
            "cycles_per_turn": f.cycles}


def _variant_notes(scene) -> list[str]:
    """What the analysis does not take from the scene's model choices."""
    from flexlink.fe.beams import BeamTheory

    notes = ["in-plane: the scene's out-of-plane model family, if any, is not part of it"]
    shear = [link.name for link in scene.links
             if link.section.beam is not BeamTheory.EULER_BERNOULLI]
    if shear:
        notes.append(f"links {', '.join(shear)} taken as Euler-Bernoulli beams (the "
                     "co-rotational element neglects shear deformation)")
    return notes


def compliant_document(scene, cycle, lives, required: float, conditions) -> dict:
    """The JSON document (without its ``files``). ``lives``: ``StripLife``s (FE and PRB;
    empty: no life asked for) under ``conditions`` (``studies.life.life.Conditions``);
    ``required`` [turns]."""
    fe_peak, k, j = cycle.stress.peak
    prb = cycle.prb
    prb_stress = np.abs(prb.clamp_stress).max(axis=1)
    kp = int(np.argmax(prb_stress))
    kt, kpt = int(np.argmax(np.abs(cycle.reaction))), int(np.argmax(np.abs(prb.drive_torque)))
    gap = np.hypot(*(cycle.joints["C"] - prb.points["C"]).T) if "C" in prb.points else None
    return {
        "command": "compliant", "scene": scene.name, "crank_angles": len(cycle.crank_angles),
        "strip": cycle.strip,
        "fe": {"peak_stress_Pa": fe_peak, "at_deg": _at(cycle.crank_angles[k]),
               "at_arc_length_m": float(cycle.stress.arc_length[j]),
               "peak_torque_N_m": abs(float(cycle.reaction[kt])),
               "peak_torque_at_deg": _at(cycle.crank_angles[kt]),
               "torque_virtual_work_gap_N_m": float(np.abs(cycle.reaction
                                                            - cycle.energy_torque).max()),
               "peak_energy_J": float(cycle.energy.max()),
               "newton_iterations": {"total": int(cycle.iterations.sum()),
                                     "max": int(cycle.iterations.max())},
               "closure_m": cycle.closure},
        "prb": {"spring_N_m_per_rad": prb.spring,
                "Theta_range_deg": [float(np.degrees(prb.Theta.min())),
                                    float(np.degrees(prb.Theta.max()))],
                "peak_spring_torque_N_m": float(np.abs(prb.spring_torque).max()),
                "peak_stress_Pa": float(prb_stress[kp]), "at_deg": _at(cycle.crank_angles[kp]),
                "peak_torque_N_m": abs(float(prb.drive_torque[kpt])),
                "peak_torque_at_deg": _at(cycle.crank_angles[kpt])},
        "prb_vs_fe": {
            "peak_stress_pct": 100 * (float(prb_stress[kp]) / fe_peak - 1),
            "peak_torque_pct": 100 * (abs(float(prb.drive_torque[kpt]))
                                      / abs(float(cycle.reaction[kt])) - 1),
            "largest_clamp_stress_gap_Pa": float(np.abs(
                prb.clamp_stress - cycle.stress.fibre_stress[:, 0]).max()),
            "largest_clamp_stress_gap_at_deg": _at(cycle.crank_angles[int(np.argmax(np.abs(
                prb.clamp_stress - cycle.stress.fibre_stress[:, 0]).max(axis=1)))]),
            "largest_clamp_point_gap_m": None if gap is None else float(gap.max()),
            "largest_clamp_point_gap_at_deg": None if gap is None
            else _at(cycle.crank_angles[int(np.argmax(gap))])},
        "life": {"required_turns": required, "reliability": conditions.reliability,
                 "surface": str(conditions.surface), "mean_stress": str(conditions.mean_stress),
                 "verdicts": [_life(v, required) for v in lives]},
        "model": list(MODEL) + [LIFE_NOTE] + _variant_notes(scene),
        "assumptions": [f"{a.field}: {a.note}" for a in scene.assumptions],
    }


def compliant_text(doc: dict) -> str:
    fe, prb, gap = doc["fe"], doc["prb"], doc["prb_vs_fe"]
    out = [f"{doc['scene']}: strip '{doc['strip']}' over {doc['crank_angles']} crank angles "
           "(nonlinear FE beside the PRB model)",
           f"  FE   peak stress {fe['peak_stress_Pa'] / 1e6:.1f} MPa at {fe['at_deg']:.0f} deg, "
           f"{fe['at_arc_length_m'] * 1e3:.1f} mm from the clamp; peak torque "
           f"{fe['peak_torque_N_m']:.4g} N m at {fe['peak_torque_at_deg']:.0f} deg "
           f"(reaction vs dU/dtheta2: {fe['torque_virtual_work_gap_N_m']:.2g} N m)",
           f"  PRB  peak stress {prb['peak_stress_Pa'] / 1e6:.1f} MPa at {prb['at_deg']:.0f} deg; "
           f"peak torque {prb['peak_torque_N_m']:.4g} N m at {prb['peak_torque_at_deg']:.0f} "
           f"deg; Theta {prb['Theta_range_deg'][0]:.1f} to {prb['Theta_range_deg'][1]:.1f} deg",
           f"  PRB vs FE: peak stress {gap['peak_stress_pct']:+.1f} %, peak torque "
           f"{gap['peak_torque_pct']:+.1f} %; clamp stress apart by up to "
           f"{gap['largest_clamp_stress_gap_Pa'] / 1e6:.1f} MPa at "
           f"{gap['largest_clamp_stress_gap_at_deg']:.0f} deg"]
    if gap["largest_clamp_point_gap_m"] is not None:
        out[-1] += (f"; clamp point apart by up to {gap['largest_clamp_point_gap_m'] * 1e3:.2f} "
                    f"mm at {gap['largest_clamp_point_gap_at_deg']:.0f} deg")
    life = doc["life"]
    if life["verdicts"]:
        out.append(f"  life against {life['required_turns']:.3g} wipe cycles (reliability "
                   f"{life['reliability']:g}, {life['surface']} surface, {life['mean_stress']}):")
    for v in life["verdicts"]:
        turns = "infinite" if v["infinite_life"] else f"{v['life_turns']:.3g} turns"
        out.append(f"    {v['model']:<4} {v['material']}: equivalent amplitude "
                   f"{v['equivalent_Pa'] / 1e6:.1f} MPa against Se {v['endurance_limit_Pa'] / 1e6:.1f}"
                   f" MPa, safety {v['safety_factor']:.3f}, life {turns} "
                   f"({'MET' if v['meets_required'] else 'NOT MET'}); yield safety "
                   f"{v['yield_safety']:.2f}")
    return "\n".join(out)


def compliant_csv(cycle) -> str:
    """Per crank angle [deg]: FE and PRB clamp stress at both fibres [Pa], the strip's largest
    |sigma| [Pa], FE torque (reaction, dU/dtheta2) and PRB torque [N m], PRB Theta [deg]."""
    cols = ["crank_angle_deg", "fe_clamp_stress_plus_Pa", "fe_clamp_stress_minus_Pa",
            "prb_clamp_stress_plus_Pa", "prb_clamp_stress_minus_Pa", "fe_strip_peak_Pa",
            "fe_torque_N_m", "fe_energy_torque_N_m", "prb_torque_N_m", "prb_Theta_deg"]
    s = cycle.stress.fibre_stress
    rows = np.column_stack([np.degrees(cycle.crank_angles), s[:, 0, 0], s[:, 0, 1],
                            cycle.prb.clamp_stress, np.abs(s).max(axis=(1, 2)),
                            cycle.reaction, cycle.energy_torque, cycle.prb.drive_torque,
                            np.degrees(cycle.prb.Theta)])
    return "\n".join([",".join(cols)] + [",".join(f"{v:.10g}" for v in row)
                                         for row in rows]) + "\n"


def compliant_plot(cycle, title: str, size=(8.0, 6.5), dpi: int = 120) -> bytes:
    """PNG: the clamp's extreme-fibre stress over the crank angle (FE and PRB), then the
    driving torque (FE reaction, FE dU/dtheta2, PRB)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    deg = np.degrees(cycle.crank_angles - cycle.crank_angles[0])
    start = math.degrees(cycle.crank_angles[0])
    fig = Figure(figsize=size, dpi=dpi, layout="constrained")
    FigureCanvasAgg(fig)
    top, bottom = fig.subplots(2, 1, sharex=True)
    s = cycle.stress.fibre_stress[:, 0] / 1e6
    top.plot(deg, s[:, 0], color="#1f77b4", label="FE, fibre +c")
    top.plot(deg, s[:, 1], color="#1f77b4", ls=":", label="FE, fibre -c")
    top.plot(deg, cycle.prb.clamp_stress[:, 0] / 1e6, color="#d62728", label="PRB, fibre +c")
    top.plot(deg, cycle.prb.clamp_stress[:, 1] / 1e6, color="#d62728", ls=":",
             label="PRB, fibre -c")
    top.set_ylabel("strip stress at the clamp [MPa]")
    top.set_title(title)
    top.legend(fontsize=8, ncol=2)
    bottom.plot(deg, cycle.reaction, color="#1f77b4", label="FE: crank reaction")
    bottom.plot(deg, cycle.energy_torque, color="#2ca02c", ls="--", label="FE: dU/dtheta2")
    bottom.plot(deg, cycle.prb.drive_torque, color="#d62728", label="PRB: K Theta dTheta/dtheta2")
    bottom.set_ylabel("driving torque [N m]")
    bottom.set_xlabel(f"crank angle from the unstressed pose ({start:.0f} deg) [deg]")
    bottom.legend(fontsize=8)
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png")
    return buffer.getvalue()
