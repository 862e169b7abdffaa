"""The drawing options of ``flexlink export``: how finely, how many frames, how large, and
whether to draw pictures."""

from __future__ import annotations

import click

_OPTIONS = (
    click.option("--subdivide", default=4, show_default=True, type=click.IntRange(1, 64),
                 help="Segments per element (the element's own shape functions between nodes)."),
    click.option("--phases", default=24, show_default=True, type=click.IntRange(2, 1000),
                 help="Animation frames per period."),
    click.option("--amplitude", default=0.1, show_default=True,
                 type=click.FloatRange(0, 1, min_open=True),
                 help="Largest drawn displacement, as a fraction of the mechanism size."),
    click.option("--pictures/--no-pictures", default=True, show_default=True,
                 help="Draw PNGs of the modes (pyvista, off screen; needs OpenGL). The frequency "
                      "plot (matplotlib) is drawn either way."),
    click.option("--common-phase", is_flag=True,
                 help="Animation time as the fraction of the period (0 ... 1 for every mode, so "
                      "modes play side by side in ParaView) instead of seconds."),
)


def export_options(command):
    """Decorate a command with --subdivide, --phases, --amplitude, --pictures/--no-pictures
    and --common-phase."""
    for option in reversed(_OPTIONS):
        command = option(command)
    return command
