"""``flexlink stability [SCENE]``: numerical stability on stiff and extreme cases."""

from __future__ import annotations

import sys

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import dumps, json_option, out_option


@click.command("stability")
@click.argument("scene_path", metavar="[SCENE]", default="cases/case1.toml", type=click.Path())
@click.option("--slow", is_flag=True, help="Also run the slow checks (1e5 DOFs; about a minute).")
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, slow, as_json, out_dir):
    """Run the stability checks on variants of SCENE (default cases/case1.toml): bearing
    stiffness 0 .. 1e30, free crank, slender to stubby links, toggle and unreachable poses,
    stiffness and mass contrast, large models, repeated eigenvalues, massless DOFs, a mechanism
    with the sparse solver, unit slips. Prints expected / got / pass per check; writes
    OUT/<scene>/stability.json. Exit code 1 if any check fails."""
    from tqdm import tqdm

    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.scene import load_scene
    from flexlink.studies.verification.self_checks import run_checks
    from ._written import announce, scene_folders

    [folder] = scene_folders(prepare_out_dir(out_dir), [scene_path])
    scene = load_scene(scene_path)

    def progress(items):
        return tqdm(items, desc="stability", unit="check", file=sys.stderr,
                    disable=as_json or not sys.stderr.isatty())

    checks = run_checks(scene, slow=slow, progress=progress)
    document = {"command": "stability", "scene": scene.path, "slow": slow,
                "passed": sum(c.passed for c in checks), "total": len(checks),
                "checks": [{"id": c.id, "name": c.name, "expected": c.expected, "got": c.got,
                            "passed": c.passed, "details": c.details} for c in checks],
                "files": [str(folder / "stability.json")]}
    write_atomic(folder / "stability.json", dumps(document))
    if as_json:
        click.echo(dumps(document))
    else:
        for c in checks:
            click.echo(f"[{'PASS' if c.passed else 'FAIL'}] {c.id}: {c.name}\n"
                       f"        expected: {c.expected}\n        got:      {c.got}")
        click.echo(f"\n{document['passed']} of {document['total']} checks passed"
                   + ("" if slow else " (slow checks skipped: --slow)"))
        announce(document["files"], as_json)
    if document["passed"] != document["total"]:
        sys.exit(1)
