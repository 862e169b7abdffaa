"""Global sparse stiffness K and mass M of a FrameModel, and the exact reduction of rigid joints.

K, M: size 3 N (model.DOF_NAMES per node). Links are rotated from their local frame with
T^T k T, where T = blockdiag(R) and R maps global (ux, uy, rz) to local (u, v, rz):
    R = [[ c, s, 0],
         [-s, c, 0],
         [ 0, 0, 1]],  c = cos(angle), s = sin(angle).
Springs are two-node elements k [[1, -1], [-1, 1]] on a pair of DOFs (or k on one DOF, to
ground). Infinite springs are not added to K: ``reduction`` turns them into exact constraints.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp

from .model import GROUND, FrameModel


def rotation(angle: float) -> np.ndarray:
    """3x3 R with local = R @ global for one node, ``angle`` [rad] of the link axis."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def _rotated(matrix, angle: float, nodes: int):
    T = sp.kron(sp.identity(nodes, format="csr"), sp.csr_matrix(rotation(angle)), format="csr")
    return (T.T @ matrix @ T).tocsr()


def assemble(model: FrameModel) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """(K [N/m, N, N m per rad], M [kg, kg m, kg m^2]) for the whole model, CSR, not reduced."""
    k_blocks, m_blocks = [], []
    next_node = 0
    for link in model.links:
        if link.first_node != next_node:  # build_model numbers links contiguously
            raise AssertionError("links must own consecutive node ranges")
        k_local, m_local = link.local_matrices()
        n = link.elements + 1
        k_blocks.append(_rotated(k_local, link.angle, n))
        m_blocks.append(_rotated(m_local, link.angle, n))
        next_node += n
    K = sp.block_diag(k_blocks, format="csr")
    M = sp.block_diag(m_blocks, format="csr")

    springs = model.springs
    finite = np.isfinite(springs.stiffness)
    a, b, k = springs.dof_a[finite], springs.dof_b[finite], springs.stiffness[finite]
    to_node = b != GROUND
    rows = np.concatenate([a, b[to_node], a[to_node], b[to_node]])
    cols = np.concatenate([a, b[to_node], b[to_node], a[to_node]])
    vals = np.concatenate([k, k[to_node], -k[to_node], -k[to_node]])
    n = model.n_dofs
    K = K + sp.coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsr()

    if model.point_masses:
        nodes = np.array([p[0] for p in model.point_masses])
        mass = np.array([p[1] for p in model.point_masses])
        idx = np.concatenate([3 * nodes, 3 * nodes + 1])
        M = M + sp.coo_matrix((np.concatenate([mass, mass]), (idx, idx)), shape=(n, n)).tocsr()
    return K, M


def reduction(model: FrameModel) -> sp.csr_matrix | None:
    """T (n_full x n_reduced) with u = T q that enforces the rigid (infinite) springs exactly:
    tied DOFs share one unknown, grounded DOFs have none. None when nothing is rigid."""
    springs = model.springs
    rigid = ~np.isfinite(springs.stiffness)
    if not rigid.any():
        return None
    n = model.n_dofs
    parent = np.arange(n + 1)  # index n stands for the ground

    def find(i):
        root = i
        while parent[root] != root:
            root = parent[root]
        while parent[i] != root:
            parent[i], i = root, parent[i]
        return root

    for a, b in zip(springs.dof_a[rigid], springs.dof_b[rigid]):
        ra, rb = find(a), find(n if b == GROUND else b)
        if ra != rb:  # the ground (index n) stays a root, so grounded groups show as root n
            if rb == n:
                parent[ra] = n
            else:
                parent[rb] = ra
    roots = np.array([find(i) for i in range(n)])
    free_roots = np.unique(roots[roots != n])
    column = np.full(n + 1, -1)
    column[free_roots] = np.arange(len(free_roots))
    keep = roots != n
    rows = np.nonzero(keep)[0]
    return sp.csr_matrix((np.ones(len(rows)), (rows, column[roots[keep]])),
                         shape=(n, len(free_roots)))
