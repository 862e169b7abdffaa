"""``flexlink modes SCENE...``: natural frequencies at the scene's pose vs its reference table."""

from __future__ import annotations

import logging

import click

from flexlink.cli import dumps, json_option, out_option


@click.command("modes")
@click.argument("scenes", nargs=-1, required=True, type=click.Path())
@click.option("-n", "--modes", "n_modes", default=4, show_default=True,
              type=click.IntRange(1, 200), help="Number of elastic modes to report.")
@click.option("-e", "--elements", default=None, type=click.IntRange(1, 100000),
              help="Elements per link (default: the scene's mesh.elements_per_link if it pins "
                   "one, else the coarsest mesh meeting --tol).")
@click.option("--tol", default=None, type=click.FloatRange(0, 1, min_open=True),
              help="Relative frequency tolerance of the default mesh: the coarsest of 8, 16, "
                   "32, ... elements/link whose Richardson error estimate meets it "
                   "[default: 1e-6].")
@click.option("--method", type=click.Choice(["auto", "dense", "sparse"]), default="auto",
              show_default=True, help="Eigen solver.")
@json_option
@out_option
def command(scenes, n_modes, elements, method, tol, as_json, out_dir):
    """Natural frequencies of each SCENE (a scene file or a folder of them) at its pose,
    compared with the scene's reference columns (measured Ex, published FE)."""
    from flexlink.analysis.mesh import DEFAULT_TOL, choose_mesh
    from flexlink.analysis.modal import analyze
    from flexlink.analysis.families import elastic_modes, scene_family
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.output.report import case_summary, csv_text, format_case, overall_mean_abs
    from flexlink.scene.load import load_scene, scene_files

    # analysis warnings come back in result.warnings and are printed with their case below;
    # logging them as well would show each one twice
    logging.getLogger("flexlink.analysis.modal").setLevel(logging.ERROR)
    out = prepare_out_dir(out_dir)
    files = scene_files(scenes)
    summaries, meshes = [], []
    for path in files:
        scene = load_scene(path)
        mesh = choose_mesh(scene, n_modes, elements, DEFAULT_TOL if tol is None else tol)
        result = analyze(scene, n_modes, mesh.elements, method)
        family = scene_family(scene)
        other = {} if family == "planar" else dict(
            zip(("computed", "kinds"), elastic_modes(scene, n_modes, mesh.elements, method)))
        summaries.append({**case_summary(result, n_modes, family, **other),
                          "mesh": mesh.as_dict(), "warnings": list(result.warnings)})
        meshes.append(mesh)
    document = {"command": "modes", "cases": summaries,
                "overall_mean_abs_error_pct": overall_mean_abs(summaries)}
    write_atomic(out / "modes.json", dumps(document))
    write_atomic(out / "modes.csv", csv_text(summaries))
    if as_json:
        click.echo(dumps(document))
        return
    for s, mesh in zip(summaries, meshes):
        click.echo(format_case(s) + "\n" + mesh.describe() + "".join(
            f"\nwarning: {w}" for w in s["warnings"]) + "\n")
    overall = document["overall_mean_abs_error_pct"]
    if overall:
        click.echo("overall mean |error|: " + ", ".join(
            f"vs {k} {v:.1f} %" for k, v in sorted(overall.items())))
    click.echo(f"written: {out / 'modes.json'}, {out / 'modes.csv'}")

