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
def command(scenes, n_modes, elements, tol, method, subdivide, phases, amplitude, pictures,
            common_phase, as_json, out_dir):
    """Write, for each SCENE (a scene file or a folder of them), the first modes as a .vtu, a
    .pvd animation per mode, a PNG per mode, an overview sheet and a frequency plot, into
    OUT/<scene file name>/ (each folder replaced as a whole), and a list of everything in
    OUT/export.json."""
    from tqdm import tqdm

    from flexlink.analysis.families import in_plane_only_note
    from flexlink.analysis.mesh import choose_mesh
    from flexlink.analysis.modal import analyze
    from flexlink.errors import FlexlinkError, InputError
    from ._failures import finish, scene_failure
    from flexlink.output.export import ExportSettings, export_case
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.output.report import case_summary
    from flexlink.scene import load_scene, scene_files

    settings = ExportSettings(n_modes=n_modes, subdivisions=subdivide, phases=phases,
                              amplitude=amplitude, pictures=pictures, plot=True,
                              common_phase=common_phase)
    out = prepare_out_dir(out_dir)
    files = scene_files(scenes)
    stems = [f.stem for f in files]
    clash = sorted({s for s in stems if stems.count(s) > 1})
    if clash:
        raise InputError(f"two scene files would write to the same folder {clash[0]!r}",
                         source="command line", expected="scene files with different names")
    cases, meshes, failures = [], [], []
    document = {"command": "export", "out": str(out), "complete": False, "cases": cases,
                "failures": failures}
    bar = tqdm(files, desc="export", unit="scene", file=sys.stderr,
               disable=as_json or not sys.stderr.isatty())
    for path in bar:
        try:
            scene = load_scene(path)
            mesh = choose_mesh(scene, n_modes, elements, tol)
            result = analyze(scene, n_modes, mesh.elements, method)
            summary = case_summary(result, n_modes)
            written = export_case(result, summary, out, settings)
        except FlexlinkError as exc:  # the other scenes go on
            failures.append(scene_failure(path, exc))
            continue
        cases.append({"scene": scene.name, "file": str(path), "mesh": mesh.as_dict(),
                      "frequencies_Hz": [row["computed_Hz"] for row in summary["modes"]],
                      "files": written})
        note = in_plane_only_note(scene, "the export")
        if note:
            cases[-1]["note"] = note
        meshes.append(mesh)
        # rewritten after every scene folder is swapped in, so export.json lists exactly the
        # folders this run has completed, even when the run is stopped half-way
        document["complete"] = len(cases) == len(files)
        write_atomic(out / "export.json", dumps(document))
    if as_json:
        click.echo(dumps(document))
        finish(failures, len(files))
        return
    for case, mesh in zip(cases, meshes):
        if "note" in case:
            click.echo(case["note"])
        f = case["files"]
        click.echo(f"{case['scene']}: {len(case['frequencies_Hz'])} modes -> {f['folder']}/  "
                   f"({len(f['vtu'])} .vtu, {len(f['pvd'])} .pvd with {len(f['frames'])} frames, "
                   f"{len(f['pictures'])} pictures, {len(f['plot'])} plot)\n  {mesh.describe()}")
    if cases:
        click.echo(f"written: {out / 'export.json'}")
    finish(failures, len(files))
