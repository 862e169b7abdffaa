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

from collections.abc import Mapping

import numpy as np

from flexlink.analysis.identity import energy_parts
from flexlink.fe.model import FrameModel
from flexlink.scene.contract import ModalDamping


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
