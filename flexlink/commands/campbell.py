"""``flexlink campbell SCENE --speeds "0:3000 rev/min"``: Campbell diagram and critical speeds."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import (harmonics_option, json_option, map_parallel_options,
                                       mesh_options, out_option, refuse_unless)
from flexlink.commands._speeds import crank_acceleration_option, speeds_option


@click.command("campbell")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@speeds_option()
@click.option("-n", "--modes", "n_modes", default=3, show_default=True,
              type=click.IntRange(1, 50), help="Tracked elastic modes.")
@click.option("--poses", default=72, show_default=True, type=click.IntRange(3, 100000),
              help="Crank angles over one revolution for the bands.")
@mesh_options(method=False)
@click.option("--margin", default=0.05, show_default=True, type=click.FloatRange(0, 1),
              help="Relative distance from a band that counts as critical.")
@harmonics_option
@click.option("--dynamic", is_flag=True,
              help="Also the bands at each speed from the modes at speed (inertia preload, "
                   "centrifugal, Coriolis), and how they move the critical speed ranges.")
@click.option("--speed-steps", default=50, show_default=True, type=click.IntRange(2, 100000),
              help="Crank speeds across the range for --dynamic.")
@crank_acceleration_option("With --dynamic: the crank's angular acceleration at every speed, "
                           "e.g. '50 rad/s^2' [default: 0, constant speed].", "acceleration")
@map_parallel_options(sorted_map=False)
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, speeds, n_modes, poses, elements, tol, margin, harmonics, dynamic,
            speed_steps, acceleration, jobs, scheduler, as_json, out_dir):
    """Campbell diagram of SCENE: each tracked mode's band over the crank cycle against crank
    speed, the harmonics n x speed, and the speed ranges where a harmonic comes within the
    margin of a band (or the nearest margin when none does). Writes campbell.png, .csv and
    .json to OUT/<scene>/; with --dynamic also campbell_at_speed.png and .csv."""
    from flexlink.output.cycle.campbell import campbell_document, campbell_text, write_campbell
    from flexlink.parallel import use_scheduler
    from flexlink.studies.cycle.campbell import campbell_study
    from flexlink.errors import InputError
    from ._progress import progress_bar
    from ._speeds import parse_acceleration, parse_speeds
    from ._written import folder_and_scene, publish

    refuse_unless("speed_steps", "--dynamic", dynamic)
    if acceleration is not None and not dynamic:
        raise InputError("a crank acceleration is for the bands at speed: give --dynamic too",
                         source="command line", field="--crank-acceleration",
                         expected="--dynamic with --crank-acceleration")
    window, qdd = parse_speeds(speeds), parse_acceleration(acceleration) or 0.0
    folder, scene = folder_and_scene(out_dir, scene_path)
    with use_scheduler(scheduler):
        study = campbell_study(scene, window, n_modes, poses, elements, tol, margin, harmonics,
                               speed_steps if dynamic else None, jobs,
                               progress_bar("tracked modes", as_json),
                               progress_bar("poses at speed", as_json), qdd)
    document = campbell_document(scene, study)
    publish(folder / "campbell.json", document, write_campbell(study, folder),
            campbell_text(document, study), as_json)
