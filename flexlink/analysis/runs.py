"""Runs of consecutive true values along a grid (of speeds, of poses): the one run finder of
the stability map's unstable ranges and the Campbell diagram's critical ranges."""

from __future__ import annotations

import numpy as np


def true_runs(mask) -> list[tuple[int, int]]:
    """(start, stop) index pairs, stop exclusive, of each maximal run of true values in the
    one-dimensional ``mask``, in order."""
    padded = np.concatenate([[False], np.asarray(mask, dtype=bool), [False]]).astype(int)
    steps = np.diff(padded)
    return [(int(a), int(b)) for a, b in zip(np.flatnonzero(steps == 1),
                                             np.flatnonzero(steps == -1))]
