"""The Campbell diagram's renderings (``studies.campbell_study.CampbellStudy``): the JSON
document and the text summary of `flexlink campbell`, the CSV of critical ranges and the PNG
diagram (and those of the diagram at speed, ``output.dynamic_campbell``)."""

from __future__ import annotations

import numpy as np

from flexlink.fileio import write_atomic
from flexlink.output.running.dynamic_campbell import dynamic_csv, dynamic_json, dynamic_lines, plot_dynamic
from flexlink.output.figures import write_figure
from flexlink.output.cycle.tracking import (events_json, periodicity_json, reseeds_json,
                                             tracking_lines, unsampled_json)
from flexlink.studies.cycle.bands import Band, CriticalSpeed
from flexlink.units import rev_per_min
from flexlink.studies.cycle.campbell import CampbellStudy
from flexlink.studies.cycle.tracking import unsampled_note


def campbell_document(scene, study: CampbellStudy) -> dict:
    """The JSON document of `flexlink campbell` (without its ``files``): the speed window
    [rev/min], the bands [Hz], the critical speed ranges [rev/min], the nearest margin, the
    tracking, and with the diagram at speed its bands and shifted ranges."""
    labels, tracked, nearest = study.labels, study.tracked, study.nearest
    document = {
        "command": "campbell", "scene": scene.name,
        "speeds_rev_per_min": [rev_per_min(study.window[0]), rev_per_min(study.window[1])],
        "margin": study.margin, "harmonics": study.harmonics, "poses": study.poses,
        "mesh": study.mesh.as_dict(),
        "bands": [{"mode": b.mode, "label": labels.get(b.mode), "min_Hz": b.low,
                   "max_Hz": b.high} for b in study.bands],
        "critical_speeds": [{"mode": c.mode, "harmonic": c.harmonic,
                             "from_rev_per_min": rev_per_min(c.low),
                             "to_rev_per_min": rev_per_min(c.high)}
                            for c in study.critical],
        "nearest_margin": None if nearest is None else {
            "mode": nearest.mode, "harmonic": nearest.harmonic, "relative_gap": nearest.gap,
            "at_rev_per_min": rev_per_min(nearest.speed)},
        "tracking_events": events_json(tracked),
        "tracking_reseeds": reseeds_json(tracked),
        "periodicity": periodicity_json(tracked),
        "unsampled_dead_centres_deg": unsampled_json(tracked),
        "unsampled_note": unsampled_note(tracked),
    }
    if study.at_speed is not None:
        document["at_speed"] = dynamic_json(study.at_speed, list(study.shifts))
    if study.note:  # the diagram holds the in-plane modes only
        document["note"] = study.note
    return document


def campbell_text(document: dict, study: CampbellStudy) -> str:
    """The text summary of `flexlink campbell` from its ``document`` (``campbell_document``)."""
    low, high = document["speeds_rev_per_min"]
    out = [f"{document['scene']}: {len(study.bands)} tracked modes over {study.poses} crank "
           f"angles, {low:g}-{high:g} rev/min, harmonics 1..{study.harmonics}, "
           f"margin {100 * study.margin:g} %", study.mesh.describe()]
    if study.note:
        out.append(study.note)
    out.append(f"{'mode':>4} {'band [Hz]':>19}  label")
    for b in document["bands"]:
        out.append(f"{b['mode']:>4} {b['min_Hz']:>9.2f}-{b['max_Hz']:<9.2f}  {b['label'] or ''}")
    out += tracking_lines(document["tracking_reseeds"], document["unsampled_note"],
                          document["periodicity"])
    if document["critical_speeds"]:
        out.append(f"critical speeds:\n{'mode':>4} {'harmonic':>8} {'from [rev/min]':>15} "
                   f"{'to [rev/min]':>13}")
        for c in document["critical_speeds"]:
            out.append(f"{c['mode']:>4} {c['harmonic']:>8} {c['from_rev_per_min']:>15.1f} "
                       f"{c['to_rev_per_min']:>13.1f}")
    else:  # the nearest margin says how close the range comes (inside a band it is 0)
        n = document["nearest_margin"]
        out.append("no critical speed in the range; nearest margin: harmonic "
                   f"{n['harmonic']} of mode {n['mode']}, relative gap "
                   f"{100 * n['relative_gap']:.2f} % at {n['at_rev_per_min']:.1f} rev/min")
    if study.at_speed is not None:
        out += dynamic_lines(study.at_speed, list(study.shifts))
    return "\n".join(out)


def write_campbell(study: CampbellStudy, folder) -> list:
    """campbell.png and campbell.csv (the critical ranges) in ``folder``, and with the diagram
    at speed campbell_at_speed.png and .csv, each written atomically; returns their paths."""
    paths = [folder / "campbell.png", folder / "campbell.csv"]
    plot_campbell(list(study.bands), study.window, study.margin, study.harmonics,
                  list(study.critical), paths[0], study.tracked.scene, study.labels)
    write_atomic(paths[1], critical_csv(list(study.critical), list(study.bands)))
    if study.at_speed is not None:
        paths += [folder / "campbell_at_speed.png", folder / "campbell_at_speed.csv"]
        plot_dynamic(study.at_speed, study.margin, study.harmonics, paths[2],
                     study.tracked.scene)
        write_atomic(paths[3], dynamic_csv(study.at_speed))
    return paths


def critical_csv(critical: list[CriticalSpeed], found: list[Band]) -> str:
    """One row per critical range: mode, its band [Hz], harmonic, speed range [rev/min]."""
    by_mode = {b.mode: b for b in found}
    lines = ["mode,band_min_Hz,band_max_Hz,harmonic,from_rev_per_min,to_rev_per_min"]
    for c in critical:
        b = by_mode[c.mode]
        lines.append(f"{c.mode},{b.low:.8g},{b.high:.8g},{c.harmonic},{rev_per_min(c.low):.6g},"
                     f"{rev_per_min(c.high):.6g}")
    return "\n".join(lines) + "\n"


def plot_campbell(found: list[Band], speeds: tuple[float, float], margin: float,
                  harmonics: int, critical: list[CriticalSpeed], path, title: str = "",
                  labels=None) -> None:
    """PNG: bands (and their margin bands, lighter) against crank speed [rev/min], harmonic
    lines n x speed, and the critical speed ranges shaded along the speed axis. Written to
    ``path`` atomically."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    labels = labels or {}
    low, high = rev_per_min(speeds[0]), rev_per_min(speeds[1])
    fig, ax = plt.subplots(figsize=(8, 5))
    top = max(b.high for b in found) * (1 + margin) * 1.1
    for b in found:
        colour = f"C{b.mode - 1}"
        ax.axhspan(b.low * (1 - margin), b.high * (1 + margin), color=colour, alpha=0.12, lw=0)
        ax.axhspan(b.low, b.high, color=colour, alpha=0.45, lw=0,
                   label=f"mode {b.mode}" + (f": {labels[b.mode]}" if labels.get(b.mode) else ""))
    rpm = np.array([low, high])
    for n in range(1, harmonics + 1):
        f = n * rpm / 60.0
        ax.plot(rpm, f, color="0.3", lw=0.8)
        if f[-1] <= top:
            ax.annotate(f"{n}x", (rpm[-1], f[-1]), fontsize=7, ha="right", va="bottom")
        else:
            ax.annotate(f"{n}x", (60.0 * top / n, top), fontsize=7, ha="right", va="top")
    for c in critical:
        ax.axvspan(rev_per_min(c.low), rev_per_min(c.high), color="red", alpha=0.08, lw=0)
    ax.set_xlim(low, high)
    ax.set_ylim(0, top)
    ax.set_xlabel("crank speed [rev/min]")
    ax.set_ylabel("frequency [Hz]")
    ax.set_title(title + f" (margin {100 * margin:g} %)")
    ax.legend(fontsize=8, loc="upper left")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    write_figure(fig, path)
