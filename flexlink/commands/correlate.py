"""``flexlink correlate SCENE TEST``: a modal test's mode shapes against the scene's model."""

from __future__ import annotations

import click

from flexlink.commands._options import json_option, mesh_options, out_option


@click.command("correlate")
@click.argument("scene", type=click.Path())
@click.argument("test", type=click.Path())
@click.option("-n", "--modes", "n_modes", default=None, type=click.IntRange(1, 200),
              help="Model modes to pair with [default: the test's modes + 4, so a mode out "
                   "of order still finds its partner].")
@mesh_options(method=False)
@click.option("--pictures/--no-pictures", default=True, show_default=True,
              help="Draw the MAC heat map and the shape overlay (matplotlib).")
@json_option
@out_option
def command(scene, test, n_modes, elements, tol, pictures, as_json, out_dir):
    """Correlate the modal TEST (UFF datasets 55 with geometry 15 or 2411, or a CSV of sensor
    points, directions, shapes, frequencies and damping) with SCENE's model at its pose: each
    sensor placed on its link by the scene's [test] table (unit, offset, rotation,
    max_distance), the model's modes read there by the element interpolation, the modes paired
    by MAC (optimal assignment; >= 0.9 good, 0.7-0.9 doubtful, below unpaired), their
    frequency errors, the unpaired modes of both sides, CoMAC per channel, the test's autoMAC
    (spatial aliasing). Writes correlation.json, correlation_pairs.csv, correlation_mac.csv,
    correlation_model.vtu and correlation_test.vtu (ParaView), correlation_mac.png and
    correlation_shapes.png to OUT/<scene>/."""
    from flexlink.analysis.mesh import choose_mesh
    from flexlink.output.correlation.correlation import (correlation_json, correlation_text,
                                                         write_correlation_files)
    from flexlink.studies.correlation.correlation import SPARE_MODES, correlate_test
    from flexlink.studies.correlation.measured import read_test
    from ._written import folder_and_scene, publish

    folder, loaded = folder_and_scene(out_dir, scene)
    measured = read_test(test)
    n_model = n_modes or measured.n_modes + SPARE_MODES
    mesh = choose_mesh(loaded, n_model, elements, tol)
    result = correlate_test(loaded, measured, n_model, mesh.elements)
    document = {"command": "correlate", **correlation_json(result)}
    files = write_correlation_files(folder, result, document, pictures)
    publish(folder / "correlation.json", document, files, correlation_text(document), as_json)
