"""``flexlink calibrate SCENE...``: fit assumed inputs to the measured table, cross-validate,
test the mode ratios, propagate material scatter, and write a Markdown report with plots."""

import shlex
import sys

import click

from flexlink.commands._calibration import settings_options, study_settings
from flexlink.commands._failures import names_scene
from flexlink.commands._options import (EnumChoice, dumps, json_option, out_option,
                                        scheduler_option)
from flexlink.fe.motions import ModelFamily


@click.command("calibrate")
@click.argument("scenes", nargs=-1, required=True, type=click.Path())
@click.option("--free", "free_specs", multiple=True, metavar="NAME=LOW:HIGH", help="A free input "
              "with bounds and units, e.g. 'L1=100 mm:1 m' (repeat). Names: L1, width, thickness, "
              "Kt, Kr, drive, joint_mass, Ktilt. Default: every input that affects the family, "
              "with wide physical bounds.")
@click.option("--family", "families", multiple=True, default=("scene",), show_default=True,
              type=EnumChoice(ModelFamily, none="scene"), help="Model family "
              "(repeat to compare; 'scene' = the first scene's [model] family).")
@settings_options
@scheduler_option("the fits and the Monte Carlo")
@json_option
@out_option
@names_scene("scenes")
def command(scenes, free_specs, families, scheduler, as_json, out_dir, **settings):
    """Calibrate each model family against the scenes' Ex column (and, separately, the paper's
    FE), cross-validate leaving one case out, fit each case alone and its mode ratios, and
    propagate Table I scatter by Monte Carlo; writes calibrate.json, report.md and PNG plots
    to OUT/<scene names>/ (e.g. OUT/cases/ for the folder cases/)."""
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.output.calibration.calibration import calibrate_document, study_document
    from flexlink.output.calibration.calibration_report import report_files, summary_text
    from flexlink.parallel import use_scheduler
    from flexlink.scene import scene_files
    from flexlink.studies.calibration.fit import parse_free
    from flexlink.studies.calibration.calibration import run_study, study_families
    from ._written import announce, run_folder

    out = run_folder(prepare_out_dir(out_dir), scenes)
    files = [str(f) for f in scene_files(scenes)]
    free = tuple(parse_free(s) for s in free_specs) or None
    settings = study_settings(**settings, show_progress=sys.stderr.isatty() and not as_json)
    studies, written = [], []
    with use_scheduler(scheduler):
        for family in study_families(families, files):  # each kept as soon as it is done
            studies.append(run_study(files, family, free, settings))
            written.append(write_atomic(out / f"study-{family}.json",
                                        dumps(study_document(studies[-1]))))
    line = "flexlink calibrate " + " ".join(shlex.quote(a) for a in sys.argv[2:])
    written += [write_atomic(out / name, data)
                for name, data in report_files(studies, line).items()]
    document = calibrate_document(studies, [*written, out / "calibrate.json"])
    written.append(write_atomic(out / "calibrate.json", dumps(document)))
    click.echo(dumps(document) if as_json else summary_text(studies))
    announce(written, as_json)
