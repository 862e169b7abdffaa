"""``flexlink calibrate SCENE...``: fit assumed inputs to the measured table, cross-validate,
test the mode ratios, propagate material scatter, and write a Markdown report with plots."""

from __future__ import annotations

import shlex
import sys

import click

from flexlink.commands._failures import names_scene
from flexlink.meshes import FIT_ELEMENTS
from flexlink.commands._options import dumps, json_option, out_option, scheduler_option


@click.command("calibrate")
@click.argument("scenes", nargs=-1, required=True, type=click.Path())
@click.option("--free", "free_specs", multiple=True, metavar="NAME=LOW:HIGH",
              help="A free input with bounds and units, e.g. 'L1=100 mm:1 m' (repeat). Names: "
                   "L1, width, thickness, Kt, Kr, drive, joint_mass, Ktilt. Default: every "
                   "input that affects the family, with wide physical bounds.")
@click.option("--family", "families", multiple=True,
              type=click.Choice(["scene", "planar", "out-of-plane", "3d"]), default=("scene",),
              show_default=True, help="Model family (repeat to compare; 'scene' = the first "
                                      "scene's [model] family).")
@click.option("--starts", default=8, show_default=True, type=click.IntRange(1, 1000),
              help="Least-squares starts per fit (the assumed inputs, then random in ln p).")
@click.option("--seed", default=0, show_default=True, type=int,
              help="Seed of the start points and the Monte Carlo samples.")
@click.option("--samples", default=200, show_default=True, type=click.IntRange(2, 10**6),
              help="Monte Carlo samples.")
@click.option("--vf-sd", default=0.05, show_default=True, type=click.FloatRange(0, 0.5),
              help="Standard deviation of the fibre volume fraction.")
@click.option("--thickness-sd", default="0.15 mm", show_default=True,
              help="Standard deviation of the laminate thickness, with unit.")
@click.option("-e", "--elements", default=FIT_ELEMENTS, show_default=True,
              type=click.IntRange(1, 10000),
              help="Elements per link in every evaluation.")
@click.option("--jobs", default=-1, show_default=True, type=int,
              help="Parallel workers (joblib; -1 = all cores).")
@scheduler_option("the fits and the Monte Carlo")
@json_option
@out_option
@names_scene("scenes")
def command(scenes, free_specs, families, starts, seed, samples, vf_sd, thickness_sd, elements,
            jobs, scheduler, as_json, out_dir):
    """Calibrate each model family against the scenes' Ex column (and, separately, the paper's
    FE), cross-validate leaving one case out, fit each case alone and its mode ratios, and
    propagate Table I scatter by Monte Carlo; writes calibrate.json, report.md and PNG plots
    to OUT/<scene names>/ (e.g. OUT/cases/ for the folder cases/)."""
    from flexlink.studies.calibration import parse_free
    from flexlink.output.calibration_report import PLOTS, best_family, mean_text, report_markdown
    from flexlink.studies.comparison import StudySettings, run_study
    from flexlink.analysis.families import scene_family
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.parallel import use_scheduler
    from flexlink.scene import load_scene, scene_files
    from flexlink.units import parse_quantity
    from ._written import announce, run_folder

    out = run_folder(prepare_out_dir(out_dir), scenes)
    files = [str(f) for f in scene_files(scenes)]
    free = tuple(parse_free(s) for s in free_specs) or None
    settings = StudySettings(
        starts=starts, seed=seed, samples=samples, vf_sd=vf_sd,
        thickness_sd=parse_quantity(thickness_sd, "length", source="command line",
                                    field="--thickness-sd"),
        elements=elements, n_jobs=jobs, progress=sys.stderr.isatty() and not as_json)
    chosen = []
    for fam in families:
        fam = scene_family(load_scene(files[0])) if fam == "scene" else fam
        if fam not in chosen:
            chosen.append(fam)

    studies, written = [], []
    with use_scheduler(scheduler):
        for fam in chosen:  # each family's study is kept as soon as it is done
            studies.append(run_study(files, fam, free, settings))
            written.append(write_atomic(out / f"study-{fam}.json", dumps(studies[-1])))
    plots = {}
    for study in studies:
        fam = study["family"]
        plots[fam] = {}
        for name, draw in PLOTS.items():
            file = f"{name}-{fam}.png"
            written.append(write_atomic(out / file, draw(study)))
            plots[fam][name] = file
    line = "flexlink calibrate " + " ".join(shlex.quote(a) for a in sys.argv[2:])
    written.append(write_atomic(out / "report.md", report_markdown(studies, plots, line)))
    written.append(out / "calibrate.json")
    document = {"command": "calibrate", "studies": studies, "files": [str(p) for p in written]}
    if len(studies) > 1:
        best = best_family(studies)
        document["best_family_by_cross_validation"] = best and best["family"]
    write_atomic(out / "calibrate.json", dumps(document))
    if as_json:
        click.echo(dumps(document))
        return
    for s in studies:
        click.echo(f"family {s['family']}: mean |error| vs Ex: assumed inputs "
                   f"{mean_text(s, 'assumed_inputs_vs_Ex')} %, calibrated "
                   f"{mean_text(s, 'calibrated_to_Ex_in_sample')} % (in sample), cross-validated "
                   f"{mean_text(s, 'cross_validated_vs_Ex')} %; paper FE vs Ex "
                   f"{mean_text(s, 'paper_FE_vs_Ex')} %")
        click.echo("  fitted to Ex: " + ", ".join(
            f"{p['name']} = {p['value']:.4g} {p['unit']}" for p in s["fit_Ex"]["parameters"]))
        u = s["uncertainty_calibrated"]
        click.echo(f"  Ex inside the 95 % Monte Carlo interval (calibrated inputs): "
                   f"{u['Ex_inside_count']} of {u['count']} modes")
    if len(studies) > 1:
        click.echo(f"best family by cross-validated error: {document['best_family_by_cross_validation']}")
    announce(written, as_json)
