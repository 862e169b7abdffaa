"""``flexlink prb SCENE``: a partially compliant linkage's FE modes beside its pseudo-rigid-body
first frequency."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import json_option, out_option


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
    from flexlink.output.pose.prb import prb_document, prb_text
    from flexlink.studies.pose.prb import compare_prb
    from ._written import folder_and_scene, publish

    folder, scene = folder_and_scene(out_dir, scene_path)
    document = prb_document(scene, compare_prb(scene, n_modes, elements))
    publish(folder / "prb.json", document, [], prb_text(document), as_json)
