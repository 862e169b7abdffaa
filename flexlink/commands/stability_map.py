"""``flexlink stability-map SCENE --speeds "0:3000 rev/min"``: parametric (Floquet) stability."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import (json_option, odd_count, out_option, parse_speeds,
                                       periodic_basis_options, scheduler_option,
                                       speeds_option)


@click.command("stability-map")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@speeds_option()
@click.option("--count", default=300, show_default=True, type=click.IntRange(2, 100000),
              help="Speeds over the range.")
@periodic_basis_options
@click.option("--poses", default=37, show_default=True, type=click.IntRange(3, 1001),
              callback=odd_count, help="Crank angles the periodic matrices are sampled at (odd).")
@click.option("--basis", "basis_size", default=None, type=click.IntRange(1, 10000),
              help="Reduced basis size; default: the smallest whose lowest MODES frequencies "
                   "match the full model's at every pose to --basis-tolerance.")
@click.option("--basis-tolerance", default=1e-3, show_default=True,
              type=click.FloatRange(0.0, 1.0, min_open=True),
              help="Relative frequency excess the basis may have at any pose.")
@click.option("--integrator", default="adiabatic", show_default=True,
              type=click.Choice(["adiabatic", "magnus"]),
              help="Monodromy steps: adiabatic, or magnus (as accurate, many times slower "
                   "below a few thousand rev/min; docs/critical-speeds.md).")
@scheduler_option("the speeds in chunks")
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, speeds, count, n_modes, damping_ratio, poses, basis_size,
            basis_tolerance, integrator, scheduler, as_json, out_dir):
    """Largest Floquet multiplier of SCENE's periodic elastic equations against crank speed
    and the unstable ranges, labelled by the nearest parametric resonance. Writes
    stability-map.png, .csv and .json to OUT/<scene>/."""
    import numpy as np

    from flexlink.parallel import use_scheduler
    from flexlink.output.running.stability_map import stability_document, stability_lines, write_stability
    from flexlink.studies.cycle.bands import _check_speeds
    from flexlink.studies.running.stability_map import Integrator, periodic_model, stability_map
    from ._progress import progress_bar
    from ._written import folder_and_scene, publish

    low, high = _check_speeds(parse_speeds(speeds))
    folder, scene = folder_and_scene(out_dir, scene_path)
    model = periodic_model(scene, n_modes, poses, damping_ratio, basis_size=basis_size,
                           tolerance=basis_tolerance)
    with use_scheduler(scheduler):
        result = stability_map(model, np.linspace(low, high, count),
                               show_progress=progress_bar("speeds", as_json) is not None,
                               integrator=Integrator(integrator))
    document = stability_document(scene.name, result, model)
    publish(folder / "stability-map.json", document, write_stability(result, model, folder,
                                                                     scene.name),
            "\n".join(stability_lines(document)), as_json)
