"""``flexlink modes SCENE...``: natural frequencies at the scene's pose vs its reference table."""

from __future__ import annotations

import logging

import click

from flexlink.commands._operating import operating_given, operating_options, run_operating
from flexlink.commands._options import dumps, json_option, mesh_options, out_option
from flexlink.commands._sensitivity import (scene_sensitivity, sensitivity_options,
                                           sensitivity_scheduler)


@click.command("modes")
@click.argument("scenes", nargs=-1, required=True, type=click.Path())
@click.option("-n", "--modes", "n_modes", default=4, show_default=True,
              type=click.IntRange(1, 200), help="Number of elastic modes to report.")
@mesh_options()
@sensitivity_options
@json_option
@out_option
@operating_options
def command(scenes, n_modes, elements, solver, tol, sensitivity, samples, seed, jobs, scheduler,
            as_json, out_dir, **at_speed):
    """Natural frequencies of each SCENE (a scene file or a folder of them) at its pose,
    compared with the scene's reference columns (measured Ex, published FE). Writes
    OUT/<scene>/modes.json and modes.csv per scene, and OUT/modes.json and modes.csv with
    every scene when there are several. With --speed: the modes about the rigid motion at that
    crank speed beside the static ones, in OUT/<scene>/modes_at_speed.json and .csv."""
    from flexlink.analysis.eigensolver import DEFAULT_SOLVER
    from flexlink.analysis.families import elastic_modes, scene_family
    from flexlink.fe.motions import ModelFamily
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.output.report import case_summary, comparison_csv, format_case
    from flexlink.scene import scene_files
    from flexlink.errors import FlexlinkError
    from ._analysed import analysed_scene
    from ._failures import finish, scene_failure
    from ._written import announce, scene_folders

    # analysis warnings come back in result.warnings and are printed with their case below;
    # logging them as well would show each one twice
    logging.getLogger("flexlink.analysis.modal").setLevel(logging.ERROR)
    out = prepare_out_dir(out_dir)
    files = scene_files(scenes)
    if operating_given(static_only=sensitivity or solver != DEFAULT_SOLVER, **at_speed):
        return run_operating(files, n_modes, elements, tol, **at_speed, as_json=as_json, out=out)
    all_folders = dict(zip(files, scene_folders(out, files)))
    summaries, meshes, folders, failures = [], [], [], []
    with sensitivity_scheduler(sensitivity, scheduler):  # one cluster for every scene
        for path in files:
            try:
                scene, mesh, result = analysed_scene(path, n_modes, elements, tol, solver)
                family = scene_family(scene)
                other = {} if family is ModelFamily.PLANAR else dict(zip(
                    ("computed", "kinds"), elastic_modes(scene, n_modes, mesh.elements, solver)))
                summary = {**case_summary(result, n_modes, family, **other),
                           "mesh": mesh.as_dict(), "warnings": list(result.warnings)}
                summary.update(_alternatives(scene, n_modes, mesh.elements, result.warnings))
                if sensitivity:
                    summary["sensitivity"] = scene_sensitivity(scene, n_modes, samples, seed,
                                                               jobs, as_json)
            except FlexlinkError as exc:  # the other scenes still get their results
                failures.append(scene_failure(path, exc))
                continue
            summaries.append(summary)
            meshes.append(mesh)
            folders.append(all_folders[path])
    parts = [(folder / "modes.json", folder / "modes.csv", [s])
             for folder, s in zip(folders, summaries)]
    if len(files) > 1 and summaries:  # the combined table of a multi-scene run
        parts.append((out / "modes.json", out / "modes.csv", summaries))
    written = [p for j, c, _ in parts for p in (j, c)]
    document = {**_document(summaries, written), "failures": failures}
    for json_path, csv_path, part in parts:
        # the combined file is the printed document; a scene's file lists its own two files
        own = document if part is summaries else _document(part, [json_path, csv_path])
        write_atomic(json_path, dumps(own))
        write_atomic(csv_path, comparison_csv(part))
    if as_json:
        click.echo(dumps(document))
        finish(failures, len(files))
        return
    for s, mesh in zip(summaries, meshes):
        click.echo(format_case(s) + "\n" + mesh.describe() + "".join(
            f"\nwarning: {w}" for w in s["warnings"]) + _extra_lines(s) + "\n")
    overall = document["overall_mean_abs_error_pct"]
    if overall:
        click.echo("overall mean |error|: " + ", ".join(
            f"vs {k} {v:.1f} %" for k, v in sorted(overall.items())))
    announce(written, as_json)
    finish(failures, len(files))


def _alternatives(scene, n_modes, elements, warnings) -> dict:
    """The other orientation; for Timoshenko composites the other shear source; and where a
    link is outside Euler-Bernoulli theory, the scene computed with Timoshenko links."""
    from flexlink.studies.alternatives import (other_orientation, other_shear_source,
                                               timoshenko_alternative)

    out = {"other_orientation": other_orientation(scene, n_modes, elements)}
    if any("Euler-Bernoulli" in w for w in warnings):
        out["timoshenko"] = timoshenko_alternative(scene, n_modes, elements)
    shear = other_shear_source(scene, n_modes, elements)
    if shear is not None:
        out["other_shear_source"] = shear
    return out


def _extra_lines(summary: dict) -> str:
    from flexlink.output.sensitivity_report import alternative_line, format_sensitivity

    lines = []
    if summary.get("other_orientation"):
        lines.append(alternative_line("other orientation", summary["other_orientation"]))
    if summary.get("timoshenko"):
        lines.append(alternative_line("Timoshenko links (computed, shear and rotary inertia)",
                                      summary["timoshenko"]))
    if summary.get("other_shear_source"):
        lines.append(alternative_line("shear modulus source", summary["other_shear_source"]))
    if summary.get("sensitivity"):
        lines.append(format_sensitivity(summary["sensitivity"]))
    return "".join("\n" + line for line in lines)


def _document(summaries: list[dict], files) -> dict:
    from flexlink.output.report import overall_mean_abs

    return {"command": "modes", "cases": summaries,
            "overall_mean_abs_error_pct": overall_mean_abs(summaries),
            "files": [str(f) for f in files]}
