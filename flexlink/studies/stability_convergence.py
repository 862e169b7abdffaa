"""Convergence of the stability map in the reduced basis, the poses and the time step.

The map is one model (``periodic_model``) and one integration (``stability_map``) per
setting; this study repeats both over basis sizes, pose counts and step phases (h omega_max)
and keeps, per setting, what a reader compares: the basis check, the unstable ranges, the
largest multiplier modulus and the growth per revolution at every speed.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable

import numpy as np

from flexlink.scene import Scene
from flexlink.studies.stability_map import (STEP_PHASE, InstabilityRange, periodic_model,
                                            stability_map)


@dataclasses.dataclass(frozen=True)
class MapSetting:
    """One map: basis size and its check error [-], poses, step phase [rad]; per speed the
    growth per revolution ln|mu|_max [-]; the unstable ranges; the largest modulus [-]."""

    basis_size: int
    basis_error: float
    poses: int
    step_phase: float
    growth_per_turn: np.ndarray
    ranges: tuple[InstabilityRange, ...]
    largest_modulus: float


def map_convergence(scene: Scene, speeds: np.ndarray, n_modes: int,
                    basis_sizes: Iterable[int | None] = (None,), poses: Iterable[int] = (37,),
                    step_phases: Iterable[float] = (STEP_PHASE,),
                    damping_ratio: float | None = None,
                    elements_per_link: int | None = None) -> tuple[MapSetting, ...]:
    """The map of ``scene`` over ``speeds`` [rad/s] for every combination of basis size (None:
    the checked one), pose count and step phase; ``damping_ratio`` as ``periodic_model``'s
    (None: the scene's declared damping, else the default)."""
    out = []
    for count in poses:
        for size in basis_sizes:
            model = periodic_model(scene, n_modes, count, damping_ratio, elements_per_link,
                                   basis_size=size)
            for phase in step_phases:
                result = stability_map(model, speeds, step_phase=phase)
                out.append(MapSetting(
                    basis_size=model.basis.size, basis_error=model.basis.error, poses=count,
                    step_phase=phase, growth_per_turn=np.log(result.largest_modulus),
                    ranges=result.ranges, largest_modulus=float(result.largest_modulus.max())))
    return tuple(out)
