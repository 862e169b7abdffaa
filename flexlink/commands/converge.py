"""``flexlink converge SCENE``: error against run time over mesh levels and solver/mass choices."""

from __future__ import annotations

import sys

import click

from flexlink.commands._options import dumps, json_option, out_option


@click.command("converge")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("-n", "--modes", "n_modes", default=4, show_default=True,
              type=click.IntRange(1, 50), help="Number of elastic modes to follow.")
@click.option("--max-elements", default=512, show_default=True, type=click.IntRange(4, 8192),
              help="Finest level (elements per link; levels are 1, 2, 4, ...).")
@click.option("--repeats", default=3, show_default=True, type=click.IntRange(1, 50),
              help="Solves per level; the median time is reported.")
@click.option("--tol", default=None, type=click.FloatRange(0, 1, min_open=True),
              help="Relative frequency tolerance: name the cheapest setting that meets it "
                   "[default: 1e-6].")
@json_option
@out_option
def command(scene_path, n_modes, max_elements, repeats, tol, as_json, out_dir):
    """Refine the mesh of SCENE (1, 2, 4, ... elements per link) with every solver and mass
    choice; report frequencies, their discretisation error against a Richardson-extrapolated
    reference, their model error against the scene's measured column, and wall times. Writes
    converge.json, converge.csv and converge.png (error against time)."""
    from tqdm import tqdm

    from flexlink.studies import convergence as cv
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.scene.load import load_scene

    tol = cv.DEFAULT_TOL if tol is None else tol
    out = prepare_out_dir(out_dir)
    scene = load_scene(scene_path)
    levels_all = cv.mesh_levels(max_elements)
    work = [(c, e) for c in cv.CHOICES for e in levels_all
            if c.method != "dense" or cv.runs_dense(e, scene)]
    def progress(rounds):
        return tqdm(rounds, desc="converge (rounds over all levels)", unit="round",
                    file=sys.stderr, disable=as_json or not sys.stderr.isatty())

    refused: list = []
    levels = cv.run_levels(scene, work, n_modes, repeats, progress, refused)
    main_choice = cv.CHOICES[0]
    main = [l for l in levels if l.choice == main_choice]
    extrapolation = cv.richardson(main)
    ref = extrapolation.reference
    errors = cv.relative_errors(levels, ref)
    best = cv.cheapest(levels, ref, tol)
    measured = _measured(scene)

    rows = []
    for level, err in zip(levels, errors):
        row = {"choice": level.choice.label, "method": level.choice.method,
               "mass": level.choice.mass, "refined": level.choice.refine,
               "elements_per_link": level.elements, "dofs": level.dofs,
               "assembly_s": level.assembly_s, "solve_s": level.solve_s, "runs": level.runs,
               "frequencies_Hz": level.frequencies, "relative_error": err,
               "max_relative_error": float(err.max())}
        if measured is not None:
            name, values = measured
            k = min(len(values), len(level.frequencies))
            row[f"error_vs_{name}_pct"] = [100 * (level.frequencies[i] - values[i]) / values[i]
                                           for i in range(k)]
        rows.append(row)
    document = {
        "command": "converge", "scene": scene.name, "file": scene.path, "modes": n_modes,
        "repeats": repeats,
        "reference": {"choice": main_choice.label, "frequencies_Hz": ref,
                      "order_used": extrapolation.order, "observed_order": extrapolation.observed,
                      "levels": extrapolation.elements, "asymptotic": extrapolation.asymptotic,
                      "second_step_change": extrapolation.uncertainty},
        "model_error": _model_error(ref, measured),
        "tolerance": tol,
        "cheapest": None if best is None else {
            "choice": best.choice.label, "elements_per_link": best.elements, "dofs": best.dofs,
            "seconds": best.total_s,
            "max_relative_error": float(errors[levels.index(best)].max())},
        "levels": rows,
        "refused": [{"choice": c.label, "elements_per_link": e, "reason": msg}
                    for c, e, msg in refused],
    }
    png = out / "converge.png"
    cv.plot_error_time(levels, ref, png, title=f"{scene.name}: error against run time")
    write_atomic(out / "converge.json", dumps(document))
    write_atomic(out / "converge.csv", _csv(rows, n_modes))
    if as_json:
        click.echo(dumps(document))
        return
    click.echo(_text(scene, document, main_choice.label, n_modes))
    for r in document["refused"]:
        click.echo(f"refused by the solver: {r['choice']} at {r['elements_per_link']} "
                   f"elements/link: {r['reason']}")
    click.echo(f"written: {out / 'converge.json'}, {out / 'converge.csv'}, {png}")


def _dense_note():
    from flexlink.analysis.solve import DENSE_LIMIT

    return f"{DENSE_LIMIT} DOFs"


def _measured(scene):
    """The scene's measured column ("Ex") if it has one, else its first column, or None."""
    if scene.reference is None or not scene.reference.columns:
        return None
    columns = scene.reference.columns
    name = "Ex" if "Ex" in columns else next(iter(columns))
    return name, columns[name]


def _model_error(reference, measured):
    if measured is None:
        return None
    name, values = measured
    k = min(len(values), len(reference))
    return {"column": name, "measured_Hz": list(values[:k]),
            "error_pct": [100 * (reference[i] - values[i]) / values[i] for i in range(k)]}


def _csv(rows, n_modes):
    head = ["choice", "elements_per_link", "dofs", "assembly_s", "solve_s"]
    head += [f"f{i + 1}_Hz" for i in range(n_modes)] + [f"err{i + 1}" for i in range(n_modes)]
    lines = [",".join(head)]
    for r in rows:
        values = [r["choice"], r["elements_per_link"], r["dofs"], f"{r['assembly_s']:.6g}",
                  f"{r['solve_s']:.6g}"]
        values += [f"{f:.15g}" for f in r["frequencies_Hz"]] + [f"{e:.3e}" for e in r["relative_error"]]
        lines.append(",".join(map(str, values)))
    return "\n".join(lines) + "\n"


def _text(scene, doc, main_label, n_modes):
    ref = doc["reference"]
    observed = " ".join(f"{p:.2f}" for p in ref["observed_order"])
    lines = [f"{scene.name} ({scene.path}): mesh convergence of {n_modes} elastic modes, "
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
                  f"dense stops at {_dense_note()}):",
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
    return "\n".join(lines)
