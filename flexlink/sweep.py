"""Natural frequencies over many poses of one linkage: the inner loop of cycle maps,
calibration and Monte Carlo.

The topology (links, sections, joints, mesh) is fixed; only joint positions change from pose to
pose, so each link's local matrices are built once (cached in ``link.py``) and every pose only
rotates and assembles them before the eigen solve. Which global entry each rotated link entry
lands in, and the springs, masses and rigid-joint reduction, depend on the topology alone; for
models the dense solver takes, ``_DensePlan`` works them out once and each pose scatters its
rotated entries straight into the reduced dense K and M (one ``np.bincount``), so the pose costs
little more than the eigen solve itself.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Mapping

import numpy as np

from .analysis import lambda_scale
from .assembly import (assemble, link_entries, point_mass_entries, reduction, rotated_entries,
                       spring_entries)
from .model import FrameModel, Topology, build_model
from .solve import DENSE_LIMIT, ELASTIC, solve_modes

EXTRA_MODES = 4  # solved beyond n_modes so that mechanism modes cannot crowd out elastic ones


@dataclasses.dataclass(frozen=True)
class SweepResult:
    """frequencies[i, j]: j-th elastic natural frequency [Hz] at pose i (NaN if fewer found);
    mechanism_counts[i]: rigid-body/mechanism modes found at pose i."""

    frequencies: np.ndarray
    mechanism_counts: np.ndarray


class _DensePlan:
    """Where every rotated link entry, spring and point mass goes in the reduced dense K and M
    of one topology (u = T q with T from ``assembly.reduction``: a 0/1 matrix, one 1 per kept
    DOF). Entries on a grounded DOF go to a spare slot at the end and are dropped."""

    def __init__(self, model: FrameModel):
        T = reduction(model)
        n_full = model.n_dofs
        if T is None:
            column, self.n = np.arange(n_full), n_full
        else:
            T = T.tocsr()
            if not (np.all(T.data == 1.0) and np.all(np.diff(T.indptr) <= 1)):
                raise AssertionError("reduction must map each DOF to at most one reduced DOF")
            column = np.full(n_full, -1)
            column[np.diff(T.indptr) == 1] = T.indices
            self.n = T.shape[1]
        self.column = column
        self.spare = self.n * self.n
        rows, cols, _ = rotated_entries(*link_entries(model))
        self.link_slots = self.slots(rows, cols)
        self.constant = []
        for rows, cols, vals in (spring_entries(model), point_mass_entries(model)):
            self.constant.append(self.scatter(self.slots(rows, cols), vals))

    def slots(self, rows, cols) -> np.ndarray:
        r, c = self.column[rows], self.column[cols]
        return np.where((r >= 0) & (c >= 0), r * self.n + c, self.spare)

    def scatter(self, slots, values) -> np.ndarray:
        summed = np.bincount(slots, weights=values, minlength=self.spare + 1)
        return summed[:self.spare].reshape(self.n, self.n)

    def matrices(self, model: FrameModel) -> tuple[np.ndarray, np.ndarray]:
        """Reduced dense (K, M) of ``model`` (same topology as the plan's): T^T K T, T^T M T."""
        _, _, values = rotated_entries(*link_entries(model))
        K = self.scatter(self.link_slots, values[0]) + self.constant[0]
        M = self.scatter(self.link_slots, values[1]) + self.constant[1]
        return K, M


def modal_sweep(topology: Topology, poses: Iterable[Mapping[str, tuple[float, float]]],
                n_modes: int, method: str = "auto", progress=None) -> SweepResult:
    """Lowest ``n_modes`` elastic frequencies [Hz] at each pose (joint name -> (x, y) [m]).

    ``progress``: optional callable wrapping the pose iterable (e.g. a tqdm factory)."""
    poses = list(poses)
    iterator = progress(poses) if progress else poses
    freqs = np.full((len(poses), n_modes), np.nan)
    mechanism = np.zeros(len(poses), dtype=int)
    plan = None
    for i, points in enumerate(iterator):
        model = build_model(topology, points)
        if plan is None and method in ("auto", "dense"):
            plan = _DensePlan(model)
            if method == "auto" and plan.n > DENSE_LIMIT:
                plan = None
                method = "sparse"
        if plan is not None:
            K, M = plan.matrices(model)
            result = solve_modes(K, M, n_modes + EXTRA_MODES, lambda_ref=lambda_scale(model),
                                 method="dense")
        else:
            K, M = assemble(model)
            result = solve_modes(K, M, n_modes + EXTRA_MODES, T=reduction(model),
                                 lambda_ref=lambda_scale(model), method=method)
        elastic = result.frequencies[[k == ELASTIC for k in result.kinds]][:n_modes]
        freqs[i, :len(elastic)] = elastic
        mechanism[i] = len(result.kinds) - int(sum(k == ELASTIC for k in result.kinds))
    return SweepResult(frequencies=freqs, mechanism_counts=mechanism)
