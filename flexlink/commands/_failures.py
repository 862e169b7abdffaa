"""Runs over several scenes: one bad scene must not cost the others their results. Each
failure is kept with the file it came from, listed at the end, and the exit status is 2."""

from __future__ import annotations

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
    click.echo(f"flexlink: {len(failures)} of {total} scene(s) failed"
               + (f"; the results of the other {done} are written" if done else ""), err=True)
    sys.exit(FAILED_EXIT)

