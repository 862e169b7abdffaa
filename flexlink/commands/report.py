"""``flexlink report SCENE... --out DIR``: one self-contained HTML page, DIR/report.html."""

from __future__ import annotations

import datetime
import logging

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import dumps, json_option, mesh_options, out_option
from flexlink.commands._sensitivity import (scene_sensitivity, sensitivity_options,
                                           sensitivity_scheduler)


@click.command("report")
@click.argument("scenes", nargs=-1, required=True, type=click.Path())
@click.option("-n", "--modes", "n_modes", default=4, show_default=True,
              type=click.IntRange(1, 50), help="Elastic modes per scene.")
@mesh_options()
@click.option("--cycle-poses", default=120, show_default=True, type=click.IntRange(0, 100000),
              help="Crank angles of each scene's cycle map (0: no cycle map).")
@sensitivity_options
@json_option
@out_option
@names_scene("scenes")
def command(scenes, n_modes, elements, tol, solver, cycle_poses, sensitivity, samples, seed, jobs,
            scheduler, as_json, out_dir):
    """Write OUT/report.html: for each SCENE (a scene file or a folder of them) its pose and
    drawing, frequencies against the reference columns, assumptions (with --sensitivity their
    end points and the Monte Carlo 95 % interval), mesh, animated mode shapes, cycle map, and
    links to the .vtu/.pvd files written beside it in OUT/<scene>/.
    The page is self-contained: it needs no network to be viewed. A scene that fails is
    listed on the page and on stderr; the others are still reported (exit status 2)."""
    import importlib.metadata
    import sys

    import plotly.offline
    from tqdm import tqdm

    from flexlink.analysis.families import in_plane_only_note
    from flexlink.errors import FlexlinkError
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.output.counts import counted
    from flexlink.output.export import ExportSettings, export_case
    from flexlink.output.export_vtk import mode_set
    from flexlink.output.html_report import render_page
    from flexlink.output.report import case_summary
    from flexlink.output.report_data import at_speed_data, cycle_data, scene_page
    from flexlink.scene import scene_files
    from flexlink.studies.cycle import modal_map
    from ._analysed import analysed_scene
    from ._failures import finish, scene_failure
    from ._written import announce, scene_folders

    logging.getLogger("flexlink.analysis.modal").setLevel(logging.ERROR)  # shown on the page
    out = prepare_out_dir(out_dir)
    files = scene_files(scenes)
    scene_folders(out, files)  # refuses two scenes sharing a folder
    settings = ExportSettings(n_modes=n_modes, pictures=False, plot=False)
    pages, written = [], []
    bar = tqdm(files, desc="report", unit="scene", file=sys.stderr,
               disable=as_json or not sys.stderr.isatty())
    failures = []
    with sensitivity_scheduler(sensitivity, scheduler):  # one cluster for every scene
        for path in bar:
            try:
                scene, mesh, result = analysed_scene(path, n_modes, elements, tol, solver)
                note = in_plane_only_note(scene, "this page")  # shown with the warnings
                summary = {**case_summary(result, n_modes),
                           "warnings": list(result.warnings) + ([note] if note else []),
                           **({"note": note} if note else {})}
                if sensitivity:
                    summary["sensitivity"] = scene_sensitivity(scene, n_modes, samples, seed,
                                                               jobs, as_json)
            except FlexlinkError as exc:  # the other scenes still get their report
                failures.append(scene_failure(path, exc))
                continue
            exported = export_case(result, summary, out, settings)
            written += exported["vtu"] + exported["pvd"]
            cycle, reason = None, None
            if cycle_poses:
                try:
                    cycle = modal_map(scene, cycle_poses, n_modes, mesh.elements)
                except FlexlinkError as exc:  # e.g. a linkage that cannot turn a full cycle
                    reason = str(exc)
            mesh_info = {**mesh.as_dict(), "describe": mesh.describe(),
                         "history": list(mesh.history)}
            pages.append(scene_page(result, summary, mesh_info, mode_set(result, n_modes),
                                    cycle_data(cycle, result.pose.crank_angle, reason),
                                    exported, out,
                                    at_speed_data(scene, n_modes, mesh.elements)))
    if not pages:  # nothing to show: no page, only the reasons
        finish(failures, len(files))
    stamp = datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")
    version = importlib.metadata.version("flexlink")
    subtitle = (f"flexlink {version}, {stamp}: {counted(len(pages), 'scene')}, first "
                f"{counted(n_modes, 'elastic mode')}")
    page = render_page(pages, plotly.offline.get_plotlyjs(), subtitle=subtitle,
                       failures=[f["error"] for f in failures])
    report = write_atomic(out / "report.html", page)
    document = {"command": "report", "report": str(report), "bytes": len(page.encode()),
                "scenes": [{"scene": p["summary"]["scene"], "file": p["summary"]["file"],
                            "mesh": p["mesh"]["elements_per_link"],
                            "frequencies_Hz": [r["computed_Hz"] for r in p["summary"]["modes"]],
                            "cycle_map": p["cycle"] is not None and "unavailable" not in p["cycle"],
                            **({"note": p["summary"]["note"]} if "note" in p["summary"] else {}),
                            **({"cycle_map_note": p["cycle"]["note"]}
                               if p["cycle"] and "note" in p["cycle"] else {})}
                           for p in pages],
                "files": [str(report)] + [str(f) for f in written], "failures": failures}
    if as_json:
        click.echo(dumps(document))
        finish(failures, len(files))
        return
    click.echo(f"report: {counted(len(pages), 'scene')}, {document['bytes'] / 1e6:.1f} MB -> "
               f"{report}")
    announce([report], as_json)
    finish(failures, len(files))
