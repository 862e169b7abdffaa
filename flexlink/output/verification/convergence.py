"""The convergence study (``studies.verification.convergence.ConvergenceStudy``) as the JSON document of
`flexlink converge`, as CSV, as a human-readable report and as the error-against-time plot."""

from __future__ import annotations

import numpy as np

from flexlink.analysis.solve import DENSE_LIMIT
from flexlink.fileio import write_atomic
from flexlink.output.figures import write_figure
from flexlink.studies.verification.convergence import (REFERENCE_CHOICE, ConvergenceStudy, Level,
                                          relative_errors)


def convergence_document(study: ConvergenceStudy) -> dict:
    """The JSON document of `flexlink converge` (without its ``files``): the Richardson
    reference [Hz] with its orders, the model error against the measured column [%], the
    cheapest level meeting the tolerance, and every level's times [s], frequencies [Hz] and
    relative errors."""
    ext, best, measured = study.extrapolation, study.cheapest, study.measured
    rows = []
    for level, err in zip(study.levels, study.errors):
        row = {"choice": level.choice.label, "method": level.choice.method,
               "mass": level.choice.mass, "refined": level.choice.refine,
               "elements_per_link": level.elements, "dofs": level.dofs,
               "assembly_s": level.assembly_s, "solve_s": level.solve_s, "runs": level.runs,
               "frequencies_Hz": level.frequencies, "relative_error": err,
               "max_relative_error": float(err.max())}
        if measured is not None:
            row[f"error_vs_{measured[0]}_pct"] = study.measured_pct(level.frequencies)
        rows.append(row)
    return {
        "command": "converge", "scene": study.scene, "file": study.file, "modes": study.n_modes,
        "repeats": study.repeats,
        "reference": {"choice": REFERENCE_CHOICE.label, "frequencies_Hz": ext.reference,
                      "order_used": ext.order, "observed_order": ext.observed,
                      "levels": ext.elements, "asymptotic": ext.asymptotic,
                      "second_step_change": ext.uncertainty},
        "model_error": None if measured is None else {
            "column": measured[0], "measured_Hz": list(measured[1][:len(ext.reference)]),
            "error_pct": study.measured_pct(ext.reference)},
        "tolerance": study.tol,
        "cheapest": None if best is None else {
            "choice": best.choice.label, "elements_per_link": best.elements, "dofs": best.dofs,
            "seconds": best.total_s,
            "max_relative_error": float(study.errors[study.levels.index(best)].max())},
        "dense_limit_dofs": DENSE_LIMIT,
        "levels": rows,
        "refused": [{"choice": c.label, "elements_per_link": e, "reason": msg}
                    for c, e, msg in study.refused],
    }


def convergence_csv(study: ConvergenceStudy) -> str:
    """One row per level and choice: elements per link, DOFs, median times [s], frequencies
    [Hz] and relative errors against the Richardson reference."""
    head = ["choice", "elements_per_link", "dofs", "assembly_s", "solve_s"]
    head += [f"f{i + 1}_Hz" for i in range(study.n_modes)]
    head += [f"err{i + 1}" for i in range(study.n_modes)]
    lines = [",".join(head)]
    for level, err in zip(study.levels, study.errors):
        values = [level.choice.label, level.elements, level.dofs, f"{level.assembly_s:.6g}",
                  f"{level.solve_s:.6g}"]
        values += [f"{f:.15g}" for f in level.frequencies]
        values += [f"{e:.3e}" for e in err]
        lines.append(",".join(map(str, values)))
    return "\n".join(lines) + "\n"


def write_convergence(study: ConvergenceStudy, folder) -> list:
    """converge.csv and converge.png (error against run time) in ``folder``, each written
    atomically; returns their paths."""
    paths = [folder / "converge.csv", folder / "converge.png"]
    write_atomic(paths[0], convergence_csv(study))
    plot_error_time(list(study.levels), study.reference, paths[1],
                    title=f"{study.scene}: error against run time")
    return paths


def convergence_text(doc: dict) -> str:
    """The report printed by ``flexlink converge``: the main choice's levels, the model error,
    every choice's error against time, and the cheapest setting meeting the tolerance."""
    ref, n_modes, main_label = doc["reference"], doc["modes"], doc["reference"]["choice"]
    observed = " ".join(f"{p:.2f}" for p in ref["observed_order"])
    lines = [f"{doc['scene']} ({doc['file']}): mesh convergence of {n_modes} elastic modes, "
             f"median of {doc['repeats']} runs per level",
             f"Richardson reference: {main_label} at {'/'.join(map(str, ref['levels']))} "
             f"elements/link; order used p = {ref['order_used']} (P1 axial element), then "
             f"{ref['order_used'] + 2} (Hermite bending), which moved it by at most "
             f"{max(ref['second_step_change']):.0e}",
             f"observed order {observed} "
             f"({'asymptotic' if ref['asymptotic'] else 'NOT in the asymptotic range'})",
             "", f"Discretisation error (relative, vs the Richardson reference), {main_label}:"]
    head = f"{'el/link':>7} {'DOFs':>6} {'asm ms':>7} {'eig ms':>7}"
    head += "".join(f" {f'f{i + 1} Hz':>15}" for i in range(n_modes))
    head += "".join(f" {f'err{i + 1}':>8}" for i in range(n_modes))
    lines.append(head)
    for r in doc["levels"]:
        if r["choice"] != main_label:
            continue
        line = (f"{r['elements_per_link']:>7} {r['dofs']:>6} {1e3 * r['assembly_s']:>7.1f} "
                f"{1e3 * r['solve_s']:>7.1f}")
        line += "".join(f" {f:>15.9f}" for f in r["frequencies_Hz"])
        line += "".join(f" {e:>8.1e}" for e in r["relative_error"])
        lines.append(line)
    model = doc["model_error"]
    if model:
        lines += ["", f"Model error (Richardson reference vs measured {model['column']}; "
                      "does not shrink with the mesh):",
                  f"{'mode':>4} {'reference Hz':>14} {model['column'] + ' Hz':>8} {'err %':>9}"]
        for i, (m, e) in enumerate(zip(model["measured_Hz"], model["error_pct"])):
            lines.append(f"{i + 1:>4} {ref['frequencies_Hz'][i]:>14.6f} {m:>8.1f} {e:>+9.1f}")
    lines += ["", "Error against run time, every choice (time = median assembly + eigen solve; "
                  f"dense stops at {doc['dense_limit_dofs']} DOFs):",
              f"{'choice':<28} {'el/link':>7} {'DOFs':>6} {'time ms':>9} {'max rel err':>11}"]
    for r in doc["levels"]:
        lines.append(f"{r['choice']:<28} {r['elements_per_link']:>7} {r['dofs']:>6} "
                     f"{1e3 * (r['assembly_s'] + r['solve_s']):>9.2f} "
                     f"{r['max_relative_error']:>11.1e}")
    best = doc["cheapest"]
    lines.append("")
    if best:
        lines.append(f"--tol {doc['tolerance']:g}: cheapest setting meeting it is {best['choice']} "
                     f"at {best['elements_per_link']} elements/link ({best['dofs']} DOFs, "
                     f"{1e3 * best['seconds']:.1f} ms, max relative error "
                     f"{best['max_relative_error']:.1e})")
    else:
        lines.append(f"--tol {doc['tolerance']:g}: no level meets it; refine further "
                     "(--max-elements)")
    for r in doc["refused"]:
        lines.append(f"refused by the solver: {r['choice']} at {r['elements_per_link']} "
                     f"elements/link: {r['reason']}")
    return "\n".join(lines)


def plot_error_time(levels: list[Level], reference: np.ndarray, path, title: str = "") -> None:
    """Log-log PNG of max relative discretisation error against median solve time, one line
    per choice."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    errors = relative_errors(levels, reference).max(axis=1)
    fig, ax = plt.subplots(figsize=(7, 5))
    for choice in dict.fromkeys(l.choice for l in levels):
        pick = [i for i, l in enumerate(levels) if l.choice == choice]
        t = [levels[i].total_s for i in pick]
        e = np.maximum(errors[pick], 1e-16)  # an exact match would vanish from a log axis
        ax.loglog(t, e, "o-", label=choice.label)
        for i in pick[::2]:
            ax.annotate(str(levels[i].elements), (levels[i].total_s, max(errors[i], 1e-16)),
                        fontsize=7, textcoords="offset points", xytext=(3, 3))
    ax.set_xlabel("median wall time per solve, assembly + eigen solve [s]")
    ax.set_ylabel("max relative frequency error vs Richardson reference")
    ax.set_title(title or "error against run time (labels: elements per link)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    write_figure(fig, path)
