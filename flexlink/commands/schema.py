"""``flexlink schema``: the scene files' JSON Schema (for TOML editors) or their reference."""

from __future__ import annotations

import click

from flexlink.commands._options import dumps, json_option, out_option

SCHEMA_FILE = "scene.schema.json"


@click.command()
@click.option("--markdown", is_flag=True, help="Print the scene reference (Markdown) instead.")
@json_option
@out_option
def command(markdown, as_json, out_dir):
    """Write the JSON Schema of scene files to OUT/scene.schema.json (TOML editors such as
    taplo / Even Better TOML use it for completion and checking); --json prints it, --markdown
    prints the scene reference generated from the same schema."""
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.scene.reference import json_schema, reference_markdown

    if markdown:
        click.echo(reference_markdown(), nl=False)
        return
    text = dumps(json_schema())
    path = write_atomic(prepare_out_dir(out_dir) / SCHEMA_FILE, text + "\n")
    if as_json:
        click.echo(text)
        return
    click.echo(f"written: {path}")
    click.echo(f"Point your TOML editor at it: a first line '#:schema {path.resolve()}' in a "
               "scene file (or that path relative to the scene's folder), or the [[rule]] of "
               "the repository's .taplo.toml, which uses the committed docs/" + SCHEMA_FILE + ".")
