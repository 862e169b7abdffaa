"""``flexlink modes SCENE --speed ...``: the modes at an operating point, beside the static ones."""

from __future__ import annotations

import click

from flexlink.commands._options import EnumChoice, dumps
from flexlink.fe.geometric import GeometricForm

_OPTIONS = (
    click.option("--speed", default=None, metavar="SPEED",
                 help="Crank speed with its unit, e.g. '2000 rev/min' or '209 rad/s': the modes "
                      "of the small vibrations about the rigid motion at that speed (inertia "
                      "preload, centrifugal and Coriolis terms), beside the static ones."),
    click.option("--crank-angle", default=None, metavar="ANGLE",
                 help="With --speed: the crank angle, e.g. '30 deg' [default: the scene's pose]."),
    click.option("--crank-acceleration", default=None, metavar="ACCELERATION",
                 help="With --speed: the crank's angular acceleration, e.g. '50 rad/s^2' "
                      "[default: 0, constant speed]."),
    click.option("--no-preload", is_flag=True, help="With --speed: leave out K_g(N)."),
    click.option("--no-centrifugal", is_flag=True,
                 help="With --speed: leave out the centrifugal softening."),
    click.option("--no-coriolis", is_flag=True,
                 help="With --speed: leave out the Coriolis (gyroscopic) coupling."),
    click.option("--geometric", type=EnumChoice(GeometricForm),
                 default="consistent", show_default=True,
                 help="With --speed: K_g of the cubic element, or of the chord only (as "
                      "OpenSees's PDelta)."),
)


def operating_options(command):
    """Decorator: the at-speed options of ``modes`` (passed on as keyword arguments)."""
    for option in reversed(_OPTIONS):
        command = option(command)
    return command


def operating_given(speed, crank_angle, crank_acceleration, no_preload, no_centrifugal,
                    no_coriolis, geometric, static_only: bool = False) -> bool:
    """Is this an operating-point run? The at-speed options without --speed are an error, and
    so are options of the static run (``static_only``: --sensitivity or --method given) with it."""
    from flexlink.errors import InputError
    if speed is not None:
        if static_only:
            raise InputError("--sensitivity and --method are for the static modes",
                             source="command line", field="--speed",
                             expected="--speed without --sensitivity and --method")
        return True
    if crank_angle is not None or crank_acceleration is not None or no_preload or \
            no_centrifugal or no_coriolis or geometric is not GeometricForm.CONSISTENT:
        raise InputError("--crank-angle, --crank-acceleration, --no-preload, --no-centrifugal, "
                         "--no-coriolis and --geometric need --speed", source="command line",
                         field="--speed", expected="a crank speed such as '2000 rev/min'")
    return False


def run_operating(files, n_modes, elements, tol, speed, crank_angle, crank_acceleration,
                  no_preload, no_centrifugal, no_coriolis, geometric, as_json, out) -> None:
    """Modes at speed of each scene file; writes OUT/<scene>/modes_at_speed.json and .csv."""
    from flexlink.analysis.mesh import choose_mesh
    from flexlink.errors import FlexlinkError
    from flexlink.fileio import write_atomic
    from flexlink.output.operating_report import (format_operating, operating_csv,
                                                  operating_summary)
    from flexlink.scene import load_scene
    from flexlink.studies.operating_point import Terms, operating_modes
    from flexlink.studies.torque import operating_point
    from flexlink.units import parse_quantity

    from ._failures import finish, scene_failure
    from ._written import announce, scene_folders

    omega = parse_quantity(speed, "angular speed", source="command line", field="--speed")
    angle = None if crank_angle is None else parse_quantity(
        crank_angle, "angle", source="command line", field="--crank-angle")
    qdd = None if crank_acceleration is None else parse_quantity(
        crank_acceleration, "angular acceleration", source="command line",
        field="--crank-acceleration")
    terms = Terms(preload=not no_preload, centrifugal=not no_centrifugal,
                  coriolis=not no_coriolis, geometric=geometric)
    folders = dict(zip(files, scene_folders(out, files)))
    summaries, written, failures = [], [], []
    for path in files:
        try:
            scene = load_scene(path)
            speed_, qdd_ = operating_point(scene, omega, qdd)  # checked as `torque` does
            mesh = choose_mesh(scene, n_modes, elements, tol)  # the static `modes` mesh
            op = operating_modes(scene, speed_, n_modes, mesh.elements, angle, qdd_, terms)
            summary = operating_summary(op)
        except FlexlinkError as exc:
            failures.append(scene_failure(path, exc))
            continue
        summaries.append(summary)
        json_path = folders[path] / "modes_at_speed.json"
        csv_path = folders[path] / "modes_at_speed.csv"
        write_atomic(json_path, dumps({"command": "modes --speed", "cases": [summary],
                                       "files": [str(json_path), str(csv_path)]}))
        write_atomic(csv_path, operating_csv([summary]))
        written += [json_path, csv_path]
    if as_json:
        click.echo(dumps({"command": "modes --speed", "cases": summaries,
                          "files": [str(p) for p in written], "failures": failures}))
    else:
        for s in summaries:
            click.echo(format_operating(s) + "\n")
        announce(written, as_json)
    finish(failures, len(files))
