"""``flexlink converge SCENE``: error against run time over mesh levels and solver/mass choices."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import TOLERANCE, json_option, out_option


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
    from flexlink.output.verification.convergence import (convergence_document, convergence_text,
                                                   write_convergence)
    from flexlink.studies.verification.convergence import DEFAULT_TOL, convergence_study
    from ._progress import progress_bar
    from ._written import folder_and_scene, publish

    folder, scene = folder_and_scene(out_dir, scene_path)
    study = convergence_study(scene, n_modes, max_elements, repeats,
                              DEFAULT_TOL if tol is None else tol,
                              progress_bar("converge (rounds over all levels)", as_json, "round"))
    document = convergence_document(study)
    publish(folder / "converge.json", document, write_convergence(study, folder),
            convergence_text(document), as_json)
