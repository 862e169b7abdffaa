"""Rotating-frame terms of a link that turns with angular velocity omega and acceleration alpha.

Derivation. Measure a link's elastic displacement w = (u, v) in the link's own frame, which
turns with the link's rigid motion (origin at its start joint, x along the link, angular
velocity omega, angular acceleration alpha, both about the plane's normal k). A material
point at rest position rho0 = (x, 0) is at rho = rho0 + w in that frame, and its absolute
acceleration, written in the frame's axes, is
    a = a_O + alpha k x rho - omega^2 rho + 2 omega k x w' + w''     (' = d/dt in the frame)
with k x (a, b) = J (a, b) = (-b, a), J = [[0, -1], [1, 0]]. Split at w = 0:
    rigid part     a_O + alpha J rho0 - omega^2 rho0   -> the d'Alembert preload (``preload``)
    linear in w    w'' + 2 omega J w' + (alpha J - omega^2 I) w.
With w = Nw q over an element (u linear, v the element's own transverse interpolation,
``timoshenko.shape_functions``; Hermite at Phi = 0), the virtual work of -rhoA times the
linear part gives, per element,
    M q'' + 2 omega S q' + (alpha S - omega^2 Mt) q,
    Mt = int rhoA Nw^T Nw dx      (the translational part of the consistent mass; all of it for
                                   Euler-Bernoulli; Timoshenko's rotary inertia has no term,
                                   since its angle adds to the frame's: (omega + psi')^2)
    S  = int rhoA Nw^T J Nw dx    (skew: S^T = int Nw^T J^T Nw = -S)
so the centrifugal softening is -omega^2 Mt, the gyroscopic (Coriolis) matrix G = 2 omega S
(skew, it does no work) and the angular-acceleration term alpha S (a skew, circulatory
stiffness). All are written in the link frame and rotated to the pose with T^T A T like K and M
(J commutes with rotations, so S stays skew). A joint mass m is a particle at its node; the node
is measured in the frame of the link whose chain it belongs to, so it carries m I in place of
Mt and m J in place of S.

At an instant the frames of two links meeting at a pin are different turning frames; the pin
ties their displacements at the instant (global components), the usual frozen-configuration
assumption of kineto-elastodynamics: the constraint's own rotation is not carried.
"""

from __future__ import annotations

import functools

import numpy as np

from flexlink.fe.beams import shear_parameter
from flexlink.fe.chain import rotated_chain
from flexlink.fe.timoshenko import WEIGHTS, XI, shape_functions

J = np.array([[0.0, -1.0], [1.0, 0.0]])


def translational_interpolation(h: float, phi: float = 0.0, xi: np.ndarray = XI) -> np.ndarray:
    """Nw at ``xi`` = x / h: (g, 2, 6), rows u and v of the element's displacement in its frame
    from the DOFs (u1, v1, rz1, u2, v2, rz2); h [m], phi the shear parameter (0: Hermite)."""
    xi = np.asarray(xi, dtype=float)
    Nv, _, _, _ = shape_functions(xi, h, phi)
    out = np.zeros((len(xi), 2, 6))
    out[:, 0, 0], out[:, 0, 3] = 1.0 - xi, xi
    out[:, 1, [1, 2, 4, 5]] = Nv.T
    return out


@functools.lru_cache(maxsize=256)
def gauss_interpolation(h: float, phi: float = 0.0) -> np.ndarray:
    """``translational_interpolation`` at the 4 Gauss points ``timoshenko.XI``, read-only."""
    out = translational_interpolation(h, phi)
    out.flags.writeable = False
    return out


def translational_mass(h: float, rhoA: float, phi: float = 0.0) -> np.ndarray:
    """Mt = int rhoA Nw^T Nw dx, 6 x 6 [kg] (4-point Gauss, exact for the cubic v)."""
    return _element_pair(float(h), float(rhoA), float(phi))[0]


def coupling(h: float, rhoA: float, phi: float = 0.0) -> np.ndarray:
    """S = int rhoA Nw^T J Nw dx, 6 x 6 [kg], skew."""
    return _element_pair(float(h), float(rhoA), float(phi))[1]


@functools.lru_cache(maxsize=256)
def _element_pair(h: float, rhoA: float, phi: float):
    """(Mt, S), read-only: cached, as a sweep asks for the same link at every pose."""
    Nw = gauss_interpolation(h, phi)
    out = (rhoA * h * np.einsum("g,gai,gaj->ij", WEIGHTS, Nw, Nw),
           rhoA * h * np.einsum("g,gai,ab,gbj->ij", WEIGHTS, Nw, J, Nw))
    for a in out:
        a.flags.writeable = False
    return out


def node_owners(model) -> np.ndarray:
    """Index of the link whose chain owns each node of ``model`` (N,)."""
    owner = np.empty(len(model.nodes), dtype=np.int64)
    for i, link in enumerate(model.links):
        owner[link.nodes] = i
    return owner


def rotating_entries(model, omega, alpha):
    """Global entries (rows, cols, values (3, E)) of the centrifugal -omega^2 Mt, gyroscopic
    2 omega S and circulatory alpha S matrices of ``model`` (a FrameModel), joint masses
    included; ``omega`` [rad/s] and ``alpha`` [rad/s^2] per link (model.links order)."""
    omega, alpha = np.asarray(omega, dtype=float), np.asarray(alpha, dtype=float)
    mats = []
    for link, w, a in zip(model.links, omega, alpha):
        h = link.length / link.elements
        phi = shear_parameter(link.section, h)
        rhoA = link.section.mass_per_length
        Mt, S = translational_mass(h, rhoA, phi), coupling(h, rhoA, phi)
        one = np.ones((link.elements, 1, 1))
        mats.append(np.stack([-w * w * Mt * one, 2.0 * w * S * one, a * S * one]))
    rows, cols, values = rotated_chain(model.links, mats)
    owner = node_owners(model)
    p_rows, p_cols, p_vals = [], [], []
    for node, m in model.point_masses:
        w, a = omega[owner[node]], alpha[owner[node]]
        for i in range(2):
            for j in range(2):
                p_rows.append(3 * node + i)
                p_cols.append(3 * node + j)
                p_vals.append([-w * w * m * (i == j), 2.0 * w * m * J[i, j], a * m * J[i, j]])
    if p_rows:
        rows = np.concatenate([rows, p_rows])
        cols = np.concatenate([cols, p_cols])
        values = np.concatenate([values, np.array(p_vals).T], axis=1)
    return rows, cols, values
