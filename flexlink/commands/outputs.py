"""``flexlink outputs SCENE``: output torques, transmission ratios and pin forces over one crank
turn for a given input torque, and (``--study``) how speed, input torque and friction change
the ratios."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import EnumChoice, json_option, out_option, turn_poses_option
from flexlink.kinematics.kinetostatics import Sharing

WHERE = "command line"


@click.command("outputs")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("--input-torque", default=None,
              help="Constant torque on the driver, e.g. '80 N m' (default: the scene's "
                   "kinetostatics.input_torque).")
@click.option("--input-torque-csv", "torque_csv", default=None, type=click.Path(),
              help="Instead: a CSV of the input torque over the crank angle (header row; crank "
                   "angle [deg] evenly over one turn, then the torque in --unit).")
@click.option("--unit", default="N*m", show_default=True,
              help="Unit of --input-torque-csv's torques.")
@click.option("--output", "outputs", multiple=True,
              help="An output body, in the order the torque flows (repeat for several; "
                   "default: the scene's kinetostatics.outputs).")
@click.option("--sharing", default=None, type=EnumChoice(Sharing),
              help="How outputs share the input (default: the scene's, else series).")
@click.option("--share", default=None, type=float,
              help="With --sharing split: the first output's share of the input power.")
@click.option("--friction", default=None, type=float,
              help="Contact-friction factor m of the first output, in [0, 1).")
@click.option("--efficiency", default=None, type=float,
              help="Bearing transmission efficiency eta, in (0, 1].")
@click.option("--speed", default=None, help="Crank speed, e.g. '2000 rev/min' (default: the "
              "scene's operation.crank_speed and crank_acceleration, else 0: at rest).")
@turn_poses_option
@click.option("--study", is_flag=True, help="Also the one-factor-at-a-time study over crank "
              "speed (0-3000 rev/min), input torque (0-1000 N m), m (0-0.9) and eta (0.6-1).")
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, input_torque, torque_csv, unit, outputs, sharing, share, friction,
            efficiency, speed, poses, study, as_json, out_dir):
    """Output torque at each output body of SCENE for a given input torque at the driver,
    with the transmission ratios, pin and ground forces, dead points and the losses of
    friction m and bearing efficiency eta. Writes outputs.csv, outputs.png and outputs.json
    (with --study also parametric.csv and parametric.png) to OUT/<scene>/."""
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.output.kinetostatics.outputs import (outputs_csv, outputs_document,
                                                       outputs_plot, outputs_text)
    from flexlink.scene import load_scene
    from flexlink.studies.kinetostatics.outputs import output_study
    from flexlink.units import parse_quantity
    from ._kinetostatics import kinetostatics_overrides
    from ._progress import progress_bar
    from ._written import publish, scene_folders

    overrides = kinetostatics_overrides(input_torque, torque_csv, unit, outputs, sharing, share,
                                        friction, efficiency)
    omega = None if speed is None else parse_quantity(speed, "angular speed", source=WHERE,
                                                      field="--speed")
    [folder] = scene_folders(prepare_out_dir(out_dir), [scene_path])
    scene = load_scene(scene_path, overrides)
    acceleration = 0.0
    if omega is None:  # the scene's operating point, with its crank acceleration if any
        omega = scene.options.crank_speed or 0.0
        acceleration = scene.options.crank_acceleration or 0.0
    curve = output_study(scene, omega, acceleration, poses,
                         progress=progress_bar("outputs", as_json))
    files = [folder / "outputs.csv", folder / "outputs.png"]
    write_atomic(files[0], outputs_csv(curve))
    write_atomic(files[1], outputs_plot(curve))
    document = outputs_document(curve, [f"{a.field}: {a.note}" for a in scene.assumptions], [])
    text = outputs_text(document)
    if study:
        from flexlink.output.kinetostatics.parametric import (parametric_csv,
                                                              parametric_document,
                                                              parametric_plot, parametric_text)
        from flexlink.studies.kinetostatics.parametric import parametric_study

        result = parametric_study(scene, omega, progress=progress_bar("study", as_json, "run"))
        more = [folder / "parametric.csv", folder / "parametric.png"]
        write_atomic(more[0], parametric_csv(result))
        write_atomic(more[1], parametric_plot(result))
        files += more
        document["parametric"] = parametric_document(result)
        text += "\n" + parametric_text(document["parametric"])
    document.pop("files")
    publish(folder / "outputs.json", document, files, text, as_json)
