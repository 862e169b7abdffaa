"""``flexlink converge SCENE``: error against run time over mesh levels and solver/mass choices."""

from __future__ import annotations

import sys

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import TOLERANCE, dumps, json_option, out_option


@click.command("converge")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("-n", "--modes", "n_modes", default=4, show_default=True,
              type=click.IntRange(1, 50), help="Number of elastic modes to follow.")
@click.option("--max-elements", default=512, show_default=True, type=click.IntRange(4, 8192),
              help="Finest level (elements per link; levels are 1, 2, 4, ...).")
@click.option("--repeats", default=3, show_default=True, type=click.IntRange(1, 50),
              help="Solves per level; the median time is reported.")
@click.option("--tol", default=None, type=TOLERANCE,
              help="Relative frequency tolerance: name the cheapest setting that meets it "
                   "[default: 1e-6].")
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, n_modes, max_elements, repeats, tol, as_json, out_dir):
    """Refine the mesh of SCENE (1, 2, 4, ... elements per link) with every solver and mass
    choice; report frequencies, their discretisation error against a Richardson-extrapolated
    reference, their model error against the scene's measured column, and wall times. Writes
    converge.json, converge.csv and converge.png (error against time) to OUT/<scene>/."""
    from tqdm import tqdm

    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.output.convergence_report import (convergence_csv, convergence_text,
                                                   plot_error_time)
    from flexlink.scene import load_scene
    from flexlink.studies.convergence import DEFAULT_TOL, convergence_study
    from ._written import announce, scene_folders

    [folder] = scene_folders(prepare_out_dir(out_dir), [scene_path])
    scene = load_scene(scene_path)

    def progress(rounds):
        return tqdm(rounds, desc="converge (rounds over all levels)", unit="round",
                    file=sys.stderr, disable=as_json or not sys.stderr.isatty())

    study = convergence_study(scene, n_modes, max_elements, repeats,
                              DEFAULT_TOL if tol is None else tol, progress)
    paths = [folder / "converge.json", folder / "converge.csv", folder / "converge.png"]
    document = {**study.document, "files": [str(p) for p in paths]}
    write_atomic(paths[0], dumps(document))
    write_atomic(paths[1], convergence_csv(document))
    plot_error_time(study.levels, study.reference, paths[2],
                    title=f"{scene.name}: error against run time")
    if as_json:
        click.echo(dumps(document))
        return
    click.echo(convergence_text(document))
    announce(paths, as_json)
