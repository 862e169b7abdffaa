"""``flexlink modes SCENE...``: natural frequencies at the scene's pose vs its reference table."""

from __future__ import annotations

import logging

import click

from flexlink.commands._operating import operating_given, operating_options, run_operating
from flexlink.commands._options import dumps, json_option, mesh_options, out_option
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
            as_json, out_dir, **at_speed):
    """Natural frequencies of each SCENE (a scene file or a folder of them) at its pose,
    compared with the scene's reference columns (measured Ex, published FE). Writes
    OUT/<scene>/modes.json and modes.csv per scene, and OUT/modes.json and modes.csv with
    every scene when there are several. With --speed: the modes about the rigid motion at that
    crank speed beside the static ones, in OUT/<scene>/modes_at_speed.json and .csv."""
    from flexlink.analysis.eigensolver import DEFAULT_SOLVER
    from flexlink.fileio import write_atomic
    from flexlink.output.report import modes_files, modes_text
    from flexlink.studies.scene_summary import scene_summary
    from ._analysed import each_scene, scene_run
    from ._failures import finish
    from ._written import announce

    # analysis warnings are printed with their scene; logged as well they would show twice
    logging.getLogger("flexlink.analysis.modal").setLevel(logging.ERROR)
    out, files, folders = scene_run(scenes, out_dir)
    if operating_given(static_only=sensitivity or solver != DEFAULT_SOLVER, **at_speed):
        return run_operating(files, n_modes, elements, tol, **at_speed, as_json=as_json, out=out)
    run = sensitivity_run(sensitivity, samples, seed, jobs, as_json)
    failures: list[dict] = []
    with sensitivity_scheduler(sensitivity, scheduler):  # one cluster for every scene
        done = list(each_scene(files, lambda path: scene_summary(
            path, n_modes, elements, tol, solver, alternatives=True, sensitivity=run), failures))
    documents, tables, document = modes_files([(folders[p], s) for p, s in done],
                                              out if len(files) > 1 else None, failures)
    for path, part in documents.items():
        write_atomic(path, dumps(part))
    for path, table in tables.items():
        write_atomic(path, table)
    text = dumps(document) + "\n" if as_json else modes_text([s for _, s in done])
    click.echo(text, nl=False)
    announce(document["files"], as_json)
    finish(failures, len(files))
