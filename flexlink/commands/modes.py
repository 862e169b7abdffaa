"""``flexlink modes SCENE...``: natural frequencies at the scene's pose vs its reference table."""

from __future__ import annotations

import click

from ..cli import dumps, json_option, out_option


@click.command("modes")
@click.argument("scenes", nargs=-1, required=True, type=click.Path())
@click.option("-n", "--modes", "n_modes", default=4, show_default=True,
              type=click.IntRange(1, 200), help="Number of elastic modes to report.")
@click.option("-e", "--elements", default=None, type=click.IntRange(1, 100000),
              help="Elements per link (default: the scene's mesh.elements_per_link).")
@click.option("--method", type=click.Choice(["auto", "dense", "sparse"]), default="auto",
              show_default=True, help="Eigen solver.")
@json_option
@out_option
def command(scenes, n_modes, elements, method, as_json, out_dir):
    """Natural frequencies of each SCENE (a scene file or a folder of them) at its pose,
    compared with the scene's reference columns (measured Ex, published FE)."""
    from ..analysis import analyze
    from ..fileio import prepare_out_dir, write_atomic
    from ..report import case_summary, csv_text, format_case, overall_mean_abs
    from ..scene import load_scene, scene_files

    out = prepare_out_dir(out_dir)
    files = scene_files(scenes)
    summaries = []
    for path in files:
        scene = load_scene(path)
        summaries.append(case_summary(analyze(scene, n_modes, elements, method), n_modes))
    document = {"command": "modes", "cases": summaries,
                "overall_mean_abs_error_pct": overall_mean_abs(summaries)}
    write_atomic(out / "modes.json", dumps(document))
    write_atomic(out / "modes.csv", csv_text(summaries))
    if as_json:
        click.echo(dumps(document))
        return
    for s in summaries:
        click.echo(format_case(s) + "\n")
    overall = document["overall_mean_abs_error_pct"]
    if overall:
        click.echo("overall mean |error|: " + ", ".join(
            f"vs {k} {v:.1f} %" for k, v in sorted(overall.items())))
    click.echo(f"written: {out / 'modes.json'}, {out / 'modes.csv'}")
