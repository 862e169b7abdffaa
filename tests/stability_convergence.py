"""Convergence of the stability map in the reduced basis, the poses and the time step.

The map is one model (``periodic_model``) and one integration (``stability_map``) per
setting; this study repeats both over basis sizes, pose counts and step settings (the
adiabatic steps per turn, or the Magnus step phase h omega_max) and keeps, per setting, what
a reader compares: the basis check, the unstable ranges, the largest multiplier modulus and
the growth per revolution at every speed.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable

import numpy as np

from flexlink.scene import Scene
from flexlink.analysis.periodic import ADIABATIC_STEPS, STEP_PHASE, Integrator, periodic_model
from flexlink.studies.running.stability_map import InstabilityRange, stability_map


@dataclasses.dataclass(frozen=True)
class MapSetting:
    """One map: basis size and its check error [-], poses, the integrator and its step
    setting (``steps``: equal adiabatic steps a turn before refinement [-], or the Magnus
    step phase h omega_max [rad]); per speed the growth per revolution ln|mu|_max [-]; the
    unstable ranges; the largest modulus [-]."""

    basis_size: int
    basis_error: float
    poses: int
    integrator: Integrator
    steps: float
    growth_per_turn: np.ndarray
    ranges: tuple[InstabilityRange, ...]
    largest_modulus: float


def map_convergence(scene: Scene, speeds: np.ndarray, n_modes: int,
                    basis_sizes: Iterable[int | None] = (None,), poses: Iterable[int] = (37,),
                    integrator: Integrator = Integrator.ADIABATIC,
                    steps: Iterable[float] | None = None,
                    damping_ratio: float | None = None,
                    elements_per_link: int | None = None) -> tuple[MapSetting, ...]:
    """The map of ``scene`` over ``speeds`` [rad/s] for every combination of basis size (None:
    the checked one), pose count and step setting of ``integrator`` (``steps``: adiabatic
    steps per turn, default ADIABATIC_STEPS, or Magnus step phases [rad], default
    STEP_PHASE); ``damping_ratio`` as ``periodic_model``'s (None: the scene's declared
    damping, else the default)."""
    adiabatic = integrator is Integrator.ADIABATIC
    settings = tuple(steps) if steps is not None else (
        (ADIABATIC_STEPS,) if adiabatic else (STEP_PHASE,))
    out = []
    for count in poses:
        for size in basis_sizes:
            model = periodic_model(scene, n_modes, count, damping_ratio, elements_per_link,
                                   basis_size=size)
            for step in settings:
                step_options = ({"adiabatic_steps": int(step)} if adiabatic
                                else {"step_phase": float(step)})
                result = stability_map(model, speeds, integrator=integrator, **step_options)
                out.append(MapSetting(
                    basis_size=model.basis.size, basis_error=model.basis.error, poses=count,
                    integrator=integrator, steps=step,
                    growth_per_turn=np.log(result.largest_modulus), ranges=result.ranges,
                    largest_modulus=float(result.largest_modulus.max())))
    return tuple(out)
