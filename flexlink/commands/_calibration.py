"""The options of ``flexlink calibrate`` that set its study (``StudySettings``): starts, seed,
Monte Carlo samples and spreads, mesh and workers."""

import click

from flexlink.meshes import FIT_ELEMENTS


def settings_options(command):
    """Decorate a command with --starts, --seed, --samples, --vf-sd, --thickness-sd, -e and
    --jobs; ``study_settings`` turns their values into the study's settings."""
    for option in reversed((
            click.option("--starts", default=8, show_default=True, type=click.IntRange(1, 1000),
                         help="Least-squares starts per fit (the assumed inputs, then random "
                              "in ln p)."),
            click.option("--seed", default=0, show_default=True, type=int,
                         help="Seed of the start points and the Monte Carlo samples."),
            click.option("--samples", default=200, show_default=True,
                         type=click.IntRange(2, 10**6), help="Monte Carlo samples."),
            click.option("--vf-sd", default=0.05, show_default=True,
                         type=click.FloatRange(0, 0.5),
                         help="Standard deviation of the fibre volume fraction."),
            click.option("--thickness-sd", default="0.15 mm", show_default=True,
                         help="Standard deviation of the laminate thickness, with unit."),
            click.option("-e", "--elements", default=FIT_ELEMENTS, show_default=True,
                         type=click.IntRange(1, 10000),
                         help="Elements per link in every evaluation."),
            click.option("--jobs", default=-1, show_default=True, type=int,
                         help="Parallel workers (joblib; -1 = all cores)."))):
        command = option(command)
    return command


def study_settings(starts, seed, samples, vf_sd, thickness_sd, elements, jobs, show_progress):
    """The ``StudySettings`` of the options above (the thickness spread read with its unit)."""
    from flexlink.studies.calibration.calibration import StudySettings
    from flexlink.units import parse_quantity

    sd = parse_quantity(thickness_sd, "length", source="command line", field="--thickness-sd")
    return StudySettings(starts=starts, seed=seed, samples=samples, vf_sd=vf_sd, thickness_sd=sd,
                         elements=elements, n_jobs=jobs, show_progress=show_progress)
