"""A scene's summary (``studies.pose.scene_summary``) rendered: its JSON document (every field name
declared here, once), the comparison table as text and as CSV. Rows pair computed and
reference frequencies by mode order of the elastic modes only; rigid-body/mechanism modes are
listed apart, never paired."""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

from flexlink.analysis.identity import DIRECTIONS, ModeIdentity
from flexlink.output.calibration.sensitivity import (alternative_document, alternative_line,
                                                format_sensitivity, sensitivity_document)
from flexlink.studies.pose.scene_summary import SceneSummary, overall_mean_abs_error


def comparison_rows(summary: SceneSummary) -> list[dict]:
    """One dict per elastic mode: mode, computed [Hz], with another family its kind, and for
    each reference column its value [Hz] and % error (computed vs reference); for the planar
    model's own modes also its identity (label, energy fractions, effective masses)."""
    rows = []
    for i, f in enumerate(summary.frequencies):
        row = {"mode": i + 1, "computed_Hz": float(f)}
        if summary.kinds is not None:
            row["kind"] = summary.kinds[i]
        for name, values in summary.reference.items():
            if i < len(values):
                row[f"{name}_Hz"] = values[i]
                row[f"error_vs_{name}_pct"] = float(summary.errors[name][i])
        rows.append({**row, **(identity_json(summary.identity, i) if summary.identity else {})})
    return rows


def identity_json(identity: ModeIdentity, j: int) -> dict:
    """Mode ``j``'s identity as JSON fields: its ``label``, the ``strain_energy`` and
    ``kinetic_energy`` fractions [-] per link and joint, and ``effective_mass_kg`` per
    direction."""
    return {"label": identity.labels[j],
            "strain_energy": dict(zip(identity.parts, identity.strain[j].tolist())),
            "kinetic_energy": dict(zip(identity.parts, identity.kinetic[j].tolist())),
            "effective_mass_kg": dict(zip(DIRECTIONS, identity.effective_mass[j].tolist()))}


def linkage_summary(scene) -> dict:
    """Lengths [m] of the four-bar (with its Grashof class), or of each beam link."""
    fb = scene.four_bar
    if fb is not None:
        return {"ground_m": fb.ground, "crank_m": fb.crank, "coupler_m": fb.coupler,
                "rocker_m": fb.rocker, "grashof": fb.grashof_class()}
    return {"bodies": [b.name for b in scene.linkage.bodies]}


def summary_document(summary: SceneSummary) -> dict:
    """The JSON document of one scene's summary; the alternatives and the sensitivity study
    only when they were asked for."""
    case = summary.case
    scene, pose, modes = case.scene, case.pose, case.modes
    out = {
        "scene": scene.name,
        "file": scene.path,
        "family": summary.family,
        "linkage": linkage_summary(scene),
        "pose": {"theta2_deg": math.degrees(pose.crank_angle),
                 "mu_deg": None if pose.mu is None else math.degrees(pose.mu),
                 "branch": pose.branch,
                 "joints_m": {k: list(v) for k, v in pose.joints.items()}},
        "elements_per_link": case.elements_per_link,
        "dofs": modes.n_dofs,
        "solver": modes.solver,
        "modes": comparison_rows(summary),
        "damping_ratio": summary.damping_ratio.tolist(),  # per elastic mode [-]
        "damping_source": summary.damping_source,
        "mechanism_modes_Hz": summary.mechanism.tolist(),
        "mass_kg": {"total": summary.mass,
                    "participating": dict(zip(DIRECTIONS, summary.participating.tolist()))},
        "mean_abs_error_pct": summary.mean_abs_error_pct,
        "max_residual": summary.max_residual,
        "max_backward_error": float(modes.backward_errors.max()),
        "orthogonality_error": modes.orthogonality_error,
        "seconds": case.seconds,
        "assumptions": [{"field": a.field, "value": a.value, "note": a.note}
                        for a in scene.assumptions],
        "reference_source": scene.reference.source if scene.reference else None,
        "mesh": summary.mesh.as_dict(),
        "warnings": list(summary.warnings) + ([summary.note] if summary.note else []),
    }
    if summary.note:
        out["note"] = summary.note
    alternatives = summary.alternatives
    if alternatives is not None:
        out["other_orientation"] = alternative_document(alternatives.orientation)
        if alternatives.timoshenko is not None:
            out["timoshenko"] = alternative_document(alternatives.timoshenko)
        if alternatives.shear_source is not None:
            out["other_shear_source"] = alternative_document(alternatives.shear_source)
    if summary.sensitivity is not None:
        out["sensitivity"] = sensitivity_document(summary.sensitivity)
    return out


def modes_document(summaries: list[SceneSummary], files, failures: list[dict] | None = None
                   ) -> dict:
    """The JSON document of ``flexlink modes`` over ``summaries`` listing ``files``, with the
    ``failures`` of a run over several scenes."""
    out = {"command": "modes", "cases": [summary_document(s) for s in summaries],
           "overall_mean_abs_error_pct": overall_mean_abs_error(summaries),
           "files": [str(f) for f in files]}
    return out if failures is None else {**out, "failures": failures}


def modes_files(scenes: list[tuple[Path, SceneSummary]], combined: Path | None,
                failures: list[dict]) -> tuple[dict[Path, dict], dict[Path, str], dict]:
    """What ``flexlink modes`` writes: the JSON documents and CSV texts of modes.json and
    modes.csv in each scene's folder, and in ``combined`` (the --out folder of a run over
    several scenes) those of every scene; and the printed document, which is the combined
    file's, or with one scene the run's own (its files and ``failures``)."""
    summaries = [s for _, s in scenes]
    parts = [(folder, [s]) for folder, s in scenes]
    if combined is not None and summaries:
        parts.append((combined, summaries))
    written = [folder / name for folder, _ in parts for name in ("modes.json", "modes.csv")]
    document = modes_document(summaries, written, failures)
    # a scene's own file lists its own two files; the combined file is the printed document
    documents = {folder / "modes.json": document if part is summaries else
                 modes_document(part, [folder / "modes.json", folder / "modes.csv"])
                 for folder, part in parts}
    tables = {folder / "modes.csv": comparison_csv(part) for folder, part in parts}
    return documents, tables, document


def hz_text(frequency: float) -> str:
    """A frequency [Hz] for the text table: two decimals from 1 Hz up, four significant digits
    below (a soft scene's modes at mHz must not all read 0.00)."""
    return f"{frequency:.2f}" if abs(frequency) >= 1.0 else f"{frequency:.4g}"


def format_case(summary: SceneSummary) -> str:
    """The comparison table of one scene with its pose, model, mesh checks, mean errors,
    damping and mechanism modes."""
    case = summary.case
    pose, modes = case.pose, case.modes
    refs = [name for name, values in summary.reference.items() if len(values)]
    head = f"{case.scene.name}  ({case.scene.path})"
    mu = "" if pose.mu is None else f"mu = {math.degrees(pose.mu):.3f} deg, "
    lines = [head, "-" * len(head),
             f"pose: theta2 = {math.degrees(pose.crank_angle):.3f} deg, {mu}{pose.branch} branch; "
             f"{summary.family} model; {case.elements_per_link} elements/link, "
             f"{modes.n_dofs} DOFs, {modes.solver} solver, "
             f"max residual {summary.max_residual:.1e}"]
    header = f"{'mode':>4} {'computed Hz':>12}" + "".join(
        f" {r + ' Hz':>9} {'err %':>8}" for r in refs)
    if len(summary.frequencies) and summary.kinds is not None:
        header += "  kind"
    if summary.identity:
        header += f" {'m_x g':>7} {'m_y g':>7}  label"
    lines.append(header)
    for i, f in enumerate(summary.frequencies):
        line = f"{i + 1:>4} {hz_text(float(f)):>12}"
        for r in refs:
            if i < len(summary.reference[r]):
                line += f" {summary.reference[r][i]:>9.1f} {summary.errors[r][i]:>+8.1f}"
            else:  # blank cells keep the columns to the right under their headings
                line += f" {'':>9} {'':>8}"
        if summary.kinds is not None:
            line += f"  {summary.kinds[i]}"
        if summary.identity:
            mass_x, mass_y = 1e3 * summary.identity.effective_mass[i]  # [g] in x and y
            line += f" {mass_x:>7.3f} {mass_y:>7.3f}  {summary.identity.labels[i]}"
        lines.append(line)
    if summary.mean_abs_error_pct:
        lines.append("mean |error|: " + ", ".join(
            f"vs {k} {v:.1f} %" for k, v in sorted(summary.mean_abs_error_pct.items())))
    if len(summary.damping_ratio):
        lines.append(f"damping ratio zeta % ({summary.damping_source}): " + ", ".join(
            f"{100 * z:.3f}" for z in summary.damping_ratio))
    lines += [f"damping: {a.field} = {a.value}, {a.note}"
              for a in case.scene.assumptions if a.field.endswith("loss_factor")]
    if len(summary.mechanism):
        lines.append("rigid-body/mechanism modes (not paired): " + ", ".join(
            f"{f:.3g} Hz" for f in summary.mechanism))
    return "\n".join(lines)


ALTERNATIVE_LABELS = (("orientation", "other orientation"),
                      ("timoshenko", "Timoshenko links (computed, shear and rotary inertia)"),
                      ("shear_source", "shear modulus source"))


def scene_text(summary: SceneSummary) -> str:
    """``format_case`` with the mesh, the warnings, the alternatives and the sensitivity study
    below it: what ``flexlink modes`` prints for one scene."""
    lines = [format_case(summary), summary.mesh.describe()]
    lines += [f"warning: {w}" for w in summary.warnings]
    if summary.alternatives is not None:
        lines += [alternative_line(label, getattr(summary.alternatives, name))
                  for name, label in ALTERNATIVE_LABELS
                  if getattr(summary.alternatives, name) is not None]
    if summary.sensitivity is not None:
        lines.append(format_sensitivity(sensitivity_document(summary.sensitivity)))
    return "\n".join(lines)


def modes_text(summaries: list[SceneSummary]) -> str:
    """What ``flexlink modes`` prints: ``scene_text`` of every scene, each followed by a blank
    line, and with any reference the mean |error| over them all."""
    text = "".join(scene_text(s) + "\n\n" for s in summaries)
    overall = overall_mean_abs_error(summaries)
    if overall:
        text += "overall mean |error|: " + ", ".join(
            f"vs {k} {v:.1f} %" for k, v in sorted(overall.items())) + "\n"
    return text


def comparison_csv(summaries: list[SceneSummary]) -> str:
    """CSV of the comparison: one row per scene and elastic mode, computed [Hz] and every
    reference column [Hz] with its % error (the keys of ``comparison_rows``), and the mode's
    identity flattened: label, strain_<part> and kinetic_<part> fractions, effective mass
    m_eff_x_kg and m_eff_y_kg."""
    rows = [{"scene": s.case.scene.name, **_flat(row)}
            for s in summaries for row in comparison_rows(s)]
    keys = ["scene", "mode", "computed_Hz"]
    for row in rows:
        keys += [k for k in row if k not in keys]
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=keys, lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    return buf.getvalue()


def _flat(row: dict) -> dict:
    """A ``comparison_rows`` row with its nested identity dicts as flat CSV columns."""
    out = {k: v for k, v in row.items() if not isinstance(v, dict)}
    for part, value in row.get("strain_energy", {}).items():
        out[f"strain_{part}"] = value
    for part, value in row.get("kinetic_energy", {}).items():
        out[f"kinetic_{part}"] = value
    for axis, value in row.get("effective_mass_kg", {}).items():
        out[f"m_eff_{axis}_kg"] = value
    return out
