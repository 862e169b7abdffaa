"""Convergence of the steady response's peak strain in the size of the reduced basis.

The basis is checked on frequencies (``analysis.pose_basis``); strain needs the curvature of
the motion, which the basis' shapes carry less well than its frequencies. This study builds
the response model (``steady_response.forced_model``) for each basis setting: the static modes
snapshotted at every other pose (``n_modes``, which sets the checked basis) and vectors added
above the checked size from the same snapshots; it keeps the peak strain of each point at each
speed, so a reader sees how much a larger basis still moves it. With ``n_modes`` equal to the
reduced DOF count the basis is the whole finite-element model: the reference. The bases are
the modal ones alone (``forced_model(..., load_vectors=False)``): the loads' static answers
the response adds to them take case 1's 2-mode basis from 8.8 % to 4e-4 of the whole
model's peak strain at 1500 rev/min, and would hide how the modes converge.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable

import numpy as np

from flexlink.scene import Scene
from flexlink.studies.running.steady_response import (StrainPoint, UnstableError, forced_model,
                                              steady_response)


@dataclasses.dataclass(frozen=True)
class StrainConvergence:
    """Per basis setting (settings,): the static modes snapshotted per pose, the basis size and
    its check's largest frequency excess [-]; speeds (speeds,) [rad/s]; points; peak_strain
    (settings, speeds, points) [-], NaN where the speed has no steady state in that basis."""

    n_modes: np.ndarray
    basis_sizes: np.ndarray
    basis_errors: np.ndarray
    speeds: np.ndarray
    points: tuple[StrainPoint, ...]
    peak_strain: np.ndarray

    def __post_init__(self):
        shape = (len(self.basis_sizes), len(self.speeds), len(self.points))
        if self.peak_strain.shape != shape or not (
                len(self.basis_errors) == len(self.n_modes) == shape[0]):
            raise ValueError(f"peak_strain must be {shape}, with one mode count and error per "
                             "basis size")

    @property
    def change(self) -> np.ndarray:
        """(settings,) [-]: the largest relative difference, over speeds and points, of each
        setting's peak strain from the largest basis' (the last setting)."""
        reference = self.peak_strain[-1]
        return np.nanmax(np.abs(self.peak_strain - reference) / np.abs(reference), axis=(1, 2))

    @property
    def step_change(self) -> np.ndarray:
        """(settings - 1,) [-]: the largest relative difference of each setting's peak strain
        from the next larger one's."""
        a, b = self.peak_strain[:-1], self.peak_strain[1:]
        return np.nanmax(np.abs(a - b) / np.abs(b), axis=(1, 2))


def strain_convergence(scene: Scene, speeds: np.ndarray,
                       settings: Iterable[tuple[int, int]] = ((6, 0), (6, 2), (6, 4)),
                       poses: int = 37, damping_ratio: float | None = None,
                       elements_per_link: int | None = None,
                       points: tuple[StrainPoint, ...] | None = None,
                       samples: int = 180) -> StrainConvergence:
    """Peak strain at ``points`` (default: each link's midspan) and ``speeds`` [rad/s] for each
    basis setting (n_modes, extra): the checked basis of ``n_modes`` static modes plus
    ``extra`` vectors; the last setting is the reference of ``StrainConvergence.change``. The
    other arguments as ``forced_model``'s and ``steady_response``'s."""
    speeds = np.asarray(speeds, dtype=float)
    modes, sizes, errors, peaks, points_used = [], [], [], [], points
    checked = {}  # n_modes -> the checked basis' model, built once for all its settings
    for n_modes, extra in settings:
        if n_modes not in checked:
            checked[n_modes] = forced_model(scene, n_modes, poses, damping_ratio, points,
                                            elements_per_link, load_vectors=False)
        model = checked[n_modes]
        if extra:
            model = forced_model(scene, n_modes, poses, damping_ratio, points,
                                 elements_per_link, basis_size=model.periodic.basis.size + extra,
                                 load_vectors=False)
        modes.append(n_modes)
        sizes.append(model.periodic.basis.size)
        errors.append(model.periodic.basis.error)
        points_used = model.points
        row = np.full((len(speeds), len(model.points)), np.nan)
        for i, speed in enumerate(speeds):
            try:
                row[i] = steady_response(model, speed, samples).peak_strain
            except UnstableError:
                continue
        peaks.append(row)
    return StrainConvergence(np.array(modes), np.array(sizes), np.array(errors), speeds,
                             points_used, np.array(peaks))
