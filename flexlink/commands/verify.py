"""``flexlink verify [SCENE]``: the numerical self-checks on stiff and extreme variants of a
scene (not the parametric stability of the running linkage, which is ``stability-map``)."""

from __future__ import annotations

import sys

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import json_option, out_option, stacked


def run_self_checks(scene_path, slow: bool, as_json: bool, out_dir) -> None:
    """Run the checks, publish ``OUT/<scene>/verify.json`` and the text; exit code 1 if any
    check fails."""
    from tqdm import tqdm

    from flexlink.output.verification.self_checks import self_checks_document, self_checks_text
    from flexlink.studies.verification.self_checks import run_checks
    from ._written import folder_and_scene, publish

    folder, scene = folder_and_scene(out_dir, scene_path)

    def progress(items):
        return tqdm(items, desc="verify", unit="check", file=sys.stderr,
                    disable=as_json or not sys.stderr.isatty())

    document = self_checks_document(scene, run_checks(scene, slow=slow, progress=progress), slow)
    publish(folder / "verify.json", document, [], self_checks_text(document), as_json)
    if document["passed"] != document["total"]:
        sys.exit(1)


# the arguments and options of verify and of its old name, stability
self_check_options = stacked([
    click.argument("scene_path", metavar="[SCENE]", default="cases/case1.toml",
                   type=click.Path()),
    click.option("--slow", is_flag=True,
                 help="Also run the slow checks (1e5 DOFs; about a minute)."),
    json_option, out_option, names_scene("scene_path")])


@click.command("verify")
@self_check_options
def command(scene_path, slow, as_json, out_dir):
    """Run the numerical self-checks on variants of SCENE (default cases/case1.toml): bearing
    stiffness 0 .. 1e30, free crank, slender to stubby links, toggle and unreachable poses,
    stiffness and mass contrast, large models, repeated eigenvalues, massless DOFs, a mechanism
    with the sparse solver, unit slips. Prints expected / got / pass per check; writes
    OUT/<scene>/verify.json. Exit code 1 if any check fails."""
    run_self_checks(scene_path, slow, as_json, out_dir)
