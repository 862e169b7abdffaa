"""Rendering of ``studies.running.torque.TorqueCurve``: CSV (one row per crank angle), the JSON
document, the text summary and the torque plot (``write_torque`` writes the CSV and the PNG)."""

from __future__ import annotations

import io
import math

import numpy as np

from flexlink.units import degrees_in_turn, rev_per_min


def torque_csv(curve) -> str:
    """Crank angle [deg], torque [N m], power [W], kinetic energy [J], load power [W], then
    Fx, Fy, |F| [N] of every reported joint force ("joint:body": on that body at that joint)."""
    cols = ["crank_angle_deg", "torque_N_m", "power_W", "kinetic_energy_J", "load_power_W"]
    for key in curve.forces:
        cols += [f"{key}_Fx_N", f"{key}_Fy_N", f"{key}_F_N"]
    lines = [",".join(cols)]
    for i, q in enumerate(curve.q):
        row = [math.degrees(q), curve.torque[i], curve.power[i], curve.kinetic_energy[i],
               curve.load_power[i]]
        for f in curve.forces.values():
            row += [f[i, 0], f[i, 1], math.hypot(*f[i])]
        lines.append(",".join("" if math.isnan(v) else f"{v:.10g}" for v in row))
    return "\n".join(lines) + "\n"


def torque_document(curve, assumptions) -> dict:
    """The JSON document: operating point, summary, per-joint peak forces, mass properties,
    the model's assumptions and the scene's."""
    peaks = {}
    for key, f in curve.forces.items():
        magnitude = np.where(curve.singular, -1.0, np.hypot(f[:, 0], f[:, 1]))
        i = int(np.argmax(magnitude))
        peaks[key] = {"peak_N": float(magnitude[i]),
                      "at_deg": degrees_in_turn(curve.q[i])}
    return {"command": "torque", "scene": curve.scene, "crank_speed_rad_s": curve.speed,
            "crank_speed_rev_per_min": rev_per_min(curve.speed),
            "crank_acceleration_rad_s2": curve.crank_acceleration, "poses": len(curve.q),
            **curve.summary(), "joint_forces": peaks,
            "singular_poses_deg": [degrees_in_turn(q) for q in curve.q[curve.singular]],
            "turn_closes": curve.turn_closes,
            "at_pose": at_pose_json(curve),
            "loads": [load_json(load) for load in curve.loads],
            "bodies": [{"body": m.body, "mass_kg": m.mass, "centroid_m": list(m.centroid),
                        "inertia_kg_m2": m.inertia} for m in curve.masses],
            "model": list(curve.model), "assumptions": list(assumptions)}


def at_pose_json(curve) -> dict | None:
    """The torque at the scene's own pose (None where the pose is singular)."""
    at = curve.at_pose
    if at is None:
        return None
    return {"crank_angle_deg": float(math.degrees(at.q) % 360.0), "torque_N_m": at.torque,
            "power_W": at.torque * curve.speed, "kinetic_energy_J": at.kinetic_energy}


def load_json(load) -> dict:
    """A [[loads]] table as it was applied: SI values, a CSV load by its sampled range."""
    unit = "N*m" if load.kind == "torque" else "N"
    doc = {"field": load.field, "kind": str(load.kind), "link": load.body, "unit": unit}
    if load.angles is None:
        doc["value"] = [float(v) for v in load.values[0]] if load.kind != "torque" \
            else float(load.values[0][0])
    else:
        doc["samples"] = len(load.angles)
        doc["range"] = [float(load.values.min()), float(load.values.max())]
    if load.kind != "torque":
        doc["at_m"] = [float(v) for v in load.at]
        doc["frame"] = str(load.frame)
    return doc


def _load_line(load: dict) -> str:
    if "value" in load:
        v = load["value"]
        value = (f"({v[0]:g}, {v[1]:g}) {load['unit']}" if isinstance(v, list)
                 else f"{v:g} {load['unit']}")
    else:
        value = (f"from {load['samples']} CSV samples, {load['range'][0]:g} to "
                 f"{load['range'][1]:g} {load['unit']}")
    where = (f" at ({1e3 * load['at_m'][0]:g}, {1e3 * load['at_m'][1]:g}) mm"
             f"{', body frame' if load.get('frame') == 'body' else ''}" if "at_m" in load else "")
    return f"  load {load['field']}: {load['kind']} {value} on {load['link']}{where}"


def torque_text(doc: dict) -> str:
    lines = [(f"{doc['scene']}: driving torque at {doc['crank_speed_rev_per_min']:.6g} rev/min "
              f"({doc['crank_speed_rad_s']:.6g} rad/s), crank acceleration "
              f"{doc['crank_acceleration_rad_s2']:.6g} rad/s^2, {doc['poses']} poses"),
             (f"  torque  peak {doc['peak_torque_N_m']:.6g} N m at "
              f"{doc['peak_torque_at_deg']:.1f} deg; max {doc['max_torque_N_m']:.6g}, min "
              f"{doc['min_torque_N_m']:.6g}, mean {doc['mean_torque_N_m']:.6g}, rms "
              f"{doc['rms_torque_N_m']:.6g} N m"),
             (f"  power   mean {doc['mean_power_W']:.6g} W, peak {doc['peak_power_W']:.6g} W at "
              f"{doc['peak_power_at_deg']:.1f} deg"),
             "  joint forces (peak |F| on the body at the joint):"]
    lines += [f"    {k:<16} {v['peak_N']:.6g} N at {v['at_deg']:.1f} deg"
              for k, v in doc["joint_forces"].items()]
    at = doc["at_pose"]
    if at is not None:
        lines.append(f"  at the scene's pose (crank {at['crank_angle_deg']:.4f} deg): torque "
                     f"{at['torque_N_m']:.6g} N m, power {at['power_W']:.6g} W")
    lines += [_load_line(load) for load in doc["loads"]]
    lines += ["  model: " + m for m in doc["model"]]
    if doc["singular_poses_deg"]:
        where = ", ".join(f"{a:g}" for a in doc["singular_poses_deg"])
        lines.append(f"warning: singular pose at crank {where} deg (a dead centre or flat pose: "
                     "the motion and the pin forces are not determined there); left out of "
                     "the peaks and means, blank in torque.csv; choose --poses so that no pose "
                     "lands on it")
    if not doc["turn_closes"]:
        lines.append("warning: after one turn the linkage is on another assembly (it changed "
                     "branch at a singular pose): the curves do not join at the turn's start, "
                     "and the means and the mean power are over this turn, not a repeating "
                     "cycle")
    return "\n".join(lines)


def torque_plot(curve, size=(8.0, 6.0), dpi: int = 120) -> bytes:
    """PNG: driving torque over the crank angle (top) and the joint forces' magnitudes."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    deg = np.degrees(curve.q)
    fig = Figure(figsize=size, dpi=dpi, layout="constrained")
    FigureCanvasAgg(fig)
    top, bottom = fig.subplots(2, 1, sharex=True)
    mean = float(np.nanmean(curve.torque))  # singular poses are NaN: gaps in the curves
    top.plot(deg, curve.torque, color="#1f77b4")
    top.axhline(mean, color="grey", ls="--", lw=1, label=f"mean {mean:.4g} N m")
    top.set_ylabel("driving torque [N m]")
    top.set_title(f"{curve.scene}: {rev_per_min(curve.speed):.4g} rev/min ({curve.speed:.4g} rad/s)"
                  + (f", {curve.crank_acceleration:.4g} rad/s^2" if curve.crank_acceleration
                     else ""))
    top.legend(fontsize=9)
    for key, f in curve.forces.items():
        bottom.plot(deg, np.hypot(f[:, 0], f[:, 1]), label=key)
    bottom.set_ylabel("joint force |F| [N]")
    bottom.set_xlabel("crank angle [deg]")
    if curve.forces:
        bottom.legend(fontsize=8, ncol=2)
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png")
    return buffer.getvalue()


def write_torque(curve, folder) -> list:
    """torque.csv and torque.png in ``folder`` (atomically); returns their paths."""
    from flexlink.fileio import write_atomic

    paths = [folder / "torque.csv", folder / "torque.png"]
    write_atomic(paths[0], torque_csv(curve))
    write_atomic(paths[1], torque_plot(curve))
    return paths
