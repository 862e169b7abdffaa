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
@click.option("--test", "test_file", type=click.Path(), default=None,
              help="Instead of the scenes' reference columns: fit the one SCENE to this modal "
                   "test (UFF or CSV, as `flexlink correlate` reads), its frequencies paired "
                   "by MAC at every step; needs --free. Writes calibrate-test.json.")
@click.option("--mac-weight", default=0.0, show_default=True, type=click.FloatRange(0, 100),
              help="With --test: weight w of the residuals w (1 - MAC) of the pairs.")
@scheduler_option("the fits and the Monte Carlo")
@json_option
@out_option
@names_scene("scenes")
def command(scenes, free_specs, families, test_file, mac_weight, scheduler, as_json, out_dir,
            **settings):
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
    if test_file is not None:
        _fit_to_test(out, files, test_file, free, mac_weight, settings["elements"], as_json)
        return
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


def _fit_to_test(out, files, test_file, free, mac_weight, elements, as_json) -> None:
    """``calibrate SCENE --test FILE``: the fit of the free inputs to the test."""
    from flexlink.errors import InputError
    from flexlink.output.calibration.by_test import by_test_json, by_test_text
    from flexlink.studies.calibration.by_test import fit_to_test
    from flexlink.studies.correlation.measured import read_test
    from ._written import publish

    if len(files) != 1:
        raise InputError(f"{len(files)} scenes: a test belongs to one", source="command line",
                         field="SCENES", expected="one scene file with --test")
    if free is None:
        raise InputError("--test needs the inputs to fit", source="command line",
                         field="--free", expected="e.g. --free 'Kt=1e5 N/m:1e8 N/m'")
    fit = fit_to_test(files[0], read_test(test_file), free, elements, mac_weight)
    document = {"command": "calibrate", **by_test_json(fit)}
    publish(out / "calibrate-test.json", document, [], by_test_text(document), as_json)
