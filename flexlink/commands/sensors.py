"""``flexlink sensors SCENE --count N``: where to put N sensors, by Effective Independence."""

from __future__ import annotations

import click

from flexlink.commands._options import json_option, mesh_options, out_option


@click.command("sensors")
@click.argument("scene", type=click.Path())
@click.option("--count", required=True, type=click.IntRange(1, 10000),
              help="Sensor channels to place (at least --modes).")
@click.option("--modes", "n_modes", default=4, show_default=True, type=click.IntRange(1, 200),
              help="Target modes: the lowest elastic modes of the scene's family.")
@click.option("--stations", default=20, show_default=True, type=click.IntRange(2, 2000),
              help="Segments per link: its inner stations are the candidate positions.")
@mesh_options(method=False)
@click.option("--uff-geometry", type=click.Choice(["15", "2411"]), default="15",
              show_default=True, help="UFF dataset of the layout's geometry.")
@click.option("--pictures/--no-pictures", default=True, show_default=True,
              help="Draw the layout on the linkage (matplotlib).")
@json_option
@out_option
def command(scene, count, n_modes, stations, elements, tol, uff_geometry, pictures, as_json,
            out_dir):
    """Pick COUNT sensor positions and directions on SCENE's links for its lowest --modes
    modes by Effective Independence (Kammer 1991), and compare them with a uniform layout of
    the same count: the largest off-diagonal autoMAC and the determinant of the Fisher
    information. Writes sensors.json, sensors.csv, sensors.uff (the layout with the predicted
    mode shapes) and sensors.png to OUT/<scene>/."""
    from flexlink.analysis.mesh import choose_mesh
    from flexlink.output.correlation.sensor_plan import plan_json, plan_text, write_plan_files
    from flexlink.studies.correlation.sensor_plan import plan_sensors
    from ._written import folder_and_scene, publish

    folder, loaded = folder_and_scene(out_dir, scene)
    mesh = choose_mesh(loaded, n_modes, elements, tol)
    plan = plan_sensors(loaded, count, n_modes, mesh.elements, stations)
    document = {"command": "sensors", **plan_json(plan)}
    files = write_plan_files(folder, plan, int(uff_geometry), pictures)
    publish(folder / "sensors.json", document, files, plan_text(document), as_json)
