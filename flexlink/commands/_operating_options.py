"""The at-speed options of ``flexlink modes`` (--speed and the options that need it), read into
the operating point the study is asked for (``studies.running.modes_at_speed.OperatingRequest``)."""

from __future__ import annotations

import click

from flexlink.commands._options import EnumChoice, stacked
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


operating_options = stacked(_OPTIONS)  # the at-speed options of ``modes``, as keywords


def operating_request(speed, crank_angle, crank_acceleration, no_preload, no_centrifugal,
                      no_coriolis, geometric, static_only: bool = False):
    """The operating point the options ask for (a ``studies.running.modes_at_speed.OperatingRequest``),
    or None for the static modes. The at-speed options without --speed are an error, and so are
    options of the static run (``static_only``: --sensitivity or --method given) with it."""
    from flexlink.errors import InputError
    from flexlink.commands._speeds import parse_acceleration, parse_speed
    from flexlink.fe.speed_terms import Terms
    from flexlink.studies.running.modes_at_speed import OperatingRequest
    from flexlink.units import parse_quantity

    if speed is None:
        if crank_angle is not None or crank_acceleration is not None or no_preload or \
                no_centrifugal or no_coriolis or geometric is not GeometricForm.CONSISTENT:
            raise InputError("--crank-angle, --crank-acceleration, --no-preload, "
                             "--no-centrifugal, --no-coriolis and --geometric need --speed",
                             source="command line", field="--speed",
                             expected="a crank speed such as '2000 rev/min'")
        return None
    if static_only:
        raise InputError("--sensitivity and --method are for the static modes",
                         source="command line", field="--speed",
                         expected="--speed without --sensitivity and --method")

    return OperatingRequest(
        speed=parse_speed(speed),
        crank_angle=None if crank_angle is None else parse_quantity(
            crank_angle, "angle", source="command line", field="--crank-angle"),
        crank_acceleration=parse_acceleration(crank_acceleration),
        terms=Terms(preload=not no_preload, centrifugal=not no_centrifugal,
                    coriolis=not no_coriolis, geometric=geometric))
