"""Rendering of the steady response: JSON document, CSV and text lines of one speed (strain
and deflection over the crank angle) or of a sweep (peak strain against speed), and their
PNGs."""

from __future__ import annotations

import math

import numpy as np

from flexlink.output.running.stability_map import damping_line, mesh_json
from flexlink.studies.running.steady_response import SMALL_DEFLECTION, depth_ratio
from flexlink.units import rev_per_min

STRAIN_NOTE = ("strain: bending strain at the fibre y = +depth/2 of the link's local frame "
               "(left of start -> end); deflection: transverse, less the chord through the "
               "link's ends")
CAVEAT = ("the reduced basis is the stability map's, checked on the lowest frequencies of "
          "every pose (docs/critical-speeds.md), with the loads' static answers at every pose "
          "added (the stability verdict is the map's own basis's); strain converges more "
          "slowly than frequency")


def _crank_deg(response) -> np.ndarray:
    return np.degrees(response.angles) % 360.0


def response_document(scene_name: str, response, model, mesh=None) -> dict:
    """One speed: per point the strain and deflection over the crank angle and their peaks,
    and whether the peak stays within the small-deflection range; the mesh (an
    ``analysis.mesh.MeshRule``, None: not stated)."""
    deg = _crank_deg(response)
    ratio = depth_ratio(model, response.peak_deflection)
    return {
        "command": "response", "scene": scene_name, "caveat": CAVEAT, "note": STRAIN_NOTE,
        "mesh": mesh_json(mesh),
        "speed_rev_per_min": rev_per_min(response.speed),
        "damping_ratio": model.periodic.damping_ratio.tolist(),
        "damping_source": model.periodic.damping_source,
        "basis_frequencies_Hz": model.periodic.frequencies.tolist(),
        "load_vectors": model.periodic.load_vectors,
        "largest_modulus": response.largest_modulus,
        "crank_deg": deg.tolist(),
        "points": [
            {"label": p.label, "link": p.link, "position_m": p.position,
             "strain": response.strain[:, k].tolist(),
             "deflection_m": response.deflection[:, k].tolist(),
             "peak_strain": float(response.peak_strain[k]),
             "peak_strain_at_deg": float(deg[np.argmax(np.abs(response.strain[:, k]))]),
             "peak_deflection_m": float(response.peak_deflection[k]),
             "deflection_to_depth": float(ratio[k]),
             "small_deflection": bool(ratio[k] <= SMALL_DEFLECTION)}
            for k, p in enumerate(model.points)],
        "small_deflection_limit": SMALL_DEFLECTION,
        "warnings": deflection_warnings(model.points, ratio),
    }


def deflection_warnings(points, ratio, speeds=None) -> list[str]:
    """One sentence per point whose peak deflection passes SMALL_DEFLECTION times its link's
    depth (``ratio``: per point, or per speed and point with ``speeds`` [rev/min])."""
    ratio = np.asarray(ratio, dtype=float)
    out = []
    for k, p in enumerate(points):
        values = ratio[..., k]
        if not np.nanmax(values, initial=0.0) > SMALL_DEFLECTION:
            continue
        where = ""
        if speeds is not None:
            first = speeds[int(np.flatnonzero(values > SMALL_DEFLECTION)[0])]
            worst = speeds[int(np.nanargmax(values))]
            where = (f" at {worst:g} rev/min (past {SMALL_DEFLECTION:g} times from {first:g} "
                     "rev/min on the sweep)")
        out.append(f"{p.label}: peak deflection {np.nanmax(values):.3g} times the link's depth"
                   f"{where}, beyond the small-deflection range (at most {SMALL_DEFLECTION:g} "
                   "times the depth): the linear model does not hold there")
    return out


def sweep_document(scene_name: str, sweep, model, mesh=None) -> dict:
    """A speed sweep: peak strain and deflection per point against speed; unstable speeds
    (no steady state) as null and listed; the mesh as in ``response_document``."""
    ratio = depth_ratio(model, sweep.peak_deflection)

    def listed(values):
        return [None if math.isnan(v) else float(v) for v in values]
    return {
        "command": "response", "scene": scene_name, "caveat": CAVEAT, "note": STRAIN_NOTE,
        "mesh": mesh_json(mesh),
        "damping_ratio": model.periodic.damping_ratio.tolist(),
        "damping_source": model.periodic.damping_source,
        "basis_frequencies_Hz": model.periodic.frequencies.tolist(),
        "load_vectors": model.periodic.load_vectors,
        "speeds_rev_per_min": (rev_per_min(sweep.speeds)).tolist(),
        "largest_modulus": listed(sweep.largest_modulus),
        "unstable_speeds_rev_per_min": (rev_per_min(sweep.speeds[sweep.unstable])).tolist(),
        "points": [{"label": p.label, "link": p.link, "position_m": p.position,
                    "peak_strain": listed(sweep.peak_strain[:, k]),
                    "peak_deflection_m": listed(sweep.peak_deflection[:, k]),
                    "deflection_to_depth": listed(ratio[:, k])}
                   for k, p in enumerate(sweep.points)],
        "small_deflection_limit": SMALL_DEFLECTION,
        "warnings": deflection_warnings(sweep.points, ratio, rev_per_min(sweep.speeds)),
    }


def response_csv(response, model) -> str:
    """One row per crank angle: strain and deflection [m] of each point."""
    head = ["crank_deg"] + [f"{p.label} {q}" for p in model.points
                            for q in ("strain", "deflection_m")]
    lines = [",".join(head)]
    for i, d in enumerate(_crank_deg(response)):
        cells = [f"{d:.4f}"] + [f"{x:.10g}" for k in range(len(model.points))
                                for x in (response.strain[i, k], response.deflection[i, k])]
        lines.append(",".join(cells))
    return "\n".join(lines) + "\n"


def sweep_csv(sweep) -> str:
    """One row per speed: the largest multiplier and each point's peaks (empty: unstable)."""
    head = ["speed_rev_per_min", "largest_modulus"] + [
        f"{p.label} {q}" for p in sweep.points for q in ("peak_strain", "peak_deflection_m")]
    lines = [",".join(head)]
    for i, w in enumerate(sweep.speeds):
        values = [sweep.largest_modulus[i]] + [x for k in range(len(sweep.points))
                                               for x in (sweep.peak_strain[i, k],
                                                         sweep.peak_deflection[i, k])]
        lines.append(",".join([f"{rev_per_min(w):.6g}"] + ["" if math.isnan(x) else f"{x:.10g}"
                                                     for x in values]))
    return "\n".join(lines) + "\n"


def response_lines(document: dict) -> list[str]:
    """The text summary of either document."""
    out = [f"{document['scene']}: {len(document['basis_frequencies_Hz'])} basis vectors "
           f"({document['load_vectors']} of them the loads' static answers)",
           damping_line(document["damping_ratio"], document["damping_source"]),
           f"caveat: {document['caveat']}"]
    if document.get("mesh"):
        out.append(document["mesh"]["description"])
    if "speeds_rev_per_min" in document:
        speeds = document["speeds_rev_per_min"]
        out.append(f"{len(speeds)} speeds, {speeds[0]:g} to {speeds[-1]:g} rev/min")
        for p in document["points"]:
            peaks = [(s, v) for s, v in zip(speeds, p["peak_strain"]) if v is not None]
            if peaks:
                s, v = max(peaks, key=lambda sv: sv[1])
                ratio = p["deflection_to_depth"][speeds.index(s)]
                out.append(f"{p['label']:>24}: largest peak strain {v * 1e6:.4g} microstrain "
                           f"at {s:g} rev/min" + (
                               f", beyond small deflection ({ratio:.3g} x depth)"
                               if ratio is not None and ratio > document[
                                   "small_deflection_limit"] else ""))
        unstable = document["unstable_speeds_rev_per_min"]
        if unstable:
            out.append(f"no steady state (|mu| >= 1) at {len(unstable)} speed(s): "
                       + ", ".join(f"{s:g}" for s in unstable[:8])
                       + (" ..." if len(unstable) > 8 else "") + " rev/min")
        return out + [f"warning: {w}" for w in document["warnings"]]
    out.append(f"at {document['speed_rev_per_min']:g} rev/min (largest |mu| "
               f"{document['largest_modulus']:.4g})")
    out.append(f"{'point':>24} {'peak strain [1e-6]':>19} {'at [deg]':>9} "
               f"{'peak deflection [mm]':>21}")
    for p in document["points"]:
        out.append(f"{p['label']:>24} {p['peak_strain'] * 1e6:>19.4g} "
                   f"{p['peak_strain_at_deg']:>9.1f} {p['peak_deflection_m'] * 1e3:>21.4g}"
                   + ("" if p["small_deflection"] else
                      f"  beyond small deflection ({p['deflection_to_depth']:.3g} x depth)"))
    return out + [f"warning: {w}" for w in document["warnings"]]


def plot_response(response, model, path, title: str) -> None:
    """PNG: strain (top) and deflection (bottom) of each point over one crank turn."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from flexlink.output.figures import write_figure

    deg = _crank_deg(response)
    order = np.argsort(deg)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for k, p in enumerate(model.points):
        top.plot(deg[order], response.strain[order, k] * 1e6, label=p.label)
        bottom.plot(deg[order], response.deflection[order, k] * 1e3, label=p.label)
    top.set(ylabel="bending strain [1e-6]",
            title=f"{title}: steady response at {rev_per_min(response.speed):g} rev/min")
    bottom.set(xlabel="crank angle [deg]", ylabel="deflection [mm]", xlim=(0, 360))
    top.legend(fontsize=8)
    write_figure(fig, path)


def plot_sweep(sweep, path, title: str, frequencies=(), harmonics: int = 4) -> None:
    """PNG: peak strain of each point against speed [rev/min], log scale; unstable speeds
    shaded; dotted: the Campbell lines k Omega = f_i of the basis ``frequencies`` [Hz],
    k = 1 ... ``harmonics``, inside the range."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from flexlink.output.figures import write_figure

    rpm = rev_per_min(sweep.speeds)
    fig, ax = plt.subplots(figsize=(8, 4))
    for k, p in enumerate(sweep.points):
        ax.semilogy(rpm, sweep.peak_strain[:, k] * 1e6, lw=1.2, label=p.label)
    step = (rpm[-1] - rpm[0]) / max(len(rpm) - 1, 1)
    for s in rpm[sweep.unstable]:
        ax.axvspan(s - step / 2, s + step / 2, color="tab:red", alpha=0.25, lw=0)
    for i, f in enumerate(frequencies):
        for k in range(1, harmonics + 1):
            at = 60.0 * f / k
            if rpm[0] <= at <= rpm[-1]:
                ax.axvline(at, color="0.5", lw=0.6, ls=":")
                ax.text(at, 0.98, f"f{i + 1}/{k}", transform=ax.get_xaxis_transform(),
                        fontsize=7, rotation=90, va="top", ha="right", color="0.4")
    ax.set(xlabel="crank speed [rev/min]", ylabel="peak bending strain [1e-6]", title=title,
           xlim=(rpm[0], rpm[-1]))
    ax.legend(fontsize=8, loc="lower right")
    write_figure(fig, path)


def write_response(result, model, folder, title: str, mesh=None) -> tuple[dict, list]:
    """response.png and response.csv in ``folder`` (atomically) for one speed
    (``SteadyResponse``) or a sweep of speeds; returns (the JSON document, with ``mesh`` as
    ``response_document`` has it, and their paths)."""
    from flexlink.fileio import write_atomic
    from flexlink.studies.running.steady_response import SteadyResponse

    paths = [folder / "response.png", folder / "response.csv"]
    if isinstance(result, SteadyResponse):
        plot_response(result, model, paths[0], title)
        csv, document = response_csv(result, model), response_document(title, result, model,
                                                                        mesh)
    else:
        plot_sweep(result, paths[0], title, model.periodic.frequencies)
        csv, document = sweep_csv(result), sweep_document(title, result, model, mesh)
    write_atomic(paths[1], csv)
    return document, paths
