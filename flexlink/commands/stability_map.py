"""``flexlink stability-map SCENE --speeds "0:3000 rev/min"``: parametric (Floquet) stability."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import (EnumChoice, json_option, out_option,
                                       periodic_basis_options, scheduler_option)
from flexlink.commands._speeds import speeds_option
from flexlink.analysis.periodic import Integrator


@click.command("stability-map")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@speeds_option()
@click.option("--count", default=300, show_default=True, type=click.IntRange(2, 100000),
              help="Speeds over the range.")
@periodic_basis_options
@click.option("--basis", "basis_size", default=None, type=click.IntRange(1, 10000),
              help="Reduced basis size; default: the smallest whose lowest MODES frequencies "
                   "match the full model's at every pose to --basis-tolerance.")
@click.option("--basis-tolerance", default=1e-3, show_default=True,
              type=click.FloatRange(0.0, 1.0, min_open=True),
              help="Relative frequency excess the basis may have at any pose.")
@click.option("--integrator", default=Integrator.ADIABATIC.value, show_default=True,
              type=EnumChoice(Integrator),
              help="Monodromy steps: adiabatic; magnus (as accurate, many times slower "
                   "below a few thousand rev/min); midpoint (the fallback's steps where the "
                   "basis is stiff; docs/critical-speeds.md).")
@scheduler_option("the speeds in chunks")
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, speeds, count, n_modes, damping_ratio, elements, tol, poses, basis_size,
            basis_tolerance, integrator, scheduler, as_json, out_dir):
    """Largest Floquet multiplier of SCENE's periodic elastic equations against crank speed
    and the unstable ranges, labelled by the nearest parametric resonance. Writes
    stability-map.png, .csv and .json to OUT/<scene>/."""
    import numpy as np

    from flexlink.analysis.periodic import periodic_model
    from flexlink.output.running.stability_map import stability_document, stability_lines, write_stability
    from flexlink.parallel import use_scheduler
    from flexlink.studies.running.stability_map import stability_map
    from ._options import periodic_mesh
    from ._progress import progress_bar, step_progress
    from ._speeds import parse_speeds
    from ._written import finite_document, folder_and_scene, publish

    low, high = parse_speeds(speeds)
    folder, scene = folder_and_scene(out_dir, scene_path)
    elements_per_link, mesh = periodic_mesh(scene, n_modes, elements, tol)
    model = periodic_model(scene, n_modes, poses, damping_ratio, elements_per_link,
                           basis_size=basis_size, tolerance=basis_tolerance)
    with use_scheduler(scheduler), step_progress("steps within a speed", as_json) as on_steps:
        result = stability_map(model, np.linspace(low, high, count),
                               show_progress=progress_bar("speeds", as_json) is not None,
                               integrator=integrator, on_steps=on_steps)
    document = finite_document(stability_document(scene.name, result, model, mesh))
    publish(folder / "stability-map.json", document, write_stability(result, model, folder,
                                                                     scene.name),
            "\n".join(stability_lines(document)), as_json)
