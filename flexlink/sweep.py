"""Natural frequencies over many poses of one linkage: the inner loop of cycle maps,
calibration and Monte Carlo.

The topology (links, sections, joints, mesh) is fixed; only joint positions change from pose to
pose, so each link's local matrices are built once (cached in ``link.py``) and every pose only
rotates and assembles them before the eigen solve.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Mapping

import numpy as np

from .analysis import lambda_scale
from .assembly import assemble, reduction
from .model import Topology, build_model
from .solve import ELASTIC, solve_modes

EXTRA_MODES = 4  # solved beyond n_modes so that mechanism modes cannot crowd out elastic ones


@dataclasses.dataclass(frozen=True)
class SweepResult:
    """frequencies[i, j]: j-th elastic natural frequency [Hz] at pose i (NaN if fewer found);
    mechanism_counts[i]: rigid-body/mechanism modes found at pose i."""

    frequencies: np.ndarray
    mechanism_counts: np.ndarray


def modal_sweep(topology: Topology, poses: Iterable[Mapping[str, tuple[float, float]]],
                n_modes: int, method: str = "auto", progress=None) -> SweepResult:
    """Lowest ``n_modes`` elastic frequencies [Hz] at each pose (joint name -> (x, y) [m]).

    ``progress``: optional callable wrapping the pose iterable (e.g. a tqdm factory)."""
    poses = list(poses)
    iterator = progress(poses) if progress else poses
    freqs = np.full((len(poses), n_modes), np.nan)
    mechanism = np.zeros(len(poses), dtype=int)
    for i, points in enumerate(iterator):
        model = build_model(topology, points)
        K, M = assemble(model)
        result = solve_modes(K, M, n_modes + EXTRA_MODES, T=reduction(model),
                             lambda_ref=lambda_scale(model), method=method)
        elastic = result.frequencies[[k == ELASTIC for k in result.kinds]][:n_modes]
        freqs[i, :len(elastic)] = elastic
        mechanism[i] = len(result.kinds) - int(sum(k == ELASTIC for k in result.kinds))
    return SweepResult(frequencies=freqs, mechanism_counts=mechanism)
