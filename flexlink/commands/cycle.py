"""``flexlink cycle SCENE``: the modal map over one crank revolution and a resonance check."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import (harmonics_option, json_option, map_parallel_options,
                                       mesh_options,
                                       out_option)


@click.command("cycle")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("-n", "--modes", "n_modes", default=3, show_default=True,
              type=click.IntRange(1, 50), help="Elastic modes per pose.")
@click.option("--poses", default=360, show_default=True, type=click.IntRange(3, 100000),
              help="Crank angles over one revolution.")
@mesh_options(method=False)
@click.option("--speed", default=None,
              help="Crank speed for the resonance check, e.g. '2000 rev/min' (default: the "
                   "scene's operation.crank_speed; none or 0: no check; negative: the other "
                   "direction, checked at |speed|).")
@click.option("--margin", default=0.05, show_default=True, type=click.FloatRange(0, 1),
              help="Relative distance that counts as near a natural frequency.")
@harmonics_option
@click.option("--track/--sorted", default=True, show_default=True,
              help="Follow each mode's shape from pose to pose by MAC (crossings and veerings "
                   "marked), or list the n-th lowest frequency at each pose (faster).")
@map_parallel_options(sorted_map=True)
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, n_modes, poses, elements, tol, speed, margin, harmonics, track, jobs,
            scheduler, as_json, out_dir):
    """Natural frequencies of the first modes at every crank angle of SCENE (CSV and PNG in
    --out), the poses where the transmission angle is 90 deg, and the crank harmonics that
    come within --margin of a natural frequency anywhere in the cycle. Writes cycle.csv,
    cycle.png and cycle.json to OUT/<scene>/."""
    from flexlink.output.cycle.modal_map import cycle_document, cycle_text, write_cycle
    from flexlink.parallel import use_scheduler
    from flexlink.studies.cycle.cycle import cycle_study
    from flexlink.units import parse_quantity
    from ._progress import progress_bar
    from ._written import folder_and_scene, publish

    folder, scene = folder_and_scene(out_dir, scene_path)
    # "none" and a bare 0 skip the check, as the option's help says (0 is 0 in any unit)
    omega = (scene.options.crank_speed if speed is None else
             0.0 if speed.strip().lower() in ("none", "0") else
             parse_quantity(speed, "angular speed", source="command line", field="--speed"))
    with use_scheduler(scheduler):
        study = cycle_study(scene, n_modes, poses, elements, tol, omega, margin, harmonics, track,
                            jobs, progress_bar("tracked modes" if track else "modal map", as_json))
    document = cycle_document(scene, study)
    publish(folder / "cycle.json", document, write_cycle(study, folder),
            cycle_text(document, study), as_json)
