"""``flexlink cycle SCENE``: the modal map over one crank revolution and a resonance check."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import (TOLERANCE, dumps, json_option,
                                       map_parallel_options, out_option)


@click.command("cycle")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("-n", "--modes", "n_modes", default=3, show_default=True,
              type=click.IntRange(1, 50), help="Elastic modes per pose.")
@click.option("--poses", default=360, show_default=True, type=click.IntRange(3, 100000),
              help="Crank angles over one revolution.")
@click.option("-e", "--elements", default=None, type=click.IntRange(1, 100000),
              help="Elements per link (default: the scene's mesh.elements_per_link if it pins "
                   "one, else the coarsest mesh meeting --tol at the start pose).")
@click.option("--tol", default=None, type=TOLERANCE,
              help="Relative frequency tolerance of the default mesh (as in `flexlink modes`) "
                   "[default: 1e-6].")
@click.option("--speed", default=None,
              help="Crank speed for the resonance check, e.g. '2000 rev/min' (default: the "
                   "scene's operation.crank_speed; none or 0: no check; negative: the other "
                   "direction, checked at |speed|).")
@click.option("--margin", default=0.05, show_default=True, type=click.FloatRange(0, 1),
              help="Relative distance that counts as near a natural frequency.")
@click.option("--harmonics", default=10, show_default=True, type=click.IntRange(1, 10000),
              help="Crank harmonics n = 1 ... this number.")
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
    from flexlink.analysis.families import in_plane_only_note
    from flexlink.output.cycle_report import cycle_document, cycle_text, write_map
    from flexlink.studies.cycle import modal_map, resonance_speed, resonances
    from flexlink.studies.campbell import nearest_harmonic
    from flexlink.studies.tracking import tracked_map
    from flexlink.analysis.mesh import choose_mesh
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.parallel import use_scheduler
    from flexlink.scene import load_scene
    from flexlink.units import parse_quantity
    from ._progress import progress_bar
    from ._written import announce, scene_folders

    [folder] = scene_folders(prepare_out_dir(out_dir), [scene_path])
    scene = load_scene(scene_path)
    omega = (scene.options.crank_speed if speed is None else
             parse_quantity(speed, "angular speed", source="command line", field="--speed"))
    check_speed, check_note = resonance_speed(omega)
    mesh = choose_mesh(scene, n_modes, elements, tol)
    with use_scheduler(scheduler):
        if track:
            result = tracked_map(scene, poses, n_modes, mesh.elements,
                                 progress=progress_bar("tracked modes", as_json), n_jobs=jobs)
        else:
            result = modal_map(scene, poses, n_modes, mesh.elements,
                               progress=progress_bar("modal map", as_json))
    to_zero = [(j, r.pose) for r in result.tracks.reseeds for j in r.vanishing] if track else []
    hits = resonances(result, check_speed, margin, harmonics, to_zero) if check_speed else []
    paths = [folder / "cycle.csv", folder / "cycle.png", folder / "cycle.json"]
    write_map(paths[0], paths[1], result, check_speed, hits)
    nearest = nearest_harmonic(result.frequencies, check_speed, harmonics) if check_speed else None
    document = cycle_document(scene, result, mesh, poses, omega, (check_speed, check_note),
                              margin, hits, nearest, paths)
    note = result.note if not track else in_plane_only_note(scene, "this map")
    if note:  # the map is not quite what was asked for: say what it is
        document["note"] = note
    write_atomic(paths[2], dumps(document))
    if as_json:
        click.echo(dumps(document))
        return
    for line in cycle_text(document, mesh.describe(), harmonics):
        click.echo(line)
    announce(paths, as_json)
