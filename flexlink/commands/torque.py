"""``flexlink torque SCENE``: driving torque and joint forces over one crank turn."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import dumps, json_option, out_option


@click.command("torque")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("--speed", default=None, help="Crank speed, e.g. '600 rev/min', '3.27 rad/s' or "
              "'10 Hz' (default: the scene's operation.crank_speed).")
@click.option("--crank-acceleration", "acceleration", default=None,
              help="Crank angular acceleration, e.g. '5 rad/s^2' (default: the scene's "
                   "operation.crank_acceleration, else 0: constant speed).")
@click.option("--poses", default=360, show_default=True, type=click.IntRange(3, 1000000),
              help="Crank angles over one turn.")
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, speed, acceleration, poses, as_json, out_dir):
    """Driving torque, drive power and joint forces of SCENE's rigid-body motion at a crank
    speed, from the links' mass and inertia and the scene's [[loads]]. Writes torque.csv,
    torque.json and torque.png to OUT/<scene>/."""
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.output.running.torque import torque_csv, torque_document, torque_plot, torque_text
    from flexlink.scene import load_scene
    from flexlink.scene.plausibility import check_speeds
    from flexlink.studies.running.torque import operating_point, torque_study
    from flexlink.units import parse_quantity
    from ._progress import progress_bar
    from ._written import announce, scene_folders

    def option(text, kind, name):
        return None if text is None else parse_quantity(text, kind, source="command line",
                                                         field=name)

    omega = option(speed, "angular speed", "--speed")
    qdd = option(acceleration, "angular acceleration", "--crank-acceleration")
    [folder] = scene_folders(prepare_out_dir(out_dir), [scene_path])
    scene = load_scene(scene_path)
    if omega is not None:
        check_speeds(scene, [omega], "--speed")
    fields = tuple(("command line: " + name) if given is not None else name for given, name in
                   ((omega, "--speed"), (qdd, "--crank-acceleration")))
    omega, qdd = operating_point(scene, omega, qdd)
    curve = torque_study(scene, omega, qdd, poses, progress_bar("torque", as_json),
                         fields=fields)
    paths = [folder / "torque.csv", folder / "torque.json", folder / "torque.png"]
    document = torque_document(curve, [f"{a.field}: {a.note}" for a in scene.assumptions],
                               [str(p) for p in paths])
    # every file's content first: a failure leaves the earlier run's files as they were
    contents = [torque_csv(curve), dumps(document), torque_plot(curve)]
    for path, content in zip(paths, contents):
        write_atomic(path, content)
    if as_json:
        click.echo(dumps(document))
        return
    click.echo(torque_text(document))
    announce(paths, as_json)
