"""Rendering of ``studies.kinetostatics.outputs.OutputCurve``: CSV (one row per crank angle),
the JSON document, the text summary and the plot of output torques and ratios over the turn
(PNG bytes; the caller writes them). Samples next to a dead point are marked in the CSV and
greyed in the plot; the summaries never quote one as a result."""

from __future__ import annotations

import io
import math

import numpy as np

from flexlink.studies.kinetostatics.outputs import angle_index, crank_deg
from flexlink.units import rev_per_min

QUOTED_DEG = (0.0, 90.0, 180.0, 240.0)  # crank angles the text quotes row by row


def _number(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


def outputs_csv(curve) -> str:
    """Crank angle [deg], input torque [N m], per output K [-], torque [N m] and the torque its
    input link puts on it [N m], the ratios [-], friction torque [N m], loss power [W], kinetic
    energy [J], then Fx, Fy, |F| [N] of every reported force, and near_dead_point (1: the
    sample is next to a dead point and unbounded there). Empty cells where undefined."""
    cols = ["crank_angle_deg", "input_torque_N_m"]
    for o in curve.outputs:
        cols += [f"K_{o}", f"T_{o}_N_m", f"R_{o}_N_m"]
    cols += [f"ratio {name}" for name in curve.ratios]
    cols += ["friction_torque_N_m", "loss_power_W", "kinetic_energy_J"]
    for key in curve.forces:
        cols += [f"{key}_Fx_N", f"{key}_Fy_N", f"{key}_F_N"]
    cols.append("near_dead_point")
    lines = [",".join(cols)]
    for i, q in enumerate(curve.q):
        row = [math.degrees(q), curve.input_torque[i]]
        for k in range(len(curve.outputs)):
            row += [curve.K[i, k], curve.torques[i, k], curve.received[i, k]]
        row += [r[i] for r in curve.ratios.values()]
        row += [curve.friction_torque[i], curve.loss_power[i], curve.kinetic_energy[i]]
        for f in curve.forces.values():
            row += [f[i, 0], f[i, 1], math.hypot(*f[i])]
        cells = [f"{v:.12g}" if math.isfinite(v) else "" for v in row]
        lines.append(",".join(cells + [str(int(curve.near[i]))]))
    return "\n".join(lines) + "\n"


def _peak(p) -> dict:
    out = {"name": p.name, "unit": p.unit, "peak": p.value, "at_deg": p.at_deg,
           "rises_towards_dead_point": p.at_band_edge}
    if p.near_value is not None:
        out["next_to_dead_point"] = {
            "sampled": p.near_value, "at_deg": p.near_at_deg, "dead_point_deg": p.dead_point_deg,
            "note": "unbounded at the dead point: this sample only shows how near the grid fell"}
    return out


def _row(curve, deg: float) -> dict:
    """The values at the sample nearest ``deg``; next to a dead point, which one and how far
    (a sample there is a value at that angle, steep in the angle, not a peak)."""
    i = angle_index(curve, deg)
    at = float(crank_deg(curve.q)[i])
    row = {"crank_deg": at, "near_dead_point": bool(curve.near[i]),
           "input_torque_N_m": float(curve.input_torque[i])}
    if curve.near[i] and curve.dead_points:
        dead = min(curve.dead_point_angles(), key=lambda d: abs((d - at + 180) % 360 - 180))
        row["dead_point_deg"] = dead
    row["torques_N_m"] = {o: _number(curve.torques[i, k]) for k, o in enumerate(curve.outputs)}
    row["ratios"] = {name: _number(r[i]) for name, r in curve.ratios.items()}
    return row


def outputs_document(curve, assumptions, files) -> dict:
    """The JSON document: inputs, dead points, the rows at ``QUOTED_DEG``, every curve's peak,
    the losses over the turn, mass properties, the model and the scene's assumptions."""
    t = curve.transmission
    lost = curve.loss_power[np.isfinite(curve.loss_power)]
    return {
        "command": "outputs", "scene": curve.scene, "crank_speed_rad_s": curve.speed,
        "crank_speed_rev_per_min": rev_per_min(curve.speed),
        "crank_acceleration_rad_s2": curve.crank_acceleration, "poses": len(curve.q),
        "input_torque_N_m": {"min": float(curve.input_torque.min()),
                             "max": float(curve.input_torque.max())},
        "outputs": [{"body": o.body, "pivot": o.pivot, "driven_by": o.feeder, "at_joint": o.feed}
                    for o in t.outputs],
        "sharing": t.sharing.value, "shares": list(t.shares),
        "friction_m": curve.losses.friction, "efficiency_eta": curve.losses.efficiency,
        "dead_points": [{"crank_deg": a, "outputs": list(bodies)}
                        for a, bodies in sorted(curve.dead_point_angles().items())],
        "samples_next_to_dead_points": int(curve.near.sum()),
        "at_crank_angles": [_row(curve, d) for d in QUOTED_DEG],
        "peaks": [_peak(p) for p in curve.peaks()],
        "mean_loss_power_W": float(lost.mean()) if lost.size else None,
        "bodies": [{"body": m.body, "mass_kg": m.mass, "inertia_kg_m2": m.inertia}
                   for m in curve.masses],
        "model": list(curve.model), "assumptions": list(assumptions), "files": files}


def _fmt(value) -> str:
    return "   --   " if value is None else f"{value:10.4g}"


def outputs_text(doc: dict) -> str:
    outs = [o["body"] for o in doc["outputs"]]
    tin = doc["input_torque_N_m"]
    torque = (f"{tin['min']:.6g} N m" if tin["min"] == tin["max"]
              else f"{tin['min']:.6g} to {tin['max']:.6g} N m")
    lines = [(f"{doc['scene']}: output torques for an input torque of {torque}, at "
              f"{doc['crank_speed_rev_per_min']:.6g} rev/min, m = {doc['friction_m']:g}, "
              f"eta = {doc['efficiency_eta']:g}, {doc['sharing']} sharing, {doc['poses']} poses"),
             "  outputs: " + "; ".join(f"{o['body']} (about {o['pivot']}, driven by "
                                       f"{o['driven_by']} at {o['at_joint']})"
                                       for o in doc["outputs"])]
    if doc["dead_points"]:
        lines.append("  dead points (an output stops; its torque and the pin forces grow without "
                     "bound): " + "; ".join(f"crank {d['crank_deg']:.3f} deg "
                                            f"({', '.join(d['outputs'])})"
                                            for d in doc["dead_points"]))
    head = "  crank [deg] " + "".join(f"{'T[' + o + ']':>12}" for o in outs)
    rows = [r for r in doc["at_crank_angles"]]
    names = list(next((r["ratios"] for r in rows if "ratios" in r), {}))
    lines.append(head + "".join(f"{n:>22}" for n in names))
    for r in rows:
        note = (f"  ({abs((r['dead_point_deg'] - r['crank_deg'] + 180) % 360 - 180):.2f} deg "
                f"from the dead point at {r['dead_point_deg']:.3f} deg: steep here, unbounded "
                "there)") if r["near_dead_point"] and "dead_point_deg" in r else ""
        lines.append(f"  {r['crank_deg']:9.1f}   " + "".join(
            f"  {_fmt(r['torques_N_m'][o])}" for o in outs) + "".join(
            f"  {_fmt(r['ratios'][n]):>20}" for n in names) + note)
    lines.append("  peaks away from the dead points:")
    for p in doc["peaks"]:
        text = f"    {p['name']:<24} {p['peak']:.6g} {p['unit']} at {p['at_deg']:.1f} deg"
        if p["rises_towards_dead_point"]:
            text += " (beside the dead-point band: still rising towards the dead point)"
        near = p.get("next_to_dead_point")
        if near:
            text += (f"; sampled {near['sampled']:.4g} at {near['at_deg']:.1f} deg is next to "
                     f"the dead point at {near['dead_point_deg']:.3f} deg (unbounded there)")
        lines.append(text)
    if doc["mean_loss_power_W"]:
        lines.append(f"  friction and bearing losses: mean {doc['mean_loss_power_W']:.6g} W")
    lines += ["  model: " + m for m in doc["model"]]
    return "\n".join(lines)


def outputs_plot(curve, size=(8.0, 7.0), dpi: int = 120) -> bytes:
    """PNG: output torques (top) and ratios (bottom) over the crank angle; samples next to a
    dead point left out, the dead points marked."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    deg = np.degrees(curve.q)
    fig = Figure(figsize=size, dpi=dpi, layout="constrained")
    FigureCanvasAgg(fig)
    top, bottom = fig.subplots(2, 1, sharex=True)
    keep = np.where(curve.near, np.nan, 1.0)
    top.plot(deg, curve.input_torque, color="grey", ls="--", lw=1, label="input T_in")
    for k, o in enumerate(curve.outputs):
        top.plot(deg, curve.torques[:, k] * keep, label=f"T[{o}]")
    for name, r in curve.ratios.items():
        bottom.plot(deg, r * keep, label=name)
    for ax in (top, bottom):
        for d in curve.dead_points:
            ax.axvline(d.crank_deg, color="red", lw=0.8, alpha=0.6)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    top.set_ylabel("torque [N m]")
    bottom.set_ylabel("transmission ratio [-]")
    bottom.set_xlabel("crank angle [deg] (red: dead points; gaps: unbounded next to them)")
    top.set_title(f"{curve.scene}: {rev_per_min(curve.speed):.4g} rev/min, m = {curve.losses.friction:g},"
                  f" eta = {curve.losses.efficiency:g}")
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png")
    return buffer.getvalue()


def outputs_report_data(curve, unavailable: str | None = None) -> dict | None:
    """What the HTML report shows of the output torques: the curves over the crank angle in
    order (None next to a dead point), the dead points, the rows at ``QUOTED_DEG`` and the
    peaks; None for a scene without an input torque, {"unavailable": reason} if it failed."""
    if curve is None:
        return {"unavailable": unavailable} if unavailable else None
    doc = outputs_document(curve, [], [])
    deg = crank_deg(curve.q)
    order = np.argsort(deg)

    def cut(values):
        return [None if curve.near[i] or not math.isfinite(values[i]) else float(values[i])
                for i in order]

    return {"crank_deg": [round(float(d), 6) for d in deg[order]],
            "input_torque_N_m": doc["input_torque_N_m"],
            "torques_N_m": {o: cut(curve.torques[:, k]) for k, o in enumerate(curve.outputs)},
            "ratios": {name: cut(r) for name, r in curve.ratios.items()},
            "rev_per_min": doc["crank_speed_rev_per_min"], "sharing": doc["sharing"],
            "friction_m": doc["friction_m"], "efficiency_eta": doc["efficiency_eta"],
            "dead_points": doc["dead_points"], "rows": doc["at_crank_angles"],
            "peaks": doc["peaks"]}
