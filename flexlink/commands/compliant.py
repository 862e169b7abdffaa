"""``flexlink compliant SCENE``: a partially compliant linkage over the crank turn at large
deflection (co-rotational FE) beside its pseudo-rigid-body model: the strip's stress, the
driving torque and, given the strip's steel, its fatigue life."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import json_option, out_option


@click.command("compliant")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("--angles", default=360, show_default=True, type=click.IntRange(12, 100000),
              help="Crank angles over one turn (the continuation's steps).")
@click.option("-e", "--elements", default=None, type=click.IntRange(1, 100000),
              help="Elements per link (default: the scene's).")
@click.option("--life/--no-life", "with_life", default=True, show_default=True,
              help="The strip's fatigue life from its material file's strength data (refused, "
                   "naming the file and key, where a datum is missing).")
@click.option("--reliability", default=0.99, show_default=True,
              type=click.FloatRange(0, 1, min_open=True, max_open=True),
              help="Reliability of the endurance limit (Marin ke), as `flexlink life`.")
@click.option("--cycles", "required", default=1e6, show_default=True,
              type=click.FloatRange(1, None), help="Required life [wipe cycles = crank turns].")
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, angles, elements, with_life, reliability, required, as_json, out_dir):
    """SCENE (with a [prb] table) turned quasi-statically through one crank turn: every link
    as co-rotational frame elements, Newton's method continued in the crank angle, the strip
    straight at the start pose. Writes compliant.csv, compliant.png and compliant.json to
    OUT/<scene>/."""
    from flexlink.fileio import write_atomic
    from flexlink.output.life.compliant_cycle import (compliant_csv, compliant_document,
                                                      compliant_plot, compliant_text)
    from flexlink.studies.life.compliant_cycle import compliant_cycle, strip_lives
    from flexlink.studies.life.life import Conditions, check_strengths
    from ._progress import progress_bar
    from ._written import folder_and_scene, publish

    conditions = Conditions(reliability=reliability)
    folder, scene = folder_and_scene(out_dir, scene_path)
    if with_life and scene.options.prb is not None:
        check_strengths(scene, [scene.options.prb.strip])  # before the study, not after it
    cycle = compliant_cycle(scene, angles, elements, progress_bar("compliant", as_json, "angle"))
    lives = strip_lives(scene, cycle, conditions) if with_life else ()
    document = compliant_document(scene, cycle, lives, required, conditions)
    paths = [folder / "compliant.csv", folder / "compliant.png"]
    write_atomic(paths[0], compliant_csv(cycle))
    write_atomic(paths[1], compliant_plot(cycle, f"{scene.name}: strip '{cycle.strip}' over "
                                                 "the crank turn"))
    publish(folder / "compliant.json", document, paths, compliant_text(document), as_json)
