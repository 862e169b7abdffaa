"""``flexlink kinematics SCENE``: rigid motion over one crank revolution."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import dumps, json_option, out_option


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
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.output.kinematics_report import variant_text, motion_csv, motion_text
    from flexlink.scene import load_scene
    from flexlink.units import rev_per_min
    from flexlink.studies.kinematics import variant_studies, motion_study
    from flexlink.units import parse_quantity
    from ._progress import progress_bar
    from ._written import announce, scene_folders

    [folder] = scene_folders(prepare_out_dir(out_dir), [scene_path])
    scene = load_scene(scene_path)
    omega = (scene.options.crank_speed if speed is None else
             parse_quantity(speed, "angular speed", source="command line", field="--speed"))
    cycle, doc = motion_study(scene, poses, omega, progress_bar("kinematics", as_json))
    members = variant_studies(scene_path, scene, poses, omega)
    paths = [folder / "kinematics.csv", folder / "kinematics.json"]
    document = {"command": "kinematics", "poses": poses,
                "crank_speed_rev_per_min": rev_per_min(omega) if omega else None,
                **doc, "family": members, "files": [str(p) for p in paths],
                "assumptions": [f"{a.field}: {a.note}" for a in scene.assumptions]}
    write_atomic(paths[0], motion_csv(cycle, omega))
    write_atomic(paths[1], dumps(document))
    if as_json:
        click.echo(dumps(document))
        return
    click.echo(motion_text(document, bool(omega)))
    if members:
        click.echo(variant_text(members, bool(omega)))
    announce(paths, as_json)
