"""``flexlink export SCENE...``: mode shapes as VTK files (ParaView), animations, pictures and
frequency plots, one folder per scene under ``--out``."""

from __future__ import annotations

import click

from flexlink.commands._export_options import export_options
from flexlink.commands._failures import names_scene
from flexlink.commands._options import dumps, json_option, mesh_options, out_option


@click.command("export")
@click.argument("scenes", nargs=-1, required=True, type=click.Path())
@click.option("-n", "--modes", "n_modes", default=4, show_default=True,
              type=click.IntRange(1, 200), help="Number of elastic modes to export.")
@mesh_options()
@export_options
@click.option("--uff", "uff", is_flag=True,
              help="Also write OUT/<scene>/<scene>_modes.uff: the modes for test software "
                   "(UFF datasets 164, 15 or 2411 and one 55 per mode, by pyuff), at every "
                   "node, or at --uff-points.")
@click.option("--uff-geometry", type=click.Choice(["15", "2411"]), default="15",
              show_default=True, help="UFF dataset of the geometry.")
@click.option("--uff-points", type=click.Path(), default=None,
              help="A test or sensor layout file (UFF or CSV, as `flexlink correlate` reads) "
                   "whose points the modes are written at, in that file's frame and unit "
                   "(the scene's [test] table places them).")
@json_option
@out_option
@names_scene("scenes")
def command(scenes, n_modes, elements, tol, solver, subdivide, phases, amplitude, pictures,
            common_phase, uff, uff_geometry, uff_points, as_json, out_dir):
    """Write, for each SCENE (a scene file or a folder of them), the first modes as a .vtu, a
    .pvd animation per mode, a PNG per mode, an overview sheet and a frequency plot, into
    OUT/<scene file name>/ (each folder replaced as a whole, with its own list of files,
    export.json), and with several scenes the combined list in OUT/export.json."""
    from flexlink.fileio import write_atomic
    from flexlink.output.export import (ExportSettings, UffSettings, export_case,
                                        export_document, export_entry, export_text)
    from flexlink.studies.pose.scene_summary import scene_summary
    from ._analysed import each_scene, scene_run
    from ._failures import finish

    from flexlink.errors import InputError
    from flexlink.studies.correlation.measured import read_test

    if uff_points is not None and not uff:
        raise InputError("--uff-points needs --uff", source="command line", field="--uff-points")
    points = read_test(uff_points) if uff_points is not None else None
    settings = ExportSettings(n_modes=n_modes, subdivisions=subdivide, phases=phases,
                              amplitude=amplitude, pictures=pictures, plot=True,
                              common_phase=common_phase,
                              uff=UffSettings(int(uff_geometry), points) if uff else None)
    out, files, _ = scene_run(scenes, out_dir)
    combined = out / "export.json" if len(files) > 1 else None  # as modes.json: several scenes
    entries, failures, done = [], [], []

    def export(path):  # the scene's folder, with its own export.json listing the files in it
        summary = scene_summary(path, n_modes, elements, tol, solver, in_plane_only="the export")
        return summary, export_case(summary, out, settings, record=lambda written: dumps(
            export_document(out, [export_entry(summary, written)], [], True)))

    progress = None if as_json else "export"
    for _, (summary, written) in each_scene(files, export, failures, progress):
        done.append((summary, written))
        entries.append(export_entry(summary, written))
        if combined:  # rewritten after each folder is swapped in: exactly the folders done
            write_atomic(combined, dumps(export_document(out, entries, failures,
                                                          len(entries) == len(files))))
    document = export_document(out, entries, failures, len(entries) == len(files))
    click.echo(dumps(document) + "\n" if as_json else export_text(done, combined), nl=False)
    finish(failures, len(files))
