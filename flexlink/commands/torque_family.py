"""``flexlink torque-family SCENE``: the driving torque of every member of the scene's
[[family]] tables."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import json_option, out_option, turn_poses_option


@click.command("torque-family")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("--speed", default=None, help="Crank speed, e.g. '2000 rev/min' (default: the "
              "scene's operation.crank_speed).")
@turn_poses_option
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, speed, poses, as_json, out_dir):
    """Driving torque over one crank turn of every [[family]] member of SCENE, from the links'
    mass and inertia and the scene's [[loads]], at one crank speed: peak, largest, smallest and
    rms torque per member, with its link lengths and the outputs' inertia about their pivots.
    Writes torque_family.csv and torque_family.json to OUT/<scene>/."""
    from flexlink.errors import InputError
    from flexlink.fileio import write_atomic
    from flexlink.output.kinetostatics.families import (families_csv, families_document,
                                                        families_text)
    from flexlink.studies.kinetostatics.families import family_torques
    from ._progress import progress_bar
    from ._speeds import operating_speed, parse_speed
    from ._written import folder_and_scene, publish

    omega = parse_speed(speed)
    folder, scene = folder_and_scene(out_dir, scene_path)
    if not scene.options.variants:
        raise InputError("no [[family]] table: nothing to vary", source=scene.path,
                         field="family")
    omega, _ = operating_speed(scene, omega, None)
    result = family_torques(scene_path, scene, omega, poses,
                            progress_bar("torque-family", as_json, "member"))
    document = families_document(result, [])
    table = folder / "torque_family.csv"
    write_atomic(table, families_csv(document))
    document.pop("files")
    publish(folder / "torque_family.json", document, [table], families_text(document), as_json)
