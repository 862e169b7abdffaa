"""Command-line interface. Every command: ``--json`` prints one JSON document on stdout,
``--out DIR`` chooses where files go (default ``out/``); tables for people otherwise."""

from __future__ import annotations

import json
import logging
import math
import sys

import click

from .errors import FlexlinkError


def _json_default(value):
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"not JSON serialisable: {type(value)}")


def dumps(document) -> str:
    return json.dumps(document, indent=2, default=_json_default, allow_nan=False)


class FlexlinkGroup(click.Group):
    """Turns flexlink's own errors into one clear line and exit code 2, no traceback."""

    def invoke(self, ctx):
        try:
            return super().invoke(ctx)
        except FlexlinkError as exc:
            click.echo(f"flexlink: error: {exc}", err=True)
            sys.exit(2)


@click.group(cls=FlexlinkGroup)
@click.option("-v", "--verbose", is_flag=True, help="Log details to stderr.")
def main(verbose):
    """flexlink: natural frequencies and mode shapes of planar linkages with flexible links."""
    logging.basicConfig(level=logging.INFO if verbose else logging.WARNING,
                        format="%(levelname)s %(name)s: %(message)s")


json_option = click.option("--json", "as_json", is_flag=True,
                           help="Print one machine-readable JSON document on stdout.")
out_option = click.option("--out", "out_dir", default="out", show_default=True,
                          type=click.Path(file_okay=False), help="Folder for result files.")


@main.command()
@click.argument("scenes", nargs=-1, required=True, type=click.Path())
@click.option("-n", "--modes", "n_modes", default=4, show_default=True,
              type=click.IntRange(1, 200), help="Number of elastic modes to report.")
@click.option("-e", "--elements", default=None, type=click.IntRange(1, 100000),
              help="Elements per link (default: the scene's mesh.elements_per_link).")
@click.option("--method", type=click.Choice(["auto", "dense", "sparse"]), default="auto",
              show_default=True, help="Eigen solver.")
@json_option
@out_option
def modes(scenes, n_modes, elements, method, as_json, out_dir):
    """Natural frequencies of each SCENE (a scene file or a folder of them) at its pose,
    compared with the scene's reference columns (measured Ex, published FE)."""
    from .analysis import analyze
    from .fileio import prepare_out_dir, write_atomic
    from .report import case_summary, csv_text, format_case, overall_mean_abs
    from .scene import load_scene, scene_files

    out = prepare_out_dir(out_dir)
    files = scene_files(scenes)
    summaries = []
    for path in files:
        scene = load_scene(path)
        summaries.append(case_summary(analyze(scene, n_modes, elements, method), n_modes))
    document = {"command": "modes", "cases": summaries, "overall_mean_abs_error_pct":
                overall_mean_abs(summaries)}
    write_atomic(out / "modes.json", dumps(document))
    write_atomic(out / "modes.csv", csv_text(summaries))
    if as_json:
        click.echo(dumps(document))
        return
    for s in summaries:
        click.echo(format_case(s) + "\n")
    overall = document["overall_mean_abs_error_pct"]
    if overall:
        click.echo("overall mean |error|: " + ", ".join(
            f"vs {k} {v:.1f} %" for k, v in sorted(overall.items())))
    click.echo(f"written: {out / 'modes.json'}, {out / 'modes.csv'}")


if __name__ == "__main__":
    main()
