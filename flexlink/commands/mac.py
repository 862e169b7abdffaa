"""``flexlink mac A B``: the MAC matrix of two scenes' (or meshes') modes and their pairing."""

from __future__ import annotations

import click

from flexlink.commands._options import EnumChoice, deprecated_for, json_option, out_option
from flexlink.fe.motions import Part


@click.command("mac")
@click.argument("scene_a", metavar="A", type=click.Path())
@click.argument("scene_b", metavar="B", type=click.Path())
@click.option("-n", "--modes", "n_modes", default=4, show_default=True,
              type=click.IntRange(1, 200), help="Elastic modes of each side.")
@click.option("-e", "--elements", default=None, type=click.IntRange(1, 100000),
              help="Elements per link of A (and of B unless --elements-b) [default: as in "
                   "`flexlink modes`].")
@click.option("--elements-b", default=None, type=click.IntRange(1, 100000),
              help="Elements per link of B, to compare two meshes of one scene.")
@click.option("--part", type=EnumChoice(Part, none="auto"), default="auto", show_default=True,
              help="Model part whose modes are compared: auto = the part of the family both "
                   "scenes declare (model.family planar -> in-plane); a comparison across "
                   "parts is refused (their shapes move different DOFs).")
@click.option("--family", "old_part", type=EnumChoice(Part, none="auto"), default=None,
              hidden=True, callback=deprecated_for("--part"), help="Deprecated: --part.")
@json_option
@out_option
def command(scene_a, scene_b, n_modes, elements, elements_b, part, old_part, as_json, out_dir):
    """MAC between the lowest elastic modes of scenes A and B at their poses, within one model
    part (in-plane: the frame model; out-of-plane: the strip model), compared link by link at
    stations along each link, so two meshes, sections or poses of one linkage can be compared;
    the scenes must name the same links. Prints the MAC matrix and pairs the modes; writes
    mac.json and mac.csv to OUT/<A>+<B>/. The mesh is chosen as for in-plane modes."""
    from flexlink.analysis.mesh import DEFAULT_TOL, choose_mesh
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.scene import load_scene
    from flexlink.output.pose.mac_comparison import comparison_json, mac_csv, mac_text
    from flexlink.studies.pose.mac_comparison import compare_scenes, mac_part
    from ._written import publish, run_folder

    folder = run_folder(prepare_out_dir(out_dir), [scene_a, scene_b])
    a, b = load_scene(scene_a), load_scene(scene_b)
    part = mac_part(a, b, part if old_part is None else old_part)
    mesh_a = choose_mesh(a, n_modes, elements, DEFAULT_TOL)
    mesh_b = choose_mesh(b, n_modes, elements if elements_b is None else elements_b, DEFAULT_TOL)
    result = compare_scenes(a, b, n_modes, mesh_a.elements, mesh_b.elements, part=part)
    write_atomic(folder / "mac.csv", mac_csv(result))
    document = {"command": "mac", **comparison_json(result, n_modes)}
    publish(folder / "mac.json", document, [folder / "mac.csv"], mac_text(document, result.mac),
            as_json)
