"""Runs over several scenes: one bad scene must not cost the others their results. Each
failure is kept with the file it came from, listed at the end, and the exit status is 2."""

from __future__ import annotations

import functools
import sys

import click

from flexlink.errors import FlexlinkError

FAILED_EXIT = 2  # as for any flexlink error (cli.FlexlinkGroup)


def scene_failure(path, exc: FlexlinkError) -> dict:
    """{"file", "error"} with the message naming the file even where the error did not."""
    message = str(exc)
    if str(path) not in message:
        message = f"{path}: {message}"
    return {"file": str(path), "error": message}


def finish(failures: list[dict], total: int) -> None:
    """List the failed scenes on stderr and exit with FAILED_EXIT; nothing if none failed."""
    if not failures:
        return
    for f in failures:
        click.echo(f"flexlink: error: {f['error']}", err=True)
    done = total - len(failures)
    if total > 1:
        click.echo(f"flexlink: {len(failures)} of {total} scene(s) failed"
                   + (f"; the results of the other {done} are written" if done else ""),
                   err=True)
    sys.exit(FAILED_EXIT)



def names_scene(param: str):
    """Decorator for a command whose ``param`` is a scene path (or a list of them): a flexlink
    error that does not name the file gets it in front, so every error line says which scene
    failed (a dead centre met in the analysis, an -n beyond the model's modes, ...)."""
    def wrap(command):
        @functools.wraps(command)
        def run(**params):
            try:
                return command(**params)
            except FlexlinkError as exc:
                given = params.get(param)
                paths = [given] if isinstance(given, str) else list(given or ())
                if len(paths) != 1 or str(paths[0]) in str(exc):
                    raise
                raise FlexlinkError(f"{paths[0]}: {exc}") from exc
        return run
    return wrap
