"""``flexlink prb SCENE``: a partially compliant linkage's FE modes beside its pseudo-rigid-body
first frequency."""

from __future__ import annotations

import math

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import dumps, json_option, out_option


@click.command("prb")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("-n", "--modes", "n_modes", default=4, show_default=True,
              type=click.IntRange(1, 50), help="FE elastic modes to list.")
@click.option("-e", "--elements", default=None, type=click.IntRange(1, 100000),
              help="Elements per link (default: the scene's).")
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, n_modes, elements, as_json, out_dir):
    """Modes of SCENE (a scene with a [prb] table) at its start pose, where the compliant strip
    is unstressed, with the strip as a flexible beam (FE), and the first frequency of the
    pseudo-rigid-body model (rigid link + torsional spring K = gamma K_Theta E I / l)."""
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.scene import load_scene
    from flexlink.studies.prb import compare_prb
    from ._written import announce, scene_folders

    [folder] = scene_folders(prepare_out_dir(out_dir), [scene_path])
    scene = load_scene(scene_path)
    result = compare_prb(scene, n_modes, elements)
    prb, fe = result.prb, list(result.fe)
    document = {
        "command": "prb", "scene": scene.name, "synthesis": scene.synthesis,
        "pose_crank_deg": math.degrees(result.crank_angle),
        "points_m": result.points,
        "fe_Hz": fe,
        "prb": {"spring_N_m_per_rad": prb.spring, "generalized_stiffness_N_m": prb.stiffness,
                "generalized_mass_kg_m2": prb.mass, "first_Hz": prb.frequency},
        "prb_vs_fe_pct": result.prb_vs_fe_pct,
        "assumptions": [f"{a.field}: {a.note}" for a in scene.assumptions],
    }
    path = folder / "prb.json"
    document["files"] = [str(path)]
    write_atomic(path, dumps(document))
    if as_json:
        click.echo(dumps(document))
        return
    s = scene.synthesis
    click.echo(scene.name)
    if s:
        click.echo(f"  synthesis {s['method']} {s['inputs']}: " + ", ".join(
            f"{k} {1e3 * v:.3f} mm" for k, v in s["lengths_m"].items()))
    click.echo(f"  pose: crank {document['pose_crank_deg']:.3f} deg (strip straight)")
    click.echo("  FE modes [Hz]: " + ", ".join(f"{f:.3f}" for f in fe))
    click.echo(f"  PRB: K = {prb.spring:.4f} N m/rad, k_q = {prb.stiffness:.4f} N m, m_q = "
               f"{prb.mass:.5g} kg m^2, first frequency {prb.frequency:.3f} Hz "
               f"({document['prb_vs_fe_pct']:+.1f} % vs FE {fe[0]:.3f} Hz)")
    announce([path], as_json)
