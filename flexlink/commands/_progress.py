"""The progress bar of long sweeps: tqdm on stderr, only for a person watching a terminal."""

from __future__ import annotations

import functools
import sys


def progress_bar(description: str, quiet: bool, unit: str = "pose"):
    """A callable wrapping an iterable of ``unit``s in a tqdm bar, or None when ``quiet`` (e.g.
    --json) or when stderr is not a terminal."""
    if quiet or not sys.stderr.isatty():
        return None
    from tqdm import tqdm

    return functools.partial(tqdm, desc=description, unit=unit, file=sys.stderr, leave=False)
