"""``flexlink modes SCENE...``: natural frequencies at the scene's pose vs its reference table."""

from __future__ import annotations

import logging

import click

from flexlink.commands._operating import run_operating
from flexlink.commands._operating_options import operating_options, operating_request
from flexlink.commands._options import json_option, mesh_options, out_option
from flexlink.commands._sensitivity import (sensitivity_options, sensitivity_run,
                                           sensitivity_scheduler)


@click.command("modes")
@click.argument("scenes", nargs=-1, required=True, type=click.Path())
@click.option("-n", "--modes", "n_modes", default=4, show_default=True,
              type=click.IntRange(1, 200), help="Number of elastic modes to report.")
@mesh_options()
@sensitivity_options
@json_option
@out_option
@operating_options
def command(scenes, n_modes, elements, solver, tol, sensitivity, samples, seed, jobs, scheduler,
            as_json, out_dir, **speed_options):
    """Natural frequencies of each SCENE (a scene file or a folder of them) at its pose,
    compared with the scene's reference columns (measured Ex, published FE). Writes
    OUT/<scene>/modes.json and modes.csv per scene, and OUT/modes.json and modes.csv with
    every scene when there are several. With --speed: the modes about the rigid motion at that
    crank speed beside the static ones, in OUT/<scene>/modes_at_speed.json and .csv."""
    from flexlink.analysis.eigensolver import DEFAULT_SOLVER
    from flexlink.output.pose.scene_summary import modes_files, modes_text
    from flexlink.studies.pose.scene_summary import scene_summary
    from ._analysed import each_scene, scene_run
    from ._failures import finish
    from ._written import publish_files

    # analysis warnings are printed with their scene; logged as well they would show twice
    logging.getLogger("flexlink.analysis.modal").setLevel(logging.ERROR)
    out, files, folders = scene_run(scenes, out_dir)
    at = operating_request(static_only=sensitivity or solver != DEFAULT_SOLVER, **speed_options)
    if at is not None:
        return run_operating(files, folders, n_modes, elements, tol, at, as_json)
    run = sensitivity_run(sensitivity, samples, seed, jobs, as_json)
    failures: list[dict] = []
    with sensitivity_scheduler(sensitivity, scheduler):  # one cluster for every scene
        done = list(each_scene(files, lambda path: scene_summary(
            path, n_modes, elements, tol, solver, alternatives=True, sensitivity=run), failures))
    documents, tables, document = modes_files([(folders[p], s) for p, s in done],
                                              out if len(files) > 1 else None, failures)
    publish_files(documents, tables, document, modes_text([s for _, s in done]), as_json)
    finish(failures, len(files))
