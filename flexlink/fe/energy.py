"""Strain energy of displacement fields computed from element deformations, and lumped mass.

Why: the assembled K of a fine mesh holds entries of size EI / h^3, while a smooth mode's
energy is of size EI / L^3; every element of a link has the same matrix, so the round-off of
those entries adds up coherently and moves the eigenvalue by about eps (L / h)^4 (4e-7 relative
at 256 elements per link). The same energy written with the element deformations
    axial:   EA / h (du)^2,                           du = u2 - u1 in the link direction
    bending: 4 EI / h (a^2 + a b + b^2),              a = rz1 - dv / h, b = rz2 - dv / h
    spring:  k (d_a - d_b)^2                          (d_b = 0 for ground)
(twice the strain energy; exactly u^T K u for the Euler-Bernoulli frame element of
``link.py``) has no such cancellation. The Rayleigh quotient of a computed eigenvector with
this energy is then accurate to the square of the vector's error, i.e. to about 1e-12.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp

from flexlink.fe.beams import BeamTheory
from flexlink.fe.joints import spring_energies
from flexlink.fe.model import FrameModel
from flexlink.fe.timoshenko import twice_bending_energy


def bending_energy(section, h: float, a, b):
    """Twice the bending strain energy of elements of length h [m] with end rotations a, b
    [rad] relative to their chords, in the section's beam theory."""
    if section.beam is BeamTheory.TIMOSHENKO:
        return twice_bending_energy(section.EI, section.kGA, h, a, b)
    return 4 * section.EI / h * (a * a + a * b + b * b)


def twice_strain_energy(model: FrameModel, shapes: np.ndarray) -> np.ndarray:
    """u^T K u [J x 2] for each column u of ``shapes`` (n_full, k), without cancellation."""
    U = np.asarray(shapes, dtype=float).reshape(model.n_dofs, -1)
    total = np.zeros(U.shape[1])
    for link in model.links:
        s, h = link.section, link.length / link.elements
        c, sn = math.cos(link.angle), math.sin(link.angle)
        nodes = link.nodes
        dx, dy = np.diff(U[3 * nodes], axis=0), np.diff(U[3 * nodes + 1], axis=0)
        rz = U[3 * nodes + 2]
        stretch = c * dx + sn * dy
        chord = (-sn * dx + c * dy) / h  # chord rotation of each element [rad]
        a, b = rz[:-1] - chord, rz[1:] - chord
        total += (s.EA / h * (stretch**2).sum(axis=0)
                  + bending_energy(s, h, a, b).sum(axis=0))
    finite = np.isfinite(model.springs.stiffness)  # rigid springs carry no energy
    total += spring_energies(model.springs, U)[finite].sum(axis=0)
    return total


def lumped_mass(model: FrameModel) -> sp.csr_matrix:
    """Diagonal (HRZ) lumped mass [kg, kg m^2] of the whole model, joint masses included.

    Per element of length h and mass m = rhoA h: m / 2 on each end node in x and y, and the
    consistent matrix's rotational diagonal (4 h^2 m / 420) scaled by the same factor as its
    translational diagonal (m / 2 over 156 m / 420), i.e. m h^2 / 78. Equal x and y masses
    make it invariant under the link's rotation. Frequencies converge at order 2 in h (the
    consistent mass: order 4 in bending)."""
    diag = np.zeros(model.n_dofs)
    for link in model.links:
        h = link.length / link.elements
        m = link.section.mass_per_length * h
        share = np.full(link.elements + 1, m)
        share[[0, -1]] = m / 2
        nodes = link.nodes
        diag[3 * nodes] += share
        diag[3 * nodes + 1] += share
        diag[3 * nodes + 2] += share * h**2 / 39  # two element ends of m h^2 / 78 per inner node
    for node, mass in model.point_masses:
        diag[3 * node] += mass
        diag[3 * node + 1] += mass
    return sp.diags(diag, format="csr")
