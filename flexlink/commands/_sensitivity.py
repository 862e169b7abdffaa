"""The --sensitivity options and run shared by ``modes`` and ``report``: every assumed input at
both ends of its range, and a Monte Carlo 95 % interval over them with the Table I spreads."""

from __future__ import annotations

import click

from flexlink.commands._options import scheduler_option


def sensitivity_options(command):
    """Decorate a command with --sensitivity, --samples, --seed, -j/--jobs and --scheduler."""
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
                         help="Worker processes for --sensitivity (-1: one per core)."),
            scheduler_option("the --sensitivity end points and Monte Carlo"))):
        command = option(command)
    return command


def sensitivity_scheduler(sensitivity: bool, scheduler: str | None):
    """The ``parallel.use_scheduler`` block of a command's scenes: --scheduler runs the
    --sensitivity evaluations, so it is refused without --sensitivity rather than ignored."""
    from flexlink.parallel import use_scheduler

    if scheduler is not None and not sensitivity:
        raise click.UsageError("--scheduler runs the --sensitivity evaluations: give "
                               "--sensitivity too, or leave --scheduler out")
    return use_scheduler(scheduler)


def sensitivity_run(sensitivity: bool, samples: int, seed: int, jobs: int, quiet: bool):
    """The ``studies.pose.scene_summary.SensitivityRun`` the options ask for; None without
    --sensitivity. ``quiet``: no progress bar (with --json)."""
    from flexlink.studies.pose.scene_summary import SensitivityRun

    return SensitivityRun(samples, seed, jobs, not quiet) if sensitivity else None
