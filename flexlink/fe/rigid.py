"""Very stiff springs as exact constraints.

A penalty spring k joins two DOFs with an error of about (element stiffness / k) in the
frequencies, but it also puts k into K next to the element stiffness, whose digits it then
rounds away: measured on Table II case 1 (16 elements/link, dense), penalty against the exact
rigid path is 2e-6 at k = 1e4 x the stiffest element, 2e-8 at 1e6 x, 3e-7 at 1e8 x, 1e-3 at
1e10 x, and the factorisation fails from about 1e17 x. So a spring at least RIGID_RATIO times
the stiffest element of its kind (translational: EA/h and 12 EI/h^3; rotational: 4 EI/h) is
replaced by the exact constraint of ``assembly.rigid_elimination``, with a logged warning.
"""

from __future__ import annotations

import dataclasses
import logging

import numpy as np

from flexlink.fe.model import FrameModel

log = logging.getLogger(__name__)

RIGID_RATIO = 1e6


def element_stiffness_scale(model: FrameModel) -> tuple[float, float]:
    """(translational [N/m], rotational [N m/rad]) stiffness of the stiffest element."""
    trans, rot = 0.0, 0.0
    for link in model.links:
        s, h = link.section, link.length / link.elements
        trans = max(trans, s.EA / h, 12 * s.EI / h**3)
        rot = max(rot, 4 * s.EI / h)
    return trans, rot


def rigid_threshold(model: FrameModel, ratio: float = RIGID_RATIO, scales=None,
                    rotational=None) -> np.ndarray:
    """Per spring of ``model``: the stiffness [N/m or N m/rad] above which it is made rigid.

    ``scales``: (translational, rotational) element stiffness of the model's family, default
    ``element_stiffness_scale`` (in-plane frame); ``rotational``: per spring, whether it acts
    on a rotation, default the in-plane DOF order (rz every third DOF)."""
    trans, rot = element_stiffness_scale(model) if scales is None else scales
    if rotational is None:
        rotational = model.springs.dof_a % 3 == 2
    return ratio * np.where(rotational, rot, trans)


def rigidified(model: FrameModel, ratio: float = RIGID_RATIO, warn: bool = True, scales=None,
               rotational=None) -> FrameModel:
    """``model`` with every finite spring at or above ``rigid_threshold`` made infinite.
    ``warn``: log which springs were switched (a sweep warns at its first pose only);
    ``scales``, ``rotational``: as in ``rigid_threshold``, for another model family."""
    springs = model.springs
    threshold = rigid_threshold(model, ratio, scales, rotational)
    switch = np.isfinite(springs.stiffness) & (springs.stiffness >= threshold)
    if not switch.any():
        return model
    labels = sorted({springs.labels[i] for i in np.flatnonzero(switch)})
    if warn:
        log.warning("%d spring(s) at least %g x the stiffest element are treated as rigid (exact "
                    "constraint) instead of as a penalty: %s", int(switch.sum()), ratio,
                    ", ".join(labels))
    stiffness = np.where(switch, np.inf, springs.stiffness)
    return dataclasses.replace(model, springs=dataclasses.replace(springs, stiffness=stiffness))
