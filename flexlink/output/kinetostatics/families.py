"""Rendering of ``studies.kinetostatics.families.FamilyTorques``: the JSON document, the text
table and a CSV with one row per member."""

from __future__ import annotations

from flexlink.units import rev_per_min



def families_document(result, files) -> dict:
    return {"command": "torque-family", "scene": result.scene,
            "crank_speed_rad_s": result.speed, "crank_speed_rev_per_min": rev_per_min(result.speed),
            "members": [{"family": m.family, "field": m.field, "value": m.value,
                         **m.summary, "lengths_m": m.lengths,
                         "pivot_inertia_kg_m2": m.pivot_inertia} for m in result.members],
            "files": files}


def families_csv(doc: dict) -> str:
    cols = ["family", "field", "value", "peak_torque_N_m", "peak_torque_at_deg",
            "max_torque_N_m", "min_torque_N_m", "rms_torque_N_m"]
    lines = [",".join(cols)]
    for m in doc["members"]:
        lines.append(",".join(f'"{m[c]}"' if isinstance(m[c], str) else f"{m[c]:.10g}"
                              for c in cols))
    return "\n".join(lines) + "\n"


def families_text(doc: dict) -> str:
    lines = [f"{doc['scene']}: driving torque of every family member at "
             f"{doc['crank_speed_rev_per_min']:.6g} rev/min"]
    family = None
    for m in doc["members"]:
        if m["family"] != family:
            family = m["family"]
            lines += ["", f"{family} ({m['field']}):",
                      "    value   peak [N m]   at [deg]   max [N m]   min [N m]   rms [N m]"
                      "   body lengths [mm]   I about pivot [kg m^2]"]
        lengths = "/".join(f"{1000 * v:.2f}" for v in m["lengths_m"].values())
        inertia = ", ".join(f"{b} {v:.4g}" for b, v in m["pivot_inertia_kg_m2"].items())
        lines.append(f"  {m['value']:>7g}   {m['peak_torque_N_m']:10.5g}   "
                     f"{m['peak_torque_at_deg']:8.1f}   {m['max_torque_N_m']:9.5g}   "
                     f"{m['min_torque_N_m']:9.5g}   {m['rms_torque_N_m']:9.5g}   "
                     f"{lengths:>24}   {inertia}")
    return "\n".join(lines)
