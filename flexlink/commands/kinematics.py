"""``flexlink kinematics SCENE``: rigid motion over one crank revolution."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import json_option, out_option


@click.command("kinematics")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("--poses", default=360, show_default=True, type=click.IntRange(3, 1000000),
              help="Crank angles over one revolution.")
@click.option("--speed", default=None,
              help="Constant crank speed, e.g. '2000 rev/min' (default: the scene's "
                   "operation.crank_speed, if any), for angular velocity and acceleration.")
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, poses, speed, as_json, out_dir):
    """Angular positions, velocity coefficients K = dtheta/dq and their derivatives
    L = dK/dq of every body of SCENE over one crank revolution: extremes and where they occur,
    limit positions, torque ratio 1/K; for a scene with [[family]] tables, every member too.
    Writes kinematics.csv and kinematics.json to OUT/<scene>/."""
    from flexlink.output.cycle.rigid_motion import (kinematics_document, kinematics_text,
                                                   write_kinematics_csv)
    from flexlink.studies.cycle.rigid_motion import motion_study, variant_studies
    from flexlink.units import parse_quantity
    from ._progress import progress_bar
    from ._written import folder_and_scene, publish

    folder, scene = folder_and_scene(out_dir, scene_path)
    omega = (scene.options.crank_speed if speed is None else
             parse_quantity(speed, "angular speed", source="command line", field="--speed"))
    study = motion_study(scene, poses, omega, progress_bar("kinematics", as_json))
    members = variant_studies(scene_path, scene, poses, omega)
    files, path = write_kinematics_csv(study, folder), folder / "kinematics.json"
    publish(path, kinematics_document(study, members, [*files, path]), files,
            kinematics_text(study, members), as_json)
