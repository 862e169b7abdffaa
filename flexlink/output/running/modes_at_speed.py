"""Modes at an operating point (``studies.running.modes_at_speed``) as JSON, a text table and CSV:
each mode beside its paired static mode, the change at speed, its growth rate, and the
preload's largest axial force. ``operating_summary`` declares the JSON's field names; the text
and the CSV show its values."""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

from flexlink.analysis.instability import Cause, RootKind
from flexlink.studies.running.modes_at_speed import ASSUMPTIONS, PAIRING_MAC, OperatingPoint
from flexlink.units import percent_error, rev_per_min


def operating_summary(op: OperatingPoint) -> dict:
    """Everything the text, CSV and JSON show, in SI and plain types. A real root has no
    frequency and no static partner; a vibration whose MAC with every static mode is below
    PAIRING_MAC keeps its nearest static mode but no change."""
    modes = []
    for i, (kind, paired) in enumerate(zip(op.kinds, op.paired)):
        s, j, mac = op.modes.eigenvalues[i], int(op.static_index[i]), float(op.mac[i])
        vibrating = kind is RootKind.VIBRATING
        f, f0 = float(op.frequencies[i]), float(op.static.elastic_frequencies[j])
        modes.append({
            "mode": i + 1, "kind": str(kind), "frequency_Hz": f if vibrating else None,
            "growth_rate_1_s": float(s.real), "growing": bool(op.modes.growing[i]),
            "static_mode": j + 1 if vibrating else None,
            "static_Hz": f0 if vibrating else None, "mac": mac if vibrating else None,
            "paired": bool(paired),
            "change_Hz": f - f0 if paired else None,
            "change_pct": float(percent_error(f, f0)) if paired else None,
            "backward_error": float(op.modes.backward_errors[i])})
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
        "pairing_mac": PAIRING_MAC,
        "modes": modes,
        "stable": bool(op.modes.stable),
        "negative_stiffness_eigenvalues": op.modes.negative_stiffness,
        "instability_causes": [str(c) for c in op.causes],
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


CAUSES = {
    Cause.PRELOAD: "buckling under the inertia preload (the frame's stiffness with the preload "
                   "alone has negative eigenvalues: compression from the links' inertia loads)",
    Cause.CENTRIFUGAL: "the centrifugal softening (the frame's stiffness with it alone has "
                       "negative eigenvalues)",
    Cause.COMBINED: "the inertia preload and the centrifugal softening together (neither "
                    "alone makes the stiffness negative)",
}


def stability_note(op: OperatingPoint) -> str | None:
    """One sentence on the negative stiffness and the growing modes, naming the cause
    ``analysis.instability`` judged from the matrices; None when every mode is neutral."""
    notes = []
    if op.modes.negative_stiffness:
        named = [CAUSES[c] for c in op.causes if c in CAUSES]
        notes.append(f"negative stiffness: the effective stiffness has "
                     f"{op.modes.negative_stiffness} negative eigenvalue(s) at this speed, from "
                     + "; ".join(named))
    diverging = [i + 1 for i, k in enumerate(op.kinds) if k is RootKind.DIVERGING]
    if diverging:
        notes.append(f"mode(s) {', '.join(map(str, diverging))} diverge (a real root: they "
                     "leave the pose without oscillating)")
    flutter = [i + 1 for i, (g, k) in enumerate(zip(op.modes.growing, op.kinds))
               if g and k is RootKind.VIBRATING]
    if flutter and Cause.CIRCULATORY in op.causes:
        notes.append(f"mode(s) {', '.join(map(str, flutter))} grow while vibrating: the "
                     "circulatory term of the links' angular acceleration (alpha S, skew: it "
                     "does work) causes it"
                     + (" with the Coriolis coupling" if op.terms.coriolis else "")
                     + ", and its sign changes over a cycle")
    elif flutter and not op.modes.negative_stiffness:
        notes.append(f"mode(s) {', '.join(map(str, flutter))} grow with a positive-definite "
                     "stiffness and no circulatory term, which a conservative system cannot: "
                     "round-off of the eigen solve (see the backward errors)")
    elif flutter:
        notes.append(f"mode(s) {', '.join(map(str, flutter))} grow while vibrating: the "
                     "negative stiffness coupled by the Coriolis term")
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


def _cells(row: dict) -> str:
    """The frequency, static, change and MAC cells of a mode row: a real root by its kind and
    growth only, an unpaired vibration without its change, named as such at the end."""
    growth = f"{row['growth_rate_1_s']:>11.3g}"
    if row["kind"] != "vibrating":
        word = "diverges" if row["kind"] == "diverging" else "decays"
        return f"{word:>12} {'':>10} {'':>10} {'':>9} {growth} {'':>6}  (real root: no frequency)"
    cells = f"{row['frequency_Hz']:>12.2f} {row['static_Hz']:>10.2f} "
    if not row["paired"]:
        return (cells + f"{'':>10} {'':>9} {growth} {row['mac']:>6.3f}  unpaired (MAC "
                f"{row['mac']:.2f} with static mode {row['static_mode']}, below "
                f"{PAIRING_MAC:g})")
    return (cells + f"{row['change_Hz']:>+10.3f} {row['change_pct']:>+9.3f} {growth} "
            f"{row['mac']:>6.3f}" + (f"  (static mode {row['static_mode']})"
                                     if row["static_mode"] != row["mode"] else ""))


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
    lines += [f"{r['mode']:>4} {_cells(r)}" for r in summary["modes"]]
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
    """One row per mode and scene; a value there is none of (a real root's frequency, an
    unpaired mode's change) is an empty cell."""
    def cell(value, fmt):
        return "" if value is None else format(value, fmt)
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(["scene", "speed_rev_per_min", "crank_angle_deg", "mode", "kind", "frequency_Hz",
                "static_Hz", "change_Hz", "change_pct", "growth_rate_1_s", "mac", "static_mode",
                "paired"])
    for s in summaries:
        for r in s["modes"]:
            w.writerow([s["scene"], f"{s['speed_rev_per_min']:.10g}", f"{s['crank_angle_deg']:.10g}",
                        r["mode"], r["kind"], cell(r["frequency_Hz"], ".10g"),
                        cell(r["static_Hz"], ".10g"), cell(r["change_Hz"], ".10g"),
                        cell(r["change_pct"], ".10g"), f"{r['growth_rate_1_s']:.10g}",
                        cell(r["mac"], ".6f"), cell(r["static_mode"], "d"), r["paired"]])
    return out.getvalue()
