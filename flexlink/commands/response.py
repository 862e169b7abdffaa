"""``flexlink response SCENE --speed ... | --speeds LOW:HIGH``: the steady elastic response."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import (json_option, out_option, parse_speeds,
                                       periodic_basis_options, refuse_unless)


@click.command("response")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("--speed", help="One crank speed, e.g. '600 rev/min' (default: the scene's).")
@click.option("--speeds", help="A sweep of crank speeds instead, e.g. '60:3000 rev/min'.")
@click.option("--count", default=100, show_default=True, type=click.IntRange(2, 100000),
              help="Speeds over the --speeds range.")
@periodic_basis_options
@click.option("--at", "points", multiple=True, metavar="LINK:DISTANCE",
              help="A strain point, e.g. 'coupler:60 mm' from its start joint (repeatable; "
                   "default: each link's midspan).")
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, speed, speeds, count, n_modes, damping_ratio, points, as_json, out_dir):
    """Steady bending strain and deflection of SCENE's links over one crank turn at a speed,
    or their peaks against speed. Writes response.png, .csv and .json to OUT/<scene>/."""
    import numpy as np

    from flexlink.errors import InputError
    from flexlink.output.running.steady_response import response_lines, write_response
    from flexlink.studies.running import steady_response as study
    from flexlink.studies.cycle.bands import _check_speeds
    from flexlink.studies.running.modes_at_speed import crank_speed
    from flexlink.units import parse_quantity
    from ._progress import progress_bar
    from ._written import folder_and_scene, publish

    if speed is not None and speeds is not None:
        raise InputError("give --speed or --speeds, not both", field="--speeds")
    refuse_unless("count", "--speeds", speeds is not None)
    sweep = None if speeds is None else np.linspace(*_check_speeds(parse_speeds(speeds)), count)
    one = speed and parse_quantity(speed, "angular speed", source="command line", field="--speed")
    at = tuple(study.parse_point(p) for p in points) or None
    folder, scene = folder_and_scene(out_dir, scene_path)
    model = study.forced_model(scene, n_modes, damping_ratio=damping_ratio, points=at)
    if sweep is None:
        result = study.steady_response(model, crank_speed(scene, one))
    else:
        result = study.response_sweep(model, sweep, progress=progress_bar("speeds", as_json))
    document, files = write_response(result, model, folder, scene.name)
    publish(folder / "response.json", document, files, "\n".join(response_lines(document)),
            as_json)
