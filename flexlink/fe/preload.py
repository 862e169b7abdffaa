"""The inertia preload: the frame solved statically under its d'Alembert loads, and the axial
force of every element.

A link moving rigidly has at a point r the acceleration a(r) = a_0 + alpha k x (r - r_0)
- omega^2 (r - r_0), linear along the link. Its d'Alembert load -rhoA a(x) per unit length is
turned into nodal loads with the element's own translational interpolation Nw
(``rotating.translational_interpolation``): f_e = -int rhoA Nw^T a(x) dx, a(x) linear between
the element's end nodes (exact, as a is linear on a rigid body), by 4-point Gauss quadrature. A
Timoshenko element's rotary inertia adds the moment -rhoI alpha per unit length on its rotation
DOFs (``int Npsi`` of it); Euler-Bernoulli elements have no rotary inertia. A joint mass m adds
-m a at its node. External loads, when given, are added as nodal loads.

The frame (the crank held by its drive spring or rigid drive, the ground bearings by theirs)
is then solved for u with K u = f; the joint forces and the driving torque are its reactions.
Each element's axial force is N = EA (u2 - u1) / h along its axis: the mean of the element's
axial force over its length (exact nodal values of a linear element), tension positive.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from flexlink.errors import NumericalError
from flexlink.fe.beams import BeamTheory, shear_parameter
from flexlink.fe.rotating import gauss_interpolation
from flexlink.fe.timoshenko import WEIGHTS, XI, shape_functions

RESIDUAL_TOL = 1e-10  # backward error of K u = f beyond which the static solve is refused


def element_inertia_loads(model, node_accelerations: np.ndarray, alpha) -> tuple[np.ndarray, ...]:
    """Per link of ``model`` (a FrameModel) the consistent d'Alembert loads (e, 6) [N, N m] of
    each element in the link frame, DOF order (u1, v1, rz1, u2, v2, rz2), for the rigid node
    accelerations ``node_accelerations`` (N, 2) [m/s^2, global] and the links' angular
    accelerations ``alpha`` (per link) [rad/s^2]. Joint masses are not in them (they act at
    nodes)."""
    acc = np.asarray(node_accelerations, dtype=float)
    out = []
    for link, a_link in zip(model.links, np.asarray(alpha, dtype=float)):
        s, h = link.section, link.length / link.elements
        phi = shear_parameter(s, h)
        c, sn = math.cos(link.angle), math.sin(link.angle)
        a = acc[link.nodes]
        local = np.stack([c * a[:, 0] + sn * a[:, 1], -sn * a[:, 0] + c * a[:, 1]], axis=1)
        q0, q1 = -s.mass_per_length * local[:-1], -s.mass_per_length * local[1:]  # (e, 2)
        Nw = gauss_interpolation(h, phi)  # (g, 2, 6)
        # load per unit length at each Gauss point: q0 (1 - xi) + q1 xi, (e, g, 2)
        q = q0[:, None, :] * (1.0 - XI)[None, :, None] + q1[:, None, :] * XI[None, :, None]
        fe = h * np.einsum("g,gai,ega->ei", WEIGHTS, Nw, q)
        if s.beam is BeamTheory.TIMOSHENKO:
            _, _, Npsi, _ = shape_functions(XI, h, phi)
            fe[:, [1, 2, 4, 5]] += -s.rotary_inertia * a_link * h * (Npsi @ WEIGHTS)
        out.append(fe)
    return tuple(out)


def inertia_loads(model, node_accelerations: np.ndarray, alpha) -> np.ndarray:
    """d'Alembert nodal loads (n_dofs,) [N, N m] of ``model`` (a FrameModel) whose nodes have
    the rigid accelerations ``node_accelerations`` (N, 2) [m/s^2, global] and whose links turn
    with angular accelerations ``alpha`` (per link) [rad/s^2]: the elements' own
    (``element_inertia_loads``) summed at the nodes, and the joint masses'."""
    acc = np.asarray(node_accelerations, dtype=float)
    parts = []
    for link, fe in zip(model.links, element_inertia_loads(model, acc, alpha)):
        c, sn = math.cos(link.angle), math.sin(link.angle)
        # local (u, v, rz) -> global (ux, uy, rz): R^T per node; ends k = 0, 1 of each element
        for k, nodes in ((0, link.nodes[:-1]), (1, link.nodes[1:])):
            parts.append((3 * nodes, c * fe[:, 3 * k] - sn * fe[:, 3 * k + 1]))
            parts.append((3 * nodes + 1, sn * fe[:, 3 * k] + c * fe[:, 3 * k + 1]))
            parts.append((3 * nodes + 2, fe[:, 3 * k + 2]))
    index, values = (np.concatenate(p) for p in zip(*parts))
    f = np.bincount(index, weights=values, minlength=model.n_dofs)
    for node, m in model.point_masses:
        f[3 * node:3 * node + 2] -= m * acc[node]
    return f


def static_displacement(Kr, T, f: np.ndarray) -> np.ndarray:
    """u (n_full,) with Kr q = T^T f, u = T q: the frame's static answer to loads ``f``.
    ``Kr`` the reduced stiffness T^T K T (dense or sparse), ``T`` from ``assembly.rigid_elimination``
    (None: nothing rigid). NumericalError when Kr is singular (a mechanism: nothing holds the
    frame against the loads)."""
    fr = f if T is None else T.T @ f
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", la.LinAlgWarning)  # the residual check below judges
        try:
            if sp.issparse(Kr):
                q = spla.splu(sp.csc_matrix(Kr)).solve(fr)
            else:  # a frame held at rest: K is definite
                q = la.cho_solve(la.cho_factor(Kr, check_finite=False), fr, check_finite=False)
        except (RuntimeError, la.LinAlgError):
            q = np.full_like(fr, np.nan)
    # normwise backward error: a stable solve keeps it near eps however ill-conditioned Kr is
    size = abs(Kr).sum(axis=0).max() * np.abs(q).sum() + np.abs(fr).sum()
    if not np.all(np.isfinite(q)) or np.abs(Kr @ q - fr).sum() > RESIDUAL_TOL * size:
        raise NumericalError(
            "the frame cannot carry its inertia loads statically: K is singular (a mechanism "
            "mode; the crank needs a drive and the links their bearings to hold the pose)")
    return q if T is None else np.asarray(T @ q)


def axial_forces(model, u: np.ndarray) -> tuple[np.ndarray, ...]:
    """Per link the (elements,) axial forces N = EA (u2 - u1) / h [N, tension positive] of the
    displacement ``u`` (n_dofs,)."""
    out = []
    for link in model.links:
        c, sn = math.cos(link.angle), math.sin(link.angle)
        nodes = link.nodes
        stretch = np.diff(c * u[3 * nodes] + sn * u[3 * nodes + 1])
        out.append(link.section.EA / (link.length / link.elements) * stretch)
    return tuple(out)
