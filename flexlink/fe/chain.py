"""Per-element 6 x 6 matrices of a link's chain as global entries, rotated to the pose.

A link's elements e = 0 ... n-1 join nodes first_node + e and first_node + e + 1; local DOF
order per element (u1, v1, rz1, u2, v2, rz2) as in ``link.py``. Every element of a link has the
same rotation, so each element matrix A (written in the link frame, symmetric or not) is turned
to the global DOFs (ux, uy, rz) as T^T A T with T = blockdiag(R, R) (``assembly.node_rotation``)
before it is placed: 36 entries per element and matrix.
"""

from __future__ import annotations

import numpy as np

from flexlink.fe.assembly import node_rotation

_LOCAL_ROWS = np.repeat(np.arange(6), 6)
_LOCAL_COLS = np.tile(np.arange(6), 6)


def placed_elements(first_node: int, matrices: np.ndarray):
    """(rows, cols, values (..., 36 e)) of element ``matrices`` (..., e, 6, 6) placed on a chain
    starting at node ``first_node``; repeated (row, col) pairs are to be summed."""
    matrices = np.asarray(matrices, dtype=float)
    e = matrices.shape[-3]
    shift = 3 * (first_node + np.arange(e))[:, None]
    rows = (_LOCAL_ROWS[None, :] + shift).ravel()
    cols = (_LOCAL_COLS[None, :] + shift).ravel()
    return rows, cols, matrices.reshape(matrices.shape[:-3] + (36 * e,))


def rotated_chain(links, matrices):
    """Global entries (rows, cols, values (v, E)) of per-link element matrices turned to each
    link's angle. ``links``: LinkMesh sequence; ``matrices``: per link an array (v, e, 6, 6)
    of v matrices per element (the same v for every link)."""
    rows, cols, values = [], [], []
    for link, mats in zip(links, matrices):
        T = np.kron(np.eye(2), node_rotation(link.angle))
        turned = T.T @ np.asarray(mats, dtype=float) @ T
        r, c, v = placed_elements(link.first_node, turned)
        rows.append(r)
        cols.append(c)
        values.append(v)
    return np.concatenate(rows), np.concatenate(cols), np.concatenate(values, axis=-1)
