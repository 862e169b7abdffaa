"""Modal damping ratios from material loss factors, by strain-energy weighting.

A material with loss factor eta dissipates 2 pi eta of its peak strain energy per cycle (the
complex modulus E (1 + i eta)). For a mode of the undamped model, each part p holds strain
energy U_p of the total U, so the mode's damping ratio is

    zeta = sum_p eta_p U_p / (2 U)

(the modal strain energy method: first order in eta, exact for one uniform material, where
zeta = eta / 2). The parts and their energies are those of ``identity.energy_parts``: each
link with its material's eta, and the joint and drive springs with none (a bearing's friction
is not a material loss, and no scene declares it), so springs holding energy lower zeta.

A scene may instead declare its modal damping in a [damping] table (``ModalDamping``): ratios
per mode, or Rayleigh damping C = alpha M + beta K, which leaves the undamped modes uncoupled
and gives mode i exactly zeta_i = alpha / (2 omega_i) + beta omega_i / 2.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import numpy as np
import scipy.linalg

from flexlink.analysis.identity import energy_parts
from flexlink.errors import InputError
from flexlink.fe.model import FrameModel
from flexlink.scene import Scene
from flexlink.scene.contract import ModalDamping

# light structural damping of a frame of links and pins, whatever their material: the joints
# dissipate more than a bare material's loss factor says; plausible 0.002 to 0.05
DEFAULT_DAMPING_RATIO = 0.01


def damping_ratios(model: FrameModel, shapes: np.ndarray,
                   loss_factors: Mapping[str, float]) -> np.ndarray:
    """(k,) damping ratio zeta [-] of each column of ``shapes`` (n_dofs, k): the links' loss
    factors ``loss_factors`` (link name -> eta [-]) weighted by their strain energy; parts not
    named (joint springs, the drive) have none."""
    parts = energy_parts(model, shapes)
    eta = np.array([loss_factors.get(name, 0.0) if link else 0.0
                    for name, link in zip(parts.names, parts.is_link)])
    return eta @ parts.strain / (2.0 * parts.strain.sum(axis=0))


def declared_ratios(damping: ModalDamping, omegas: np.ndarray) -> np.ndarray:
    """(k,) damping ratio [-] of the elastic modes with circular frequencies ``omegas`` (k,)
    [rad/s], lowest first, from a scene's declared damping."""
    omegas = np.asarray(omegas, dtype=float)
    if damping.is_rayleigh:
        return damping.alpha / (2.0 * omegas) + damping.beta * omegas / 2.0
    ratios = np.asarray(damping.ratios, dtype=float)
    return ratios[np.minimum(np.arange(omegas.size), ratios.size - 1)]


def modal_damping_ratios(model: FrameModel, shapes: np.ndarray, omegas: np.ndarray,
                         loss_factors: Mapping[str, float],
                         declared: ModalDamping | None) -> np.ndarray:
    """(k,) damping ratio [-] of each elastic mode (columns of ``shapes``, circular
    frequencies ``omegas`` [rad/s]): the scene's declared damping where it has one, else the
    links' loss factors weighted by strain energy."""
    if declared is not None:
        return declared_ratios(declared, omegas)
    return damping_ratios(model, shapes, loss_factors)


def damping_source(declared: ModalDamping | None) -> str:
    """How the ratios were found, for the outputs."""
    if declared is None:
        return "material loss, strain-energy weighted"
    if declared.is_rayleigh:
        return (f"declared in [damping]: Rayleigh, alpha {declared.alpha:g} 1/s, "
                f"beta {declared.beta:g} s")
    if len(declared.ratios) > 1:
        return "declared in [damping], per mode"
    return f"declared in [damping], {declared.ratios[0]:g} for every mode"


@dataclasses.dataclass(frozen=True)
class BasisDamping:
    """ratios (n,) [-], one per basis vector, and how they were found (for the outputs)."""

    ratios: np.ndarray
    source: str

    def __post_init__(self):
        if np.ndim(self.ratios) != 1:
            raise ValueError(f"BasisDamping.ratios has shape {np.shape(self.ratios)}, expected "
                             "(n,)")


def declares_loss_factors(scene: Scene) -> bool:
    """True where the scene (or a base file, or an override) writes a material loss factor."""
    fields = ["material.loss_factor"] + [f"links.{link.name}.material.loss_factor"
                                         for link in scene.links]
    return any(scene.has_field(field) for field in fields)


def checked_ratio(given: float) -> float:
    """``given`` [-] if it is a damping ratio in [0, 1), else InputError."""
    if not 0.0 <= given < 1.0:
        raise InputError(f"damping ratio {given} is outside [0, 1)", field="damping ratio",
                         expected="a ratio in [0, 1)")
    return float(given)


def basis_damping(scene: Scene, given: float | None, omegas: np.ndarray,
                  model: FrameModel, shapes: np.ndarray) -> BasisDamping:
    """The damping ratio of each vector of a basis of the periodic equations at speed, first
    found first: ``given`` [-] for every vector where not None; else the scene's [damping]
    table (``declared_ratios``: a ratio, a ratio per mode, or Rayleigh) over the vectors'
    Ritz frequencies ``omegas`` (n,) [rad/s] at the scene's pose, lowest first; else the
    material loss factors the scene writes, weighted by each vector's strain energy
    (``damping_ratios``; ``shapes`` (n_dofs, n): the vectors in ``model``'s global DOFs, that
    pose's frame model), links whose factor is not written taking the assumed one the scene
    lists; else DEFAULT_DAMPING_RATIO. Loss factors the scene only assumes are not used: they
    are the bare material's, and a running linkage loses more at its joints and fixings."""
    omegas = np.asarray(omegas, dtype=float)
    if given is not None:
        return BasisDamping(np.full(omegas.size, checked_ratio(given)),
                            f"--damping-ratio {given:g} for every basis vector")
    declared = scene.options.damping
    if declared is not None:
        ratios = declared_ratios(declared, omegas)
        if ratios.size and ratios[0] >= 1.0:  # only Rayleigh's can: a ratio is below 1
            lowest = float(omegas[0])
            field = ("damping.rayleigh_beta" if declared.beta * lowest / 2.0
                     >= declared.alpha / (2.0 * lowest) else "damping.rayleigh_alpha")
            raise InputError(f"gives the lowest mode ({lowest / (2.0 * np.pi):.4g} Hz) a damping "
                             f"ratio of {ratios[0]:.3g}: overdamped, it decays without "
                             "vibrating, and the running linkage's studies follow vibrating "
                             "modes", source=scene.file_of(field), field=field,
                             expected="Rayleigh coefficients that leave the lowest mode below "
                                      "critical: zeta_1 = alpha / (2 omega_1) + beta omega_1 / 2 < 1")
        return BasisDamping(ratios, damping_source(declared))
    if declares_loss_factors(scene):
        return BasisDamping(damping_ratios(model, shapes, scene.loss_factors),
                            "material loss factors written in the scene, weighted by each "
                            "basis vector's strain energy")
    return BasisDamping(np.full(omegas.size, DEFAULT_DAMPING_RATIO),
                        f"default {DEFAULT_DAMPING_RATIO:g} for every basis vector (the scene "
                        "declares no damping and writes no loss factor; light structural "
                        "damping of a frame of links and pins, whose joints dissipate more "
                        "than its material, plausible 0.002 to 0.05)")


def deformation_damping(scene: Scene, given: float | None, mass: np.ndarray,
                        stiffness: np.ndarray, models, shapes: np.ndarray) -> np.ndarray:
    """C (poses, n, n) of a basis sampled over the turn, each pose's from that pose's own
    modes in the basis: C = M Phi diag(2 zeta_i omega_i) Phi^T M with K Phi = M Phi omega^2,
    Phi^T M Phi = I, and zeta_i by ``basis_damping``'s rule over the pose's own modes (a given
    ratio, the scene's [damping] table over their frequencies, or the loss factors weighted by
    their strain energy in the pose's frame model). So the damping acts on the rate of the
    pose's own elastic deformation: Rayleigh damping is alpha M + beta K of the pose (exactly,
    the modes spanning the basis), and a motion that strains nothing at the pose (the turning
    of the links' frames carrying the pins' translations, which the scene pose's modes would
    read as a stretch of the pin springs) is not damped.

    mass, stiffness (poses, n, n): M and the elastic K (no speed terms) in the basis;
    ``models``: the frame model at each pose; ``shapes`` (poses, n_dofs, n): the basis in each
    pose's global DOFs."""
    out = np.empty_like(np.asarray(mass, dtype=float))
    for p, (M, K) in enumerate(zip(mass, stiffness)):
        values, Phi = scipy.linalg.eigh(K, M)  # M-orthonormal modes of the pose, lowest first
        omegas = np.sqrt(np.maximum(values, 0.0))
        ratios = basis_damping(scene, given, omegas, models[p], shapes[p] @ Phi).ratios
        MPhi = M @ Phi
        out[p] = (MPhi * (2.0 * ratios * omegas)) @ MPhi.T
    return out


def overdamped_note(ratios: np.ndarray) -> str | None:
    """A sentence naming the modes whose damping ratio [-] is 1 or more (overdamped: they
    decay without vibrating, so their undamped frequencies are no frequencies of the damped
    linkage), or None."""
    ratios = np.asarray(ratios, dtype=float)
    over = np.flatnonzero(ratios >= 1.0)
    if not len(over):
        return None
    modes = ", ".join(str(i + 1) for i in over)
    return (f"mode(s) {modes} overdamped (damping ratio {ratios[over].min():.3g} to "
            f"{ratios[over].max():.3g}, at least 1): they decay without vibrating, and their "
            "frequencies are the undamped ones only; a structure's damping ratio is 0.001 to "
            "0.1 (for Rayleigh damping zeta_i = alpha / (2 omega_i) + beta omega_i / 2)")
