"""Runs over several scene files, one at a time: the files and their folders found before any
solve, and one bad scene must not cost the others their results, so each failure is kept with
the file it came from (``_failures.scene_failure``)."""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from pathlib import Path

from flexlink.commands._failures import scene_failure
from flexlink.commands._written import scene_folders
from flexlink.errors import FlexlinkError


def scene_run(scenes, out_dir) -> tuple[Path, list[Path], dict[Path, Path]]:
    """(the --out folder, the scene files the SCENE arguments name, each file's own folder in
    it), every folder made and checked writable before any solve; two scene files with the
    same name are refused (``_written.scene_folders``)."""
    from flexlink.fileio import prepare_out_dir
    from flexlink.scene import scene_files

    out = prepare_out_dir(out_dir)
    files = scene_files(scenes)
    return out, files, dict(zip(files, scene_folders(out, files)))


def each_scene(files: list, study: Callable, failures: list[dict], progress: str | None = None
               ) -> Iterator[tuple]:
    """(path, study(path)) of each scene file in turn; a scene whose study raises a flexlink
    error is appended to ``failures`` instead, and the next one goes on. ``progress``: the
    description of a bar over the scenes on stderr, shown only to a person at a terminal."""
    if progress is not None and sys.stderr.isatty():
        from tqdm import tqdm

        files = tqdm(files, desc=progress, unit="scene", file=sys.stderr)
    for path in files:
        try:
            result = study(path)
        except FlexlinkError as exc:
            failures.append(scene_failure(path, exc))
            continue
        yield path, result
