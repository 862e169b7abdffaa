"""Stress along and across the fibres in the plies of a woven 0/90 strip, and its strength
ratio per ply (maximum stress and Tsai-Wu).

The strip's laminate strain along the link, eps_x (from the beam: eps_x = sigma / E_beam), is
the same in the 0 and 90 degree layers of a ply (``mixtures``: each woven ply is a balanced
cross-ply of two unidirectional layers). A narrow strip is free to contract sideways, so the
laminate's sideways force vanishes: eps_y = -A12 / A22 eps_x = -Q12 / A11 eps_x. In the
layers' own axes (1 along the fibres, 2 across; no shear strain in beam bending):

    0-degree layer:   sigma1 = Q11 eps_x + Q12 eps_y,   sigma2 = Q12 eps_x + Q22 eps_y
    90-degree layer:  sigma1 = Q11 eps_y + Q12 eps_x,   sigma2 = Q12 eps_y + Q22 eps_x

(their mean along x is A11 eps_x + A12 eps_y = E_beam eps_x, the beam stress).

Unidirectional layer strengths from the constituents' ``[strength]`` (rule of mixtures at
equal strain for the fibre-dominated ones, matrix values for the others; textbook first
estimates, e.g. Jones, Mechanics of Composite Materials, ch. 3, which overestimate the
matrix-dominated strengths since they leave out the strain magnification between fibres):
    Xt = sigma_fu,t (Vf + (1 - Vf) Em / Ef),  Xc = sigma_fu,c (Vf + (1 - Vf) Em / Ef)
    Yt = sigma_mu,t,  Yc = sigma_mu,c,  S = tau_mu

Strength ratio R (the factor on the stress at which the layer fails; R > 1 holds):
    maximum stress  R = min(X / |sigma1|, Y / |sigma2|), X and Y of the sign of the stress
    Tsai-Wu         R the positive root of F11 s1^2 R^2 + ... : a R^2 + b R = 1 with
                    a = F11 s1^2 + F22 s2^2 + 2 F12 s1 s2, b = F1 s1 + F2 s2,
                    F1 = 1/Xt - 1/Xc, F11 = 1/(Xt Xc), likewise F2, F22, F12 = -sqrt(F11 F22)/2
No fatigue life is given for a composite: it does not follow a metal's S-N rules, and no
fatigue curve of this laminate is known.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.materials.mixtures import Constituent, Lamina
from flexlink.materials.strength import Strength


@dataclasses.dataclass(frozen=True)
class PlyStrength:
    """A unidirectional layer's strengths [Pa]: along the fibres Xt, Xc, across Yt, Yc,
    in-plane shear S."""

    Xt: float
    Xc: float
    Yt: float
    Yc: float
    S: float

    def __post_init__(self):
        for f in dataclasses.fields(self):
            if not getattr(self, f.name) > 0:
                raise ValueError(f"{f.name} must be positive")


def ply_strength(fiber: Constituent, fiber_strength: Strength, matrix: Constituent,
                 matrix_strength: Strength, fiber_fraction: float) -> PlyStrength:
    """The layer's strengths from its constituents' ``[strength]`` (module docstring); an
    InputError naming the file and key for a datum the files do not give."""
    why = "the ply strengths of a composite link"
    vf = fiber_fraction
    share = vf + (1.0 - vf) * matrix.E / fiber.E
    return PlyStrength(
        Xt=fiber_strength.need("tensile_strength", why).value * share,
        Xc=fiber_strength.need("compressive_strength", why).value * share,
        Yt=matrix_strength.need("tensile_strength", why).value,
        Yc=matrix_strength.need("compressive_strength", why).value,
        S=matrix_strength.need("shear_strength", why).value)


def layer_stresses(ply: Lamina, eps_x) -> np.ndarray:
    """(sigma1, sigma2) [Pa] of the 0 and 90 degree layers at strip strains ``eps_x``
    (...,): shape (..., 2 layers, 2)."""
    eps_x = np.asarray(eps_x, dtype=float)
    denom = 1.0 - ply.nu12 * ply.nu21
    q11, q22 = ply.E1 / denom, ply.E2 / denom
    q12 = ply.nu12 * q22
    eps_y = -q12 / (0.5 * (q11 + q22)) * eps_x
    zero = np.stack([q11 * eps_x + q12 * eps_y, q12 * eps_x + q22 * eps_y], axis=-1)
    ninety = np.stack([q11 * eps_y + q12 * eps_x, q12 * eps_y + q22 * eps_x], axis=-1)
    return np.stack([zero, ninety], axis=-2)


def max_stress_ratio(stresses, strength: PlyStrength) -> np.ndarray:
    """R [-] of layer stresses (..., 2) = (sigma1, sigma2) [Pa]; inf where unstressed."""
    s1, s2 = np.moveaxis(np.asarray(stresses, dtype=float), -1, 0)
    X = np.where(s1 >= 0, strength.Xt, strength.Xc)
    Y = np.where(s2 >= 0, strength.Yt, strength.Yc)
    with np.errstate(divide="ignore"):
        return np.minimum(X / np.abs(s1), Y / np.abs(s2))


def tsai_wu_ratio(stresses, strength: PlyStrength) -> np.ndarray:
    """R [-] of layer stresses (..., 2) [Pa] by Tsai-Wu; inf where unstressed."""
    s1, s2 = np.moveaxis(np.asarray(stresses, dtype=float), -1, 0)
    p = strength
    F1, F2 = 1 / p.Xt - 1 / p.Xc, 1 / p.Yt - 1 / p.Yc
    F11, F22 = 1 / (p.Xt * p.Xc), 1 / (p.Yt * p.Yc)
    F12 = -0.5 * np.sqrt(F11 * F22)
    a = F11 * s1**2 + F22 * s2**2 + 2 * F12 * s1 * s2
    b = F1 * s1 + F2 * s2
    with np.errstate(divide="ignore", invalid="ignore"):
        root = 2.0 / (b + np.sqrt(b * b + 4 * a))  # (-b + sqrt(b^2 + 4a)) / 2a, no cancellation
    return np.where(a + np.abs(b) > 0, root, np.inf)
