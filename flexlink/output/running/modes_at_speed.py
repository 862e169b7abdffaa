"""Modes at an operating point (``studies.running.modes_at_speed``) as JSON, a text table and CSV:
each mode beside its paired static mode, the change at speed, its growth rate, and the
preload's largest axial force. ``operating_summary`` declares the JSON's field names; the text
and the CSV show its values."""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

from flexlink.studies.running.modes_at_speed import ASSUMPTIONS, OperatingPoint
from flexlink.units import percent_error, rev_per_min



def operating_summary(op: OperatingPoint) -> dict:
    """Everything the text, CSV and JSON show, in SI and plain types."""
    modes = []
    static = op.static_frequencies
    for i, (f, rate, grows, mac, j) in enumerate(zip(op.frequencies, op.modes.growth_rates,
                                                    op.modes.growing, op.mac, op.static_index)):
        modes.append({
            "mode": i + 1, "frequency_Hz": float(f), "growth_rate_1_s": float(rate),
            "growing": bool(grows), "static_mode": int(j) + 1, "static_Hz": float(static[i]),
            "divergent": bool(abs(op.modes.eigenvalues[i].imag) <= 1e-8 * abs(op.modes.eigenvalues[i])),
            "change_Hz": float(f - static[i]), "change_pct": float(percent_error(f, static[i])),
            "mac": float(mac), "backward_error": float(op.modes.backward_errors[i])})
    largest = op.largest_axial
    terms = op.terms
    return {
        "scene": op.scene.name, "file": op.scene.path,
        "crank_angle_deg": math.degrees(op.motion.q),
        "speed_rad_s": op.motion.speed, "speed_rev_per_min": rev_per_min(op.motion.speed),
        "crank_acceleration_rad_s2": op.motion.crank_acceleration,
        "terms": {"preload": terms.preload, "centrifugal": terms.centrifugal,
                  "coriolis": terms.coriolis, "angular_acceleration": terms.acceleration,
                  "geometric_stiffness": terms.geometric.value},
        "assumptions": list(ASSUMPTIONS),
        "elements_per_link": op.elements_per_link, "dofs": op.static.n_dofs,
        "modes": modes,
        "stable": bool(op.modes.stable),
        "negative_stiffness_eigenvalues": op.modes.negative_stiffness,
        "stability": stability_note(op),
        "largest_axial_force": {"N": largest.value, "link": largest.link,
                                "element": largest.element + 1,
                                "position_m": largest.position},
        "links": {name: {"omega_rad_s": float(w), "alpha_rad_s2": float(a),
                         "max_tension_N": float(max(N.max(), 0.0)),
                         "max_compression_N": float(max(-N.min(), 0.0))}
                  for (name, N), w, a in zip(op.axial_forces.items(), op.link_omega,
                                             op.link_alpha)},
        "warnings": list(op.warnings),
    }


def stability_note(op: OperatingPoint) -> str | None:
    """One sentence on divergence or growing modes; None when every mode is neutral."""
    notes = []
    if op.modes.negative_stiffness:
        notes.append(f"divergence: the effective stiffness has {op.modes.negative_stiffness} "
                     "negative eigenvalue(s) at this speed (the preload or the centrifugal "
                     "softening overcomes the frame's stiffness)")
    grows = [i + 1 for i, g in enumerate(op.modes.growing) if g]
    if grows:
        circulatory = op.terms.acceleration and bool(abs(op.link_alpha).max() > 0)
        notes.append(f"mode(s) {', '.join(map(str, grows))} grow in the frozen configuration "
                     "(positive real part)" + (
                         "; the links' angular acceleration (circulatory term with the Coriolis "
                         "coupling) causes it, and its sign changes over a cycle"
                         if circulatory else ""))
    return "; ".join(notes) or None


def operating_document(summaries: list[dict], files, failures: list[dict] | None = None) -> dict:
    """The JSON document of ``modes --speed``: the scenes' summaries, the files written and,
    for the run's own printed document, the scenes that failed."""
    document = {"command": "modes --speed", "cases": summaries, "files": [str(f) for f in files]}
    return document if failures is None else {**document, "failures": failures}


def operating_files(scenes: list[tuple[Path, OperatingPoint]], failures: list[dict]
                    ) -> tuple[dict[Path, dict], dict[Path, str], dict]:
    """What ``modes --speed`` writes: modes_at_speed.json and .csv in each scene's folder (the
    JSON documents and the CSV texts, by path), and the printed document with every scene,
    every file and the ``failures``."""
    documents, tables, summaries = {}, {}, []
    for folder, op in scenes:
        summary = operating_summary(op)
        json_path, csv_path = folder / "modes_at_speed.json", folder / "modes_at_speed.csv"
        documents[json_path] = operating_document([summary], [json_path, csv_path])
        tables[csv_path] = operating_csv([summary])
        summaries.append(summary)
    written = [p for pair in zip(documents, tables) for p in pair]
    return documents, tables, operating_document(summaries, written, failures)


def operating_text(ops: list[OperatingPoint]) -> str:
    """The text tables of the operating points, each followed by an empty line."""
    return "".join(format_operating(operating_summary(op)) + "\n\n" for op in ops)


def _frequency(row: dict) -> str:
    return "diverges" if row["divergent"] else f"{row['frequency_Hz']:.2f}"


def format_operating(summary: dict) -> str:
    """The text table of one operating point."""
    head = f"{summary['scene']}  ({summary['file']})"
    off = [k for k, v in summary["terms"].items() if v is False]
    lines = [head, "-" * len(head),
             f"at speed: {summary['speed_rev_per_min']:.6g} rev/min ({summary['speed_rad_s']:.6g} "
             f"rad/s), crank angle {summary['crank_angle_deg']:.3f} deg"
             + (f", crank acceleration {summary['crank_acceleration_rad_s2']:.6g} rad/s^2"
                if summary["crank_acceleration_rad_s2"] else "")
             + f"; {summary['elements_per_link']} elements/link, {summary['dofs']} DOFs; "
             f"K_g {summary['terms']['geometric_stiffness']}"
             + (f"; terms off: {', '.join(off)}" if off else ""),
             f"{'mode':>4} {'at speed Hz':>12} {'static Hz':>10} {'change Hz':>10} "
             f"{'change %':>9} {'growth 1/s':>11} {'MAC':>6}"]
    for r in summary["modes"]:
        lines.append(f"{r['mode']:>4} {_frequency(r):>12} {r['static_Hz']:>10.2f} "
                     f"{r['change_Hz']:>+10.3f} {r['change_pct']:>+9.3f} "
                     f"{r['growth_rate_1_s']:>11.3g} {r['mac']:>6.3f}"
                     + (f"  (static mode {r['static_mode']})" if r["static_mode"] != r["mode"]
                        else ""))
    big = summary["largest_axial_force"]
    kind = "tension" if big["N"] >= 0 else "compression"
    lines.append(f"largest axial force: {abs(big['N']):.4g} N {kind} in link {big['link']} "
                 f"(element {big['element']}, {1000 * big['position_m']:.1f} mm from its start)")
    if summary["stability"]:
        lines.append("warning: " + summary["stability"])
    lines += ["warning: " + w for w in summary["warnings"]]
    lines += ["assumed: " + a for a in summary["assumptions"]]
    return "\n".join(lines)


def operating_csv(summaries: list[dict]) -> str:
    """One row per mode and scene."""
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(["scene", "speed_rev_per_min", "crank_angle_deg", "mode", "frequency_Hz",
                "static_Hz", "change_Hz", "change_pct", "growth_rate_1_s", "mac", "static_mode"])
    for s in summaries:
        for r in s["modes"]:
            w.writerow([s["scene"], f"{s['speed_rev_per_min']:.10g}", f"{s['crank_angle_deg']:.10g}",
                        r["mode"], f"{r['frequency_Hz']:.10g}", f"{r['static_Hz']:.10g}",
                        f"{r['change_Hz']:.10g}", f"{r['change_pct']:.10g}",
                        f"{r['growth_rate_1_s']:.10g}", f"{r['mac']:.6f}", r["static_mode"]])
    return out.getvalue()
