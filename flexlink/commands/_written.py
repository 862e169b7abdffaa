"""Where commands put their files, and how they say so: one folder per scene (``OUT/<scene
file name>/``) so that running a command on another scene never replaces a result unseen, and
one line per written file on stderr (the ``--json`` document lists them under ``files``)."""

from __future__ import annotations

from pathlib import Path

import click

from flexlink.errors import InputError
from flexlink.fileio import prepare_out_dir


def scene_folders(out: Path, scene_paths) -> list[Path]:
    """``out/<stem>`` for each scene file, created and checked writable; two scene files with
    the same name would share a folder, so they are refused."""
    stems = [Path(p).stem for p in scene_paths]
    clash = sorted({s for s in stems if stems.count(s) > 1})
    if clash:
        raise InputError(f"two scene files would write to the same folder {clash[0]!r}",
                         source="command line", expected="scene files with different names")
    return [prepare_out_dir(Path(out) / s) for s in stems]


def folder_and_scene(out_dir, scene_path):
    """(``OUT/<scene file name>/``, the scene read from ``scene_path``): the folder is made
    and checked writable first, so a run never fails for want of it after its study."""
    from flexlink.scene import load_scene

    [folder] = scene_folders(prepare_out_dir(out_dir), [scene_path])
    return folder, load_scene(scene_path)


def run_folder(out: Path, arguments) -> Path:
    """``out/<names>`` for a run over several scene arguments (files or folders), named after
    them: ``cases/`` gives ``out/cases``, ``a.toml b.toml`` gives ``out/a+b``."""
    name = "+".join(Path(a).stem if Path(a).suffix == ".toml" else Path(a).resolve().name
                    for a in arguments)
    return prepare_out_dir(Path(out) / name)


# More files than this in one folder (a ParaView series' frames) are said in one line.
FILES_LISTED_ONE_BY_ONE = 5


def announce(paths, quiet: bool) -> list[str]:
    """Say on stderr which files were written (not with ``--json``, whose document lists
    them all); a folder that received more than ``FILES_LISTED_ONE_BY_ONE`` of them is one
    line with the count, the first and the last. Returns the paths as strings for that
    document."""
    paths = [str(p) for p in paths]
    if not quiet:
        folders: dict[Path, list[str]] = {}
        for p in paths:
            folders.setdefault(Path(p).parent, []).append(p)
        for folder, inside in folders.items():
            if len(inside) > FILES_LISTED_ONE_BY_ONE:
                click.echo(f"wrote {len(inside)} files in {folder}/ ({Path(inside[0]).name} "
                           f"... {Path(inside[-1]).name})", err=True)
            else:
                for p in inside:
                    click.echo(f"wrote {p}", err=True)
    return paths


def finite_document(document: dict) -> dict:
    """``document`` itself where JSON can hold it, checked before any file of the run is
    written; else NumericalError naming the first value that is not finite."""
    import math

    from flexlink.commands._options import dumps
    from flexlink.errors import NumericalError

    def first(value, where):
        if isinstance(value, float) and not math.isfinite(value):
            return where
        items = (value.items() if isinstance(value, dict) else
                 enumerate(value) if isinstance(value, list | tuple) else ())
        return next((w for k, v in items if (w := first(v, f"{where}[{k!r}]"))), None)

    try:
        dumps(document)
    except ValueError as error:
        where = first(document, "") or str(error)
        raise NumericalError(f"the result {where} is not a finite number: nothing "
                             "written") from error
    return document


def publish(path: Path, document: dict, files, text: str, as_json: bool) -> None:
    """A command's last step: its JSON ``document`` with the list of ``files`` written before
    it and then ``path`` itself (its ``files``), written to ``path`` atomically; then printed
    on stdout (``--json``), or else ``text`` printed and the files listed on stderr."""
    from flexlink.commands._options import dumps
    from flexlink.fileio import write_atomic

    document = {**document, "files": [str(p) for p in [*files, path]]}
    write_atomic(path, dumps(document))
    if as_json:
        click.echo(dumps(document))
        return
    click.echo(text)
    announce(document["files"], as_json)


def publish_files(documents: dict[Path, dict], tables: dict[Path, str], document: dict,
                  text: str, as_json: bool) -> None:
    """The last step of a command over several scenes: each JSON document and text table
    written to its path atomically, then the printed ``document`` on stdout (``--json``), or
    else ``text`` printed and its ``files`` listed on stderr."""
    from flexlink.commands._options import dumps
    from flexlink.fileio import write_atomic

    for path, part in documents.items():
        write_atomic(path, dumps(part))
    for path, table in tables.items():
        write_atomic(path, table)
    click.echo(dumps(document) + "\n" if as_json else text, nl=False)
    announce(document["files"], as_json)
