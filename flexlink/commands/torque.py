"""``flexlink torque SCENE``: driving torque and joint forces over one crank turn."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import json_option, out_option
from flexlink.commands._speeds import crank_acceleration_option, speed_option


@click.command("torque")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@speed_option("Crank speed, e.g. '600 rev/min', '3.27 rad/s' or '10 Hz' (default: the scene's "
              "operation.crank_speed).")
@crank_acceleration_option("Crank angular acceleration, e.g. '5 rad/s^2' (default: the scene's "
                           "operation.crank_acceleration, else 0: constant speed).",
                           "acceleration")
@click.option("--poses", default=360, show_default=True, type=click.IntRange(3, 1000000),
              help="Crank angles over one turn.")
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, speed, acceleration, poses, as_json, out_dir):
    """Driving torque, drive power and joint forces of SCENE's rigid-body motion at a crank
    speed, from the links' mass and inertia and the scene's [[loads]]. Writes torque.csv,
    torque.png and torque.json to OUT/<scene>/."""
    from flexlink.output.running.torque import torque_document, torque_text, write_torque
    from flexlink.scene.plausibility import check_speeds
    from flexlink.studies.running.torque import torque_study
    from ._progress import progress_bar
    from ._speeds import operating_speed, parse_acceleration, parse_speed
    from ._written import folder_and_scene, publish

    given = parse_speed(speed), parse_acceleration(acceleration)
    folder, scene = folder_and_scene(out_dir, scene_path)
    if given[0] is not None:
        check_speeds(scene, [given[0]], "--speed")
    fields = tuple(("command line: " + name) if value is not None else name for value, name in
                   zip(given, ("--speed", "--crank-acceleration")))
    omega, qdd = operating_speed(scene, *given)
    curve = torque_study(scene, omega, qdd, poses, progress_bar("torque", as_json),
                         fields=fields)
    document = torque_document(curve, [f"{a.field}: {a.note}" for a in scene.assumptions])
    publish(folder / "torque.json", document, write_torque(curve, folder),
            torque_text(document), as_json)
