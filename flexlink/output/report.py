"""Comparison of computed frequencies with reference columns (measured Ex, published FE), as
plain rows, a human-readable table, JSON-ready dicts and CSV text. Pairing is by mode order of
the elastic modes only; rigid-body/mechanism modes are listed apart, never paired."""

from __future__ import annotations

import csv
import io
import math

import numpy as np

from flexlink.analysis.damping import damping_source, modal_damping_ratios
from flexlink.analysis.identity import DIRECTIONS, mode_identity, participating_mass, total_mass
from flexlink.analysis.modal import CaseResult
from flexlink.units import percent_error


def comparison_rows(result: CaseResult, n_modes: int, computed=None, kinds=None) -> list[dict]:
    """One dict per elastic mode: mode, computed [Hz], and for each reference column its value
    [Hz] and % error (computed vs reference); for the planar model's own modes also its
    identity (``identity.mode_identity``: label, energy fractions, effective masses)."""
    identity = [{}] * n_modes
    if computed is None:
        computed = result.elastic_frequencies(n_modes)
        identity = mode_identity(result.model, result.modes.shapes[:, result.modes.elastic[:n_modes]])
    columns = result.scene.reference.columns if result.scene.reference else {}
    rows = []
    for i, f in enumerate(computed):
        row = {"mode": i + 1, "computed_Hz": float(f)}
        if kinds is not None:
            row["kind"] = kinds[i]
        for name, values in columns.items():
            if i < len(values):
                row[f"{name}_Hz"] = values[i]
                row[f"error_vs_{name}_pct"] = percent_error(float(f), values[i])
        rows.append({**row, **identity[i]})
    return rows


def mean_abs_errors(rows: list[dict]) -> dict[str, float]:
    """Mean absolute % error per reference column over the rows."""
    out = {}
    for key in {k for r in rows for k in r if k.startswith("error_vs_")}:
        values = [abs(r[key]) for r in rows if key in r]
        out[key.removeprefix("error_vs_").removesuffix("_pct")] = float(np.mean(values))
    return out


def linkage_summary(scene) -> dict:
    """Lengths [m] of the four-bar (with its Grashof class), or of each beam link."""
    fb = scene.four_bar
    if fb is not None:
        return {"ground_m": fb.ground, "crank_m": fb.crank, "coupler_m": fb.coupler,
                "rocker_m": fb.rocker, "grashof": fb.grashof_class()}
    return {"bodies": [b.name for b in scene.linkage.bodies]}


def case_summary(result: CaseResult, n_modes: int, family: str = "planar", computed=None,
                 kinds=None) -> dict:
    """JSON-ready summary of one case. ``computed``/``kinds``: the frequencies [Hz] and mode
    kinds of a model family other than the planar one of ``result`` (see ``families.py``)."""
    scene, pose, modes = result.scene, result.pose, result.modes
    rows = comparison_rows(result, n_modes, computed, kinds)
    mechanism = [float(f) for f, k in zip(modes.frequencies, modes.kinds) if k != "elastic"]
    return {
        "scene": scene.name,
        "file": scene.path,
        "family": family,
        "linkage": linkage_summary(scene),
        "pose": {"theta2_deg": math.degrees(pose.theta2),
                 "mu_deg": None if pose.mu is None else math.degrees(pose.mu),
                 "branch": pose.branch,
                 "joints_m": {k: list(v) for k, v in pose.joints.items()}},
        "elements_per_link": result.elements_per_link,
        "dofs": modes.n_dofs,
        "solver": modes.solver,
        "modes": rows,
        # per elastic mode: declared in [damping], else from the links' loss factors [-]
        "damping_ratio": [] if computed is not None else [float(z) for z in modal_damping_ratios(
            result.model, modes.shapes[:, modes.elastic[:n_modes]],
            2 * math.pi * modes.elastic_frequencies[:n_modes], scene.loss_factors,
            scene.options.damping)],
        "damping_source": damping_source(scene.options.damping),
        "mechanism_modes_Hz": mechanism,
        "mass_kg": {"total": total_mass(result.model),
                    "participating": dict(zip(DIRECTIONS, map(float, participating_mass(result.model))))},
        "mean_abs_error_pct": mean_abs_errors(rows),
        "max_residual": float(np.nanmax(modes.residuals[modes.elastic])),
        "max_backward_error": float(modes.backward_errors.max()),
        "orthogonality_error": modes.orthogonality_error,
        "seconds": result.seconds,
        "assumptions": [{"field": a.field, "value": a.value, "note": a.note}
                        for a in scene.assumptions],
        "reference_source": scene.reference.source if scene.reference else None,
    }


def overall_mean_abs(summaries: list[dict]) -> dict[str, float]:
    pooled: dict[str, list[float]] = {}
    for s in summaries:
        for row in s["modes"]:
            for key, value in row.items():
                if key.startswith("error_vs_"):
                    pooled.setdefault(key[9:-4], []).append(abs(value))
    return {k: float(np.mean(v)) for k, v in pooled.items()}


def hz_text(frequency: float) -> str:
    """A frequency [Hz] for the text table: two decimals from 1 Hz up, four significant digits
    below (a soft scene's modes at mHz must not all read 0.00)."""
    return f"{frequency:.2f}" if abs(frequency) >= 1.0 else f"{frequency:.4g}"


def format_case(summary: dict) -> str:
    rows = summary["modes"]
    refs = [k[:-3] for k in (rows[0] if rows else {}) if k.endswith("_Hz") and k != "computed_Hz"]
    head = f"{summary['scene']}  ({summary['file']})"
    pose = summary["pose"]
    lines = [head, "-" * len(head),
             f"pose: theta2 = {pose['theta2_deg']:.3f} deg, "
             + ("" if pose["mu_deg"] is None else f"mu = {pose['mu_deg']:.3f} deg, ") +
             f"{pose['branch']} branch; {summary.get('family', 'planar')} model; "
             f"{summary['elements_per_link']} elements/link, "
             f"{summary['dofs']} DOFs, {summary['solver']} solver, "
             f"max residual {summary['max_residual']:.1e}"]
    header = f"{'mode':>4} {'computed Hz':>12}" + "".join(f" {r + ' Hz':>9} {'err %':>8}" for r in refs)
    if rows and "kind" in rows[0]:
        header += "  kind"
    if rows and "label" in rows[0]:
        header += f" {'m_x g':>7} {'m_y g':>7}  label"
    lines.append(header)
    for row in rows:
        line = f"{row['mode']:>4} {hz_text(row['computed_Hz']):>12}"
        for r in refs:
            if f"{r}_Hz" in row:
                line += f" {row[f'{r}_Hz']:>9.1f} {row[f'error_vs_{r}_pct']:>+8.1f}"
        if "kind" in row:
            line += f"  {row['kind']}"
        if "label" in row:
            mass = row["effective_mass_kg"]
            line += f" {1e3 * mass['x']:>7.3f} {1e3 * mass['y']:>7.3f}  {row['label']}"
        lines.append(line)
    if summary["mean_abs_error_pct"]:
        lines.append("mean |error|: " + ", ".join(
            f"vs {k} {v:.1f} %" for k, v in sorted(summary["mean_abs_error_pct"].items())))
    if summary.get("damping_ratio"):
        lines.append(f"damping ratio zeta % ({summary['damping_source']}): " + ", ".join(
            f"{100 * z:.3f}" for z in summary["damping_ratio"]))
    lines += [f"damping: {a['field']} = {a['value']}, {a['note']}"
              for a in summary["assumptions"] if a["field"].endswith("loss_factor")]
    if summary["mechanism_modes_Hz"]:
        lines.append("rigid-body/mechanism modes (not paired): " + ", ".join(
            f"{f:.3g} Hz" for f in summary["mechanism_modes_Hz"]))
    return "\n".join(lines)


def comparison_csv(summaries: list[dict]) -> str:
    """CSV of the comparison: one row per scene and elastic mode, computed [Hz] and every
    reference column [Hz] with its % error (the keys of ``comparison_rows``), and the mode's
    identity flattened: label, strain_<part> and kinetic_<part> fractions, effective mass
    m_eff_x_kg and m_eff_y_kg."""
    rows = [{"scene": s["scene"], **_flat(row)} for s in summaries for row in s["modes"]]
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
