"""The --sensitivity options and run shared by ``modes`` and ``report``: every assumed input at
both ends of its range, and a Monte Carlo 95 % interval over them with the Table I spreads."""

from __future__ import annotations

import click


def sensitivity_options(command):
    """Decorate a command with --sensitivity, --samples, --seed and -j/--jobs."""
    for option in reversed((
            click.option("--sensitivity", is_flag=True,
                         help="Also evaluate every assumed input at both ends of its range and "
                              "a Monte Carlo 95 % interval over them with the Table I spreads."),
            click.option("--samples", default=200, show_default=True,
                         type=click.IntRange(10, 100000),
                         help="Monte Carlo samples per scene (with --sensitivity)."),
            click.option("--seed", default=1, show_default=True, type=int,
                         help="Monte Carlo seed."),
            click.option("-j", "--jobs", default=-1, show_default=True, type=int,
                         help="Worker processes for --sensitivity (-1: one per core)."))):
        command = option(command)
    return command


def scene_sensitivity(scene, n_modes: int, samples: int, seed: int, jobs: int,
                      quiet: bool) -> dict:
    """JSON-ready end points and interval of ``scene`` (``output.sensitivity_report``)."""
    from flexlink.output.sensitivity_report import sensitivity_dict
    from flexlink.studies.sensitivity import STUDY_ELEMENTS, end_points, interval

    points = end_points(scene.path, n_modes, STUDY_ELEMENTS, jobs, not quiet)
    spread = interval(scene.path, samples, seed, n_modes, STUDY_ELEMENTS, jobs, not quiet)
    reference = dict(scene.reference.columns) if scene.reference else {}
    return sensitivity_dict(points, spread, reference, STUDY_ELEMENTS)
