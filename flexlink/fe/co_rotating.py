"""Co-rotating node coordinates of a linkage model: each node's in-plane translation measured
along its link's direction, which keeps a mode's meaning as the links turn over the cycle.

DOF order per node: (ux, uy, rz); rz is unchanged by a rotation in the plane.
"""

from __future__ import annotations

import numpy as np

from flexlink.errors import NumericalError
from flexlink.fe.rotating import node_owners


def link_angles(model) -> np.ndarray:
    """Each link's direction angle [rad] from its first node to its last."""
    ends = np.array([model.nodes[link.nodes[-1]] - model.nodes[link.nodes[0]]
                     for link in model.links])
    return np.arctan2(ends[:, 1], ends[:, 0])


def co_rotating_turn(model, reference, T) -> np.ndarray:
    """R (reduced) taking co-rotating node DOFs to global ones: each node's (ux, uy) turned by
    how far its link has turned since the reference pose (``reference``: its link angles).
    The co-rotating DOFs keep a mode's meaning over the turn (a crank's bending stays bending
    after half a revolution); global ones do not. A rigid pin's shared translation turns
    with the first of its links (one DOF, one rotation: any choice is a valid coordinate)."""
    node_turn = (link_angles(model) - reference)[node_owners(model)]
    if T is not None:
        T = T.tocsc()
        for j in np.flatnonzero(np.diff(T.indptr) > 1):
            nodes = T.indices[T.indptr[j]:T.indptr[j + 1]] // 3
            node_turn[nodes] = node_turn[nodes[0]]
    c, s = np.cos(node_turn), np.sin(node_turn)
    R = np.zeros((model.n_dofs, model.n_dofs))
    ux, uy = 3 * np.arange(len(model.nodes)), 3 * np.arange(len(model.nodes)) + 1
    R[ux, ux], R[ux, uy], R[uy, ux], R[uy, uy] = c, -s, s, c
    R[ux + 2, ux + 2] = 1.0
    # R T = T Rr: Rr = (T^T T)^-1 T^T R T, T^T T counting the DOFs tied in each column
    Rr = R if T is None else (np.asarray(T.T @ (T.T @ R.T).T)
                              / np.diff(T.indptr)[:, None])
    if not np.allclose(Rr.T @ Rr, np.eye(Rr.shape[0]), atol=1e-12):
        raise NumericalError("a grounded or tied DOF is one direction of a turning node: the "
                             "co-rotating coordinates cannot be formed")
    return Rr
