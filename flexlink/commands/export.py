"""``flexlink export SCENE...``: mode shapes as VTK files (ParaView), animations, pictures and
frequency plots, one folder per scene under ``--out``."""

from __future__ import annotations

import sys

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import dumps, json_option, mesh_options, out_option


@click.command("export")
@click.argument("scenes", nargs=-1, required=True, type=click.Path())
@click.option("-n", "--modes", "n_modes", default=4, show_default=True,
              type=click.IntRange(1, 200), help="Number of elastic modes to export.")
@mesh_options()
@click.option("--subdivide", default=4, show_default=True, type=click.IntRange(1, 64),
              help="Segments per element (the element's own shape functions between nodes).")
@click.option("--phases", default=24, show_default=True, type=click.IntRange(2, 1000),
              help="Animation frames per period.")
@click.option("--amplitude", default=0.1, show_default=True,
              type=click.FloatRange(0, 1, min_open=True),
              help="Largest drawn displacement, as a fraction of the mechanism size.")
@click.option("--pictures/--no-pictures", default=True, show_default=True,
              help="Draw PNGs of the modes (pyvista, off screen; needs OpenGL). The frequency "
                   "plot (matplotlib) is drawn either way.")
@click.option("--common-phase", is_flag=True,
              help="Animation time as the fraction of the period (0 ... 1 for every mode, so "
                   "modes play side by side in ParaView) instead of seconds.")
@json_option
@out_option
@names_scene("scenes")
def command(scenes, n_modes, elements, tol, solver, subdivide, phases, amplitude, pictures,
            common_phase, as_json, out_dir):
    """Write, for each SCENE (a scene file or a folder of them), the first modes as a .vtu, a
    .pvd animation per mode, a PNG per mode, an overview sheet and a frequency plot, into
    OUT/<scene file name>/ (each folder replaced as a whole, with its own list of files,
    export.json), and with several scenes the combined list in OUT/export.json."""
    from tqdm import tqdm

    from flexlink.analysis.families import in_plane_only_note
    from flexlink.analysis.mesh import choose_mesh
    from flexlink.analysis.modal import analyze
    from flexlink.errors import FlexlinkError
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.output.counts import counted
    from flexlink.output.export import ExportSettings, export_case
    from flexlink.output.report import case_summary
    from flexlink.scene import load_scene, scene_files

    from ._failures import finish, scene_failure
    from ._written import scene_folders

    settings = ExportSettings(n_modes=n_modes, subdivisions=subdivide, phases=phases,
                              amplitude=amplitude, pictures=pictures, plot=True,
                              common_phase=common_phase)
    out = prepare_out_dir(out_dir)
    files = scene_files(scenes)
    scene_folders(out, files)  # each OUT/<scene>/ writable before any solve, as for modes
    combined = out / "export.json" if len(files) > 1 else None  # as modes.json: several scenes
    cases, meshes, failures = [], [], []
    document = {"command": "export", "out": str(out), "complete": False, "cases": cases,
                "failures": failures}
    bar = tqdm(files, desc="export", unit="scene", file=sys.stderr,
               disable=as_json or not sys.stderr.isatty())
    for path in bar:
        try:
            scene = load_scene(path)
            mesh = choose_mesh(scene, n_modes, elements, tol)
            result = analyze(scene, n_modes, mesh.elements, solver)
            summary = case_summary(result, n_modes)
            case = {"scene": scene.name, "file": str(path), "mesh": mesh.as_dict(),
                    "frequencies_Hz": [row["computed_Hz"] for row in summary["modes"]]}
            note = in_plane_only_note(scene, "the export")
            if note:  # the export holds the in-plane modes only
                case["note"] = note
            case["files"] = export_case(result, summary, out, settings,
                                        record=_scene_record(document, case))
        except FlexlinkError as exc:  # the other scenes go on
            failures.append(scene_failure(path, exc))
            continue
        cases.append(case)
        meshes.append(mesh)
        document["complete"] = len(cases) == len(files)
        if combined:
            # rewritten after every scene folder is swapped in, so it lists exactly the folders
            # this run has completed, even when the run is stopped half-way
            write_atomic(combined, dumps(document))
    if as_json:
        click.echo(dumps(document))
        finish(failures, len(files))
        return
    for case, mesh in zip(cases, meshes):
        if "note" in case:
            click.echo(case["note"])
        f = case["files"]
        click.echo(f"{case['scene']}: {counted(len(case['frequencies_Hz']), 'mode')} -> "
                   f"{f['folder']}/  ({len(f['vtu'])} .vtu, {len(f['pvd'])} .pvd with "
                   f"{counted(len(f['frames']), 'frame')}, {counted(len(f['pictures']), 'picture')}"
                   f", {counted(len(f['plot']), 'plot')})\n  {mesh.describe()}")
    if cases:
        click.echo("written: " + ", ".join([*(c["files"]["record"][0] for c in cases),
                                            *([str(combined)] if combined else [])]))
    finish(failures, len(files))


def _scene_record(document: dict, case: dict):
    """The text of OUT/<scene>/export.json: the run's document with only this scene, written
    into the scene's folder with the files it lists."""
    def record(written: dict) -> str:
        return dumps({**document, "complete": True, "cases": [{**case, "files": written}],
                      "failures": []})
    return record
