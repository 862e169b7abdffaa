"""The cycle map's renderings (``studies.cycle.modal_map.ModalMap``, or ``studies.cycle.tracking.TrackedMap``
for its tracked lines): the CSV of frequencies over the crank angle, the PNG of the map, and of
`flexlink cycle`'s study (``studies.cycle.cycle.CycleStudy``) the JSON document and the text
summary."""

from __future__ import annotations

import math

import numpy as np

from flexlink.fileio import write_atomic
from flexlink.output.figures import cycle_axes, write_figure
from flexlink.output.pose.synthesis_text import synthesis_line
from flexlink.output.cycle.tracking import (events_json, periodicity_json, plot_tracked,
                                             reseeds_json, tracked_csv, tracking_lines,
                                             unsampled_json)
from flexlink.studies.cycle.modal_map import ModalMap, Resonance, runs
from flexlink.studies.cycle.cycle import CycleStudy
from flexlink.studies.cycle.tracking import unsampled_note
from flexlink.units import rev_per_min


def modal_map_csv(result: ModalMap) -> str:
    """One row per pose: input angle [deg], then f1 ... fN [Hz]."""
    n = result.frequencies.shape[1]
    lines = ["crank_angle_deg," + ",".join(f"f{j + 1}_Hz" for j in range(n))]
    for q, row in zip(result.q, result.frequencies):
        lines.append(f"{math.degrees(q):.6g}," + ",".join(f"{v:.8g}" for v in row))
    return "\n".join(lines) + "\n"


def plot_map(result: ModalMap, path, crank_speed: float | None = None,
             hits: list[Resonance] = ()) -> None:
    """PNG of frequency against input angle, one line per mode; vertical lines mark the poses
    where mu = 90 deg; crank harmonics that resonate are drawn as horizontal dashes. Written to
    ``path`` atomically."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4.8))
    deg = np.degrees(result.q)
    for j in range(result.frequencies.shape[1]):
        ax.plot(deg, result.frequencies[:, j], label=f"mode {j + 1}")
    cycle_axes(ax, deg, result.mu90, hits, result.scene + (
        f" (crank {rev_per_min(crank_speed):g} rev/min)" if crank_speed else ""))
    ax.grid(alpha=0.3)
    fig.tight_layout()
    write_figure(fig, path)


def cycle_document(scene, study: CycleStudy) -> dict:
    """The JSON document of `flexlink cycle` (without its ``files``): each mode's range over
    the cycle [Hz] and where [deg], the mu = 90 deg poses, the resonance check with its hits,
    the tracking (for a tracked map), the nearest harmonic and the scene's assumptions."""
    result, poses = study.map, study.poses
    f = result.frequencies
    return {
        "command": "cycle", "scene": scene.name, "poses": poses,
        "synthesis": scene.synthesis,
        "modes": [{"mode": j + 1, "min_Hz": float(f[:, j].min()),
                   "at_crank_deg": math.degrees(result.q[f[:, j].argmin()]) % 360.0,
                   "max_Hz": float(f[:, j].max()),
                   "at_crank_deg_max": math.degrees(result.q[f[:, j].argmax()]) % 360.0}
                  for j in range(f.shape[1])],
        "mu90_crank_deg": {k: [math.degrees(a) for a in v] for k, v in result.mu90.items()},
        "mechanism_modes_max": int(result.mechanism_counts.max()),
        "mesh": study.mesh.as_dict(),
        "crank_speed_rev_per_min": None if study.crank_speed is None
        else rev_per_min(study.crank_speed),
        "resonance_check": {"speed_rev_per_min": None if study.check_speed is None
                                                 else rev_per_min(study.check_speed),
                            "note": study.check_note},
        "margin": study.margin,
        "resonances": [{"harmonic": h.harmonic, "harmonic_Hz": h.frequency, "mode": h.mode,
                        "closest_relative_gap": h.closest,
                        "crank_deg_ranges": [[round(math.degrees(a), 2), round(math.degrees(b), 2)]
                                             for a, b in runs(h.angles, 2 * math.pi / poses)]}
                       for h in study.hits],
        "tracking": {"by": "MAC", "labels": list(result.labels),
                     "events": events_json(result), "reseeds": reseeds_json(result),
                     "periodicity": periodicity_json(result),
                     "unsampled_dead_centres_deg": unsampled_json(result),
                     "unsampled_note": unsampled_note(result)} if study.tracked
        else {"by": "frequency order"},
        "nearest_harmonic": None if study.nearest is None else dict(zip(
            ("relative_gap", "mode", "harmonic"), study.nearest)),
        "assumptions": [f"{a.field}: {a.note}" for a in scene.assumptions],
        **({"note": study.note} if study.note else {}),  # the map is not quite what was asked
    }


def cycle_text(document: dict, study: CycleStudy) -> str:
    """The text summary of `flexlink cycle` from its ``document`` (``cycle_document``)."""
    margin, harmonics = document["margin"], study.harmonics
    out = [f"{document['scene']}: first {len(document['modes'])} elastic modes over "
           f"{document['poses']} crank angles", study.mesh.describe()]
    if document.get("note"):
        out.append(document["note"])
    synthesis = document["synthesis"]
    if synthesis:
        out.append(synthesis_line(synthesis, inputs=False))
    out.append(f"{'mode':>4} {'min [Hz]':>10} {'at [deg]':>9} {'max [Hz]':>10} {'at [deg]':>9}")
    labels = document["tracking"].get("labels", [])
    for m in document["modes"]:
        out.append(f"{m['mode']:>4} {m['min_Hz']:>10.2f} {m['at_crank_deg']:>9.1f} "
                   f"{m['max_Hz']:>10.2f} {m['at_crank_deg_max']:>9.1f}"
                   + (f"  {labels[m['mode'] - 1]}" if m["mode"] <= len(labels) else ""))
    for pair, angles in document["mu90_crank_deg"].items():
        where = (", ".join(f"{a:.2f}" for a in angles) + " deg") if angles else "never in the cycle"
        out.append(f"mu = 90 deg ({pair}) at crank {where}")
    check = document["resonance_check"]
    if check["note"]:
        out.append(check["note"])
    if check["speed_rev_per_min"] and not document["resonances"]:
        near = document["nearest_harmonic"]
        out.append(f"resonance check at {check['speed_rev_per_min']:g} "
                   f"rev/min: no harmonic 1..{harmonics} within {100 * margin:g} % of a natural "
                   f"frequency; nearest: harmonic {near['harmonic']} at "
                   f"{100 * near['relative_gap']:.1f} % from mode {near['mode']}")
    tracking = document["tracking"]
    for e in tracking.get("events", []):
        out.append(f"{e['kind']} of modes {e['lines'][0]} and {e['lines'][1]} at crank "
                   f"{e['crank_deg']:.1f} deg (gap {100 * e['gap']:.1f} %)")
    out += tracking_lines(tracking.get("reseeds", []), tracking.get("unsampled_note"),
                          tracking.get("periodicity"))
    for h in document["resonances"]:
        ranges = ", ".join(f"{a:.1f}-{b:.1f}" for a, b in h["crank_deg_ranges"])
        out.append(f"resonance: harmonic {h['harmonic']} ({h['harmonic_Hz']:.2f} Hz) within "
                   f"{100 * margin:g} % of mode {h['mode']} at crank {ranges} deg")
    return "\n".join(out)


def write_cycle(study: CycleStudy, folder) -> list:
    """cycle.csv and cycle.png of the map in ``folder`` (tracked lines with their events for a
    tracked map), each written atomically; returns their paths."""
    paths = [folder / "cycle.csv", folder / "cycle.png"]
    result = study.map
    write_atomic(paths[0], tracked_csv(result) if study.tracked else modal_map_csv(result))
    (plot_tracked if study.tracked else plot_map)(result, paths[1], study.check_speed, study.hits)
    return paths
