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
