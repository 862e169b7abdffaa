"""Crank-rocker synthesis as `flexlink synth` reports it: the four-bar a synthesis method gives
for its design targets (``kinematics.synthesis``), with the measures that check those targets,
its transmission angle limits and rocker swing."""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.kinematics.synthesis import brodell_soni, minimax
from flexlink.studies.array_shapes import check_shape

METHODS = {"minimax": minimax, "brodell-soni": brodell_soni}  # name -> (angle, angle, ground)


@dataclasses.dataclass(frozen=True)
class CrankRocker:
    """The crank-rocker of synthesis ``method`` from the targets ``inputs`` (as given, text
    with units): ``lengths`` [m] (ground, crank, coupler, rocker), ``ratios`` R2, R3, R4 (to
    the ground link), ``transmission`` (mu_min, mu_max) [rad] and the rocker ``swing`` [rad]."""

    method: str
    inputs: dict[str, str]
    lengths: np.ndarray
    ratios: np.ndarray
    transmission: np.ndarray
    swing: float

    def __post_init__(self):
        check_shape("CrankRocker", "lengths", self.lengths, (4,))
        check_shape("CrankRocker", "ratios", self.ratios, (3,))
        check_shape("CrankRocker", "transmission", self.transmission, (2,))


def crank_rocker(method: str, inputs: dict[str, str], first: float, second: float,
                 ground: float) -> CrankRocker:
    """The crank-rocker of ``METHODS[method]`` from its two target angles ``first`` and
    ``second`` [rad] (minimax: theta4i, delta; brodell-soni: gamma_min, swing) and the ground
    link ``ground`` [m]; ``inputs``: the targets as given, kept for the report."""
    four_bar = METHODS[method](first, second, ground)
    return CrankRocker(method=method, inputs=inputs, lengths=np.array(four_bar.lengths),
                       ratios=np.array(four_bar.ratios),
                       transmission=np.array(four_bar.transmission_limits()),
                       swing=four_bar.rocker_swing())
