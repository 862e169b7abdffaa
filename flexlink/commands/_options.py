"""What every command shares: the JSON style and the ``--json`` and ``--out`` options."""

from __future__ import annotations

import json

import click


def _json_default(value):
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"not JSON serialisable: {type(value)}")


def dumps(document) -> str:
    """The one JSON style of every command (NaN refused: JSON has none)."""
    return json.dumps(document, indent=2, default=_json_default, allow_nan=False)


json_option = click.option("--json", "as_json", is_flag=True,
                           help="Print one machine-readable JSON document on stdout.")
out_option = click.option("--out", "out_dir", default="out", show_default=True,
                          type=click.Path(file_okay=False), help="Folder for result files.")


def mesh_options(method: bool = True):
    """-e/--elements and --tol (the mesh rule of ``analysis.mesh.choose_mesh``), and with
    ``method`` the eigen solver's --method: one wording for every command that solves a scene."""
    options = [
        click.option("-e", "--elements", default=None, type=click.IntRange(1, 100000),
                     help="Elements per link (default: the scene's mesh.elements_per_link if it "
                          "pins one, else the coarsest mesh meeting --tol)."),
        click.option("--tol", default=None, type=click.FloatRange(0, 1, min_open=True),
                     help="Relative frequency tolerance of the default mesh: the coarsest of 8, "
                          "16, 32, ... elements/link whose Richardson error estimate meets it "
                          "[default: 1e-6]."),
    ]
    if method:
        options.append(click.option("--method", type=click.Choice(["auto", "dense", "sparse"]),
                                    default="auto", show_default=True, help="Eigen solver."))

    def decorate(command):
        for option in reversed(options):
            command = option(command)
        return command
    return decorate
