"""Where commands put their files, and how they say so: one folder per scene (``OUT/<scene
file name>/``) so that running a command on another scene never replaces a result unseen, and
one line per written file on stderr (the ``--json`` document lists them under ``files``)."""

from __future__ import annotations

import io
from pathlib import Path

import click

from flexlink.errors import InputError
from flexlink.fileio import prepare_out_dir, write_atomic


def scene_folders(out: Path, scene_paths) -> list[Path]:
    """``out/<stem>`` for each scene file, created and checked writable; two scene files with
    the same name would share a folder, so they are refused."""
    stems = [Path(p).stem for p in scene_paths]
    clash = sorted({s for s in stems if stems.count(s) > 1})
    if clash:
        raise InputError(f"two scene files would write to the same folder {clash[0]!r}",
                         source="command line", expected="scene files with different names")
    return [prepare_out_dir(Path(out) / s) for s in stems]


def run_folder(out: Path, arguments) -> Path:
    """``out/<names>`` for a run over several scene arguments (files or folders), named after
    them: ``cases/`` gives ``out/cases``, ``a.toml b.toml`` gives ``out/a+b``."""
    name = "+".join(Path(a).stem if Path(a).suffix == ".toml" else Path(a).resolve().name
                    for a in arguments)
    return prepare_out_dir(Path(out) / name)


def write_drawn(path: Path, draw) -> Path:
    """Write the picture ``draw(file)`` renders (a matplotlib figure saved to a file object)
    atomically: drawn into memory, then ``fileio.write_atomic``, so a failure while drawing
    or writing leaves the old picture whole."""
    buffer = io.BytesIO()
    draw(buffer)
    return write_atomic(path, buffer.getvalue())


def announce(paths, quiet: bool) -> list[str]:
    """Say on stderr which files were written (not with ``--json``, whose document lists
    them); returns them as strings for that document."""
    paths = [str(p) for p in paths]
    if not quiet:
        for p in paths:
            click.echo(f"wrote {p}", err=True)
    return paths
