"""``flexlink response SCENE --speed ... | --speeds LOW:HIGH``: the steady elastic response."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import dumps, json_option, out_option


@click.command("response")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("--speed", help="One crank speed, e.g. '600 rev/min' (default: the scene's).")
@click.option("--speeds", help="A sweep of crank speeds instead, e.g. '60:3000 rev/min'.")
@click.option("--count", default=100, show_default=True, type=click.IntRange(2, 100000),
              help="Speeds over the --speeds range.")
@click.option("-n", "--modes", "n_modes", default=6, show_default=True,
              type=click.IntRange(1, 50), help="Static modes of the reduced basis.")
@click.option("--damping-ratio", default=0.01, show_default=True, type=float,
              help="Modal damping ratio in [0, 1).")
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

    from flexlink.commands.campbell import parse_speeds
    from flexlink.errors import InputError
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.output import steady_response as out
    from flexlink.scene import load_scene
    from flexlink.studies import steady_response as study
    from flexlink.studies.campbell import _check_speeds
    from flexlink.studies.operating_point import crank_speed
    from flexlink.units import parse_quantity
    from ._progress import progress_bar
    from ._written import announce, scene_folders

    if speed is not None and speeds is not None:
        raise InputError("give --speed or --speeds, not both", field="--speeds")
    sweep = None if speeds is None else np.linspace(*_check_speeds(parse_speeds(speeds)), count)
    one = speed and parse_quantity(speed, "angular speed", source="command line", field="--speed")
    at = tuple(study.parse_point(p) for p in points) or None
    [folder] = scene_folders(prepare_out_dir(out_dir), [scene_path])
    scene = load_scene(scene_path)
    one = crank_speed(scene, one) if sweep is None else None
    model = study.forced_model(scene, n_modes, damping_ratio=damping_ratio, points=at)
    paths = [folder / f"response.{x}" for x in ("png", "csv", "json")]
    if sweep is None:
        result = study.steady_response(model, one)
        out.plot_response(result, model, paths[0], scene.name)
        csv, document = out.response_csv(result, model), out.response_document(scene.name, result, model)
    else:
        result = study.response_sweep(model, sweep, progress=progress_bar("speeds", as_json))
        out.plot_sweep(result, paths[0], scene.name, model.periodic.frequencies)
        csv, document = out.sweep_csv(result), out.sweep_document(scene.name, result, model)
    write_atomic(paths[1], csv)
    write_atomic(paths[2], dumps({**document, "files": [str(p) for p in paths]}))
    click.echo(dumps(document) if as_json else "\n".join(out.response_lines(document)))
    announce(paths, as_json)
