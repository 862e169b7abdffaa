"""``flexlink response SCENE --speed ... | --speeds LOW:HIGH``: the steady elastic response."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import (json_option, out_option, periodic_basis_options,
                                       refuse_unless)
from flexlink.commands._speeds import speed_option, speeds_option


@click.command("response")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@speed_option("One crank speed, e.g. '600 rev/min' (default: the scene's).")
@speeds_option("A sweep of crank speeds instead, e.g. '60:3000 rev/min'.", required=False)
@click.option("--count", default=100, show_default=True, type=click.IntRange(2, 100000),
              help="Speeds over the --speeds range.")
@periodic_basis_options
@click.option("--at", "points", multiple=True, metavar="LINK:DISTANCE",
              help="A strain point, e.g. 'coupler:60 mm' from its start joint (repeatable; "
                   "default: each link's midspan).")
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, speed, speeds, count, n_modes, damping_ratio, elements, tol, poses,
            points, as_json, out_dir):
    """Steady bending strain and deflection of SCENE's links over one crank turn at a speed,
    or their peaks against speed. Writes response.png, .csv and .json to OUT/<scene>/."""
    from flexlink.output.running.steady_response import response_lines, write_response
    from flexlink.studies.running import steady_response as study
    from ._options import parse_point, periodic_mesh
    from ._progress import progress_bar, step_progress
    from ._speeds import operating_speed, speed_or_sweep
    from ._written import folder_and_scene, publish

    one, sweep = speed_or_sweep(speed, speeds, count)
    refuse_unless("count", "--speeds", speeds is not None)
    at = tuple(parse_point(p) for p in points) or None
    folder, scene = folder_and_scene(out_dir, scene_path)
    if at is not None:
        study.check_points(scene, at, field="--at")
    if sweep is None:
        one = operating_speed(scene, one)[0]
    elements_per_link, mesh = periodic_mesh(scene, n_modes, elements, tol)
    model = study.forced_model(scene, n_modes, poses, damping_ratio=damping_ratio, points=at,
                               elements_per_link=elements_per_link)
    with step_progress("Floquet steps within a speed", as_json) as on_steps:
        if sweep is None:
            result = study.steady_response(model, one, on_steps=on_steps)
        else:
            result = study.response_sweep(model, sweep, progress=progress_bar("speeds", as_json),
                                          on_steps=on_steps)
    document, files = write_response(result, model, folder, scene.name, mesh)
    publish(folder / "response.json", document, files, "\n".join(response_lines(document)),
            as_json)
