"""Modal damping ratios from material loss factors, by strain-energy weighting.

A material with loss factor eta dissipates 2 pi eta of its peak strain energy per cycle (the
complex modulus E (1 + i eta)). For a mode of the undamped model, each part p holds strain
energy U_p of the total U, so the mode's damping ratio is

    zeta = sum_p eta_p U_p / (2 U)

(the modal strain energy method: first order in eta, exact for one uniform material, where
zeta = eta / 2). The parts and their energies are those of ``identity.energy_parts``: each
link with its material's eta, and the joint and drive springs with none (a bearing's friction
is not a material loss, and no scene declares it), so springs holding energy lower zeta.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from flexlink.analysis.identity import energy_parts
from flexlink.fe.model import FrameModel


def damping_ratios(model: FrameModel, shapes: np.ndarray,
                   loss_factors: Mapping[str, float]) -> np.ndarray:
    """(k,) damping ratio zeta [-] of each column of ``shapes`` (n_dofs, k): the links' loss
    factors ``loss_factors`` (link name -> eta [-]) weighted by their strain energy; parts not
    named (joint springs, the drive) have none."""
    parts = energy_parts(model, shapes)
    eta = np.array([loss_factors.get(name, 0.0) if link else 0.0
                    for name, link in zip(parts.names, parts.is_link)])
    return eta @ parts.strain / (2.0 * parts.strain.sum(axis=0))
