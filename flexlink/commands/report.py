"""``flexlink report SCENE... --out DIR``: one self-contained HTML page, DIR/report.html."""

from __future__ import annotations

import logging

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import dumps, json_option, mesh_options, out_option
from flexlink.commands._sensitivity import (sensitivity_options, sensitivity_run,
                                           sensitivity_scheduler)


@click.command("report")
@click.argument("scenes", nargs=-1, required=True, type=click.Path())
@click.option("-n", "--modes", "n_modes", default=4, show_default=True,
              type=click.IntRange(1, 50), help="Elastic modes per scene.")
@mesh_options()
@click.option("--cycle-poses", default=120, show_default=True, type=click.IntRange(0, 100000),
              help="Crank angles of each scene's cycle map (0: no cycle map).")
@sensitivity_options
@click.option("--test", "test_file", type=click.Path(), default=None,
              help="A modal test file (UFF or CSV, as `flexlink correlate` reads): each scene's "
                   "page gets a Test correlation section.")
@json_option
@out_option
@names_scene("scenes")
def command(scenes, n_modes, elements, tol, solver, cycle_poses, sensitivity, samples, seed, jobs,
            scheduler, test_file, as_json, out_dir):
    """Write OUT/report.html: for each SCENE (a scene file or a folder of them) its pose and
    drawing, frequencies against the reference columns, assumptions (with --sensitivity their end
    points and the Monte Carlo 95 % interval), mesh, animated mode shapes, cycle map, and links
    to the .vtu/.pvd files written beside it in OUT/<scene>/. The page is self-contained: it
    needs no network to be viewed. A scene that fails is listed on the page and on stderr; the
    others are still reported (exit status 2)."""
    from flexlink.fileio import write_atomic
    from flexlink.output.export import ExportSettings, export_case
    from flexlink.output.report_data import report_document, report_html, report_text, scene_page
    from flexlink.studies.report_scene import report_scene
    from ._analysed import each_scene, scene_run
    from ._failures import finish
    from ._written import announce

    logging.getLogger("flexlink.analysis.modal").setLevel(logging.ERROR)  # shown on the page
    out, files, _ = scene_run(scenes, out_dir)
    run = sensitivity_run(sensitivity, samples, seed, jobs, as_json)
    measured = None
    if test_file is not None:
        from flexlink.studies.correlation.measured import read_test

        measured = read_test(test_file)

    def page(path):  # with the scene's .vtu and .pvd files, which the page links to
        scene = report_scene(path, n_modes, elements, tol, solver, cycle_poses, run)
        if scene.summary is None:  # kinematics only: no modes to export or correlate
            return scene_page(scene, {}, out)
        return scene_page(scene, export_case(scene.summary, out, ExportSettings(
            n_modes=n_modes, pictures=False, plot=False)), out, _correlation(scene, measured))

    failures: list[dict] = []
    with sensitivity_scheduler(sensitivity, scheduler):  # one cluster for every scene
        pages = [p for _, p in each_scene(files, page, failures, None if as_json else "report")]
    if not pages:  # nothing to show: no page, only the reasons
        finish(failures, len(files))
    report = write_atomic(out / "report.html", html := report_html(pages, failures, n_modes))
    document = report_document(report, html, pages, out, failures)
    click.echo(dumps(document) if as_json else report_text(document))
    announce([report], as_json)
    finish(failures, len(files))


def _correlation(scene, measured) -> dict | None:
    """The test's correlation with the report's scene, at the scene's mesh, as JSON."""
    if measured is None:
        return None
    from flexlink.output.correlation.correlation import correlation_json
    from flexlink.studies.correlation.correlation import correlate_test

    return correlation_json(correlate_test(scene.summary.case.scene, measured,
                                           elements=scene.summary.mesh.elements))
