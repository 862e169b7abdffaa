"""The progress bar of long sweeps: tqdm on stderr, only for a person watching a terminal."""

from __future__ import annotations

import contextlib
import functools
import sys


def progress_bar(description: str, quiet: bool, unit: str = "pose"):
    """A callable wrapping an iterable of ``unit``s in a tqdm bar, or None when ``quiet`` (e.g.
    --json) or when stderr is not a terminal."""
    if quiet or not sys.stderr.isatty():
        return None
    from tqdm import tqdm

    return functools.partial(tqdm, desc=description, unit=unit, file=sys.stderr, leave=False)


@contextlib.contextmanager
def step_progress(description: str, quiet: bool):
    """A context giving a callable that adds a count of done steps to a tqdm bar of unknown
    total (the work inside one speed, e.g. Floquet steps), or None as ``progress_bar``."""
    make = progress_bar(description, quiet, unit="step")
    if make is None:
        yield None
        return
    bar = make(total=None)
    try:
        yield bar.update
    finally:
        bar.close()
