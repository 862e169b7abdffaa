"""The modal damping of the periodic equations at speed: one ratio per reduced basis vector.

Where it comes from, first found first:
1. a ratio given by the user (``--damping-ratio``), the same for every basis vector;
2. the scene's [damping] table (``analysis.damping.declared_ratios``: a ratio, a ratio per
   mode, or Rayleigh zeta_i = alpha / (2 omega_i) + beta omega_i / 2), over the basis vectors'
   Ritz frequencies at the scene's pose, lowest first;
3. material loss factors written in the scene (a link's or the shared material's
   ``loss_factor``), weighted by each basis vector's strain energy at the scene's pose
   (``analysis.damping.damping_ratios``); links whose factor is not written take the assumed
   one the scene lists;
4. else ``DEFAULT_DAMPING_RATIO``. The loss factors the scene only assumes are not used here:
   they are the bare material's, and a running linkage loses more at its joints and fixings.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.analysis.damping import damping_ratios, damping_source, declared_ratios
from flexlink.errors import InputError
from flexlink.fe.model import FrameModel
from flexlink.scene import Scene

# light structural damping of a bolted metal frame; plausible 0.002 to 0.05
DEFAULT_DAMPING_RATIO = 0.01


@dataclasses.dataclass(frozen=True)
class BasisDamping:
    """ratios (n,) [-], one per basis vector, and how they were found (for the outputs)."""

    ratios: np.ndarray
    source: str


def declares_loss_factors(scene: Scene) -> bool:
    """True where the scene (or a base file, or an override) writes a material loss factor."""
    fields = ["material.loss_factor"] + [f"links.{link.name}.material.loss_factor"
                                         for link in scene.links]
    return any(scene.has_field(field) for field in fields)


def checked_ratio(given: float) -> float:
    """``given`` [-] if it is a damping ratio in [0, 1), else InputError naming the option."""
    if not 0.0 <= given < 1.0:
        raise InputError(f"damping ratio {given} is outside [0, 1)", field="--damping-ratio",
                         expected="a ratio in [0, 1)")
    return float(given)


def basis_damping(scene: Scene, given: float | None, omegas: np.ndarray,
                  model: FrameModel, shapes: np.ndarray) -> BasisDamping:
    """The damping ratio of each basis vector: ``given`` [-] for all where not None, else the
    scene's declared damping (module docstring). ``omegas`` (n,) [rad/s]: the vectors' Ritz
    frequencies at the scene's pose; ``shapes`` (n_dofs, n): the vectors in ``model``'s global
    DOFs (that pose's frame model), for the loss factors' strain-energy weighting."""
    omegas = np.asarray(omegas, dtype=float)
    if given is not None:
        return BasisDamping(np.full(omegas.size, checked_ratio(given)),
                            f"--damping-ratio {given:g} for every basis vector")
    declared = scene.options.damping
    if declared is not None:
        return BasisDamping(declared_ratios(declared, omegas), damping_source(declared))
    if declares_loss_factors(scene):
        return BasisDamping(damping_ratios(model, shapes, scene.loss_factors),
                            "material loss factors written in the scene, weighted by each "
                            "basis vector's strain energy")
    return BasisDamping(np.full(omegas.size, DEFAULT_DAMPING_RATIO),
                        f"default {DEFAULT_DAMPING_RATIO:g} for every basis vector (the scene "
                        "declares no damping; light structural damping of a bolted metal "
                        "frame, plausible 0.002 to 0.05)")
