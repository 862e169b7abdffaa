"""The at-speed options of ``flexlink modes`` (--speed and the options that need it), read into
the operating point the study is asked for (``studies.running.modes_at_speed.OperatingRequest``)."""

from __future__ import annotations

import click

from flexlink.commands._options import EnumChoice, stacked
from flexlink.fe.geometric import GeometricForm

# --terms names -> the Terms field each switches (acceleration: the circulatory alpha S term)
TERM_NAMES = ("preload", "centrifugal", "coriolis", "acceleration")

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
    click.option("--terms", default=None, metavar="LIST",
                 help="With --speed: the speed terms that enter, comma-separated from "
                      f"{', '.join(TERM_NAMES)} (or 'none') [default: all]; 'preload' alone is "
                      "the preloaded frame that OpenSees checks (docs/operating-point.md)."),
    click.option("--geometric", type=EnumChoice(GeometricForm),
                 default="consistent", show_default=True,
                 help="With --speed: K_g of the cubic element, or of the chord only (as "
                      "OpenSees's PDelta)."),
)


operating_options = stacked(_OPTIONS)  # the at-speed options of ``modes``, as keywords


def chosen_terms(text: str | None, no_preload: bool, no_centrifugal: bool,
                 no_coriolis: bool) -> dict[str, bool]:
    """Which speed terms enter, from --terms (a comma-separated list of TERM_NAMES, or
    'none') or else the --no-* flags; InputError naming --terms for an unknown name or for
    --terms given with a --no-* flag."""
    from flexlink.errors import InputError

    flags = {"--no-preload": no_preload, "--no-centrifugal": no_centrifugal,
             "--no-coriolis": no_coriolis}
    if text is None:
        return {"preload": not no_preload, "centrifugal": not no_centrifugal,
                "coriolis": not no_coriolis, "acceleration": True}
    expected = f"a comma-separated list of {', '.join(TERM_NAMES)}, or 'none'"
    given = [flag for flag, on in flags.items() if on]
    if given:
        raise InputError(f"--terms lists the terms that enter; {given[0]} as well would say it "
                         "twice", source="command line", field="--terms", expected=expected)
    names = [] if text.strip() == "none" else [n.strip() for n in text.split(",")]
    unknown = [n for n in names if n not in TERM_NAMES]
    if unknown or not text.strip():
        raise InputError(f"unknown term {unknown[0] if unknown else text!r}",
                         source="command line", field="--terms", expected=expected)
    return {name: name in names for name in TERM_NAMES}


def operating_request(speed, crank_angle, crank_acceleration, no_preload, no_centrifugal,
                      no_coriolis, terms, geometric, static_only: bool = False):
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
                no_centrifugal or no_coriolis or terms is not None or \
                geometric is not GeometricForm.CONSISTENT:
            raise InputError("--crank-angle, --crank-acceleration, --no-preload, "
                             "--no-centrifugal, --no-coriolis, --terms and --geometric need "
                             "--speed",
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
        terms=Terms(**chosen_terms(terms, no_preload, no_centrifugal, no_coriolis),
                    geometric=geometric))
