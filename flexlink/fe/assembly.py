"""Global sparse stiffness K and mass M of a FrameModel, and the exact elimination of rigid joints.

K, M: size 3 N (model.DOF_NAMES per node). Links are rotated from their local frame with
T^T k T, where T = blockdiag(R) and R maps global (ux, uy, rz) to local (u, v, rz):
    R = [[ c, s, 0],
         [-s, c, 0],
         [ 0, 0, 1]],  c = cos(angle), s = sin(angle).
Springs are two-node elements k [[1, -1], [-1, 1]] on a pair of DOFs (or k on one DOF, to
ground). Infinite springs are not added to K: ``rigid_elimination`` turns them into exact constraints.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp

from flexlink.fe.beams import link_entries
from flexlink.fe.joints import joint_mass_entries
from flexlink.fe.model import GROUND, FrameModel


def node_rotation(angle: float) -> np.ndarray:
    """3x3 R with local = R @ global for one node, ``angle`` [rad] of the link axis."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def rotated_entries(rows, cols, values, cos, sin):
    """Entries of T^T A T from entries of A, T = blockdiag(R) with a rotation per entry.

    rows, cols (e,): DOF indices (3 per node); values (v, e): v matrices sharing those entries;
    cos, sin (e,): the rotation of each entry's link. Each entry (3a + p, 3b + q) spreads over
    its 3 x 3 node block: A'[3a + i, 3b + j] += R[p, i] A[3a + p, 3b + q] R[q, j].
    Returns (rows (9e,), cols (9e,), values (v, 9e)); repeated (row, col) pairs are to be summed.
    """
    rows, cols = np.asarray(rows), np.asarray(cols)
    zero, one = np.zeros_like(cos), np.ones_like(cos)
    R = np.stack([np.stack([cos, sin, zero], -1), np.stack([-sin, cos, zero], -1),
                  np.stack([zero, zero, one], -1)], 1)  # (e, 3, 3)
    e = np.arange(len(rows))
    a, b = R[e, rows % 3], R[e, cols % 3]  # (e, 3): row p of R, row q of R
    spread = np.asarray(values)[:, :, None, None] * (a[:, :, None] * b[:, None, :])
    block = np.arange(3)
    out_rows = (rows - rows % 3)[:, None, None] + block[None, :, None]
    out_cols = (cols - cols % 3)[:, None, None] + block[None, None, :]
    shape = (len(rows), 3, 3)
    return (np.broadcast_to(out_rows, shape).ravel(), np.broadcast_to(out_cols, shape).ravel(),
            spread.reshape(spread.shape[0], -1))


def placed_link_entries(model: FrameModel):
    """All links' local entries at their global node offsets, not yet rotated:
    (rows, cols, values (2, e) = K and M, cos, sin (e,) of each entry's link)."""
    parts = []
    next_node = 0
    for link in model.links:
        if link.first_node != next_node:  # build_model numbers links contiguously
            raise AssertionError("links must own consecutive node ranges")
        s = link.section
        rows, cols, k, m = link_entries(link.length, link.elements, s)
        offset = 3 * link.first_node
        parts.append((rows + offset, cols + offset, k, m,
                      np.full(len(rows), math.cos(link.angle)),
                      np.full(len(rows), math.sin(link.angle))))
        next_node += link.elements + 1
    rows, cols, k, m, c, s = (np.concatenate(column) for column in zip(*parts))
    return rows, cols, np.stack([k, m]), c, s


def spring_entries(model: FrameModel):
    """(rows, cols, values) of the model's finite springs; rigid ones are left to
    ``rigid_elimination``."""
    return springs_stiffness_entries(model.springs)


def springs_stiffness_entries(springs):
    """(rows, cols, values) of two-node springs k [[1, -1], [-1, 1]] (or k to ground) for the
    finite entries of a ``model.Springs``."""
    finite = np.isfinite(springs.stiffness)
    a, b, k = springs.dof_a[finite], springs.dof_b[finite], springs.stiffness[finite]
    to_node = b != GROUND
    rows = np.concatenate([a, b[to_node], a[to_node], b[to_node]])
    cols = np.concatenate([a, b[to_node], b[to_node], a[to_node]])
    vals = np.concatenate([k, k[to_node], -k[to_node], -k[to_node]])
    return rows, cols, vals


def point_mass_entries(model: FrameModel):
    """(rows, cols, values) of the lumped joint masses (translational DOFs only)."""
    return joint_mass_entries(model.point_masses, (0, 1))


def assemble(model: FrameModel) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """(K [N/m, N, N m per rad], M [kg, kg m, kg m^2]) for the whole model, CSR, not reduced."""
    n = model.n_dofs
    rows, cols, values = rotated_entries(*placed_link_entries(model))
    k_rows, k_cols, k_vals = spring_entries(model)
    m_rows, m_cols, m_vals = point_mass_entries(model)
    K = sp.coo_matrix((np.concatenate([values[0], k_vals]),
                       (np.concatenate([rows, k_rows]), np.concatenate([cols, k_cols]))),
                      shape=(n, n)).tocsr()
    M = sp.coo_matrix((np.concatenate([values[1], m_vals]),
                       (np.concatenate([rows, m_rows]), np.concatenate([cols, m_cols]))),
                      shape=(n, n)).tocsr()
    return K, M


def reduced_columns(T, n_full: int) -> tuple[np.ndarray, int]:
    """(column (n_full,), n_reduced): each full DOF's reduced DOF under u = T q, -1 where it is
    grounded. T (from ``rigid_elimination``, None: nothing rigid) is 0/1 with at most one 1 per row,
    so T^T A T only renumbers and drops A's entries."""
    if T is None:
        return np.arange(n_full), n_full
    T = T.tocsr()
    if not (np.all(T.data == 1.0) and np.all(np.diff(T.indptr) <= 1)):
        raise AssertionError("the rigid elimination must map each DOF to at most one reduced DOF")
    column = np.full(n_full, -1)
    column[np.diff(T.indptr) == 1] = T.indices
    return column, T.shape[1]


def dense_slots(column: np.ndarray, n: int, rows, cols) -> np.ndarray:
    """Flat index r n + c in the reduced n x n matrix of each full entry (rows, cols), or n^2
    (a spare slot, dropped) where either DOF is grounded; ``column`` from ``reduced_columns``."""
    r, c = column[rows], column[cols]
    return np.where((r >= 0) & (c >= 0), r * n + c, n * n)


def dense_sum(slots, values, n: int) -> np.ndarray:
    """The n x n dense matrix of ``values`` summed into their ``dense_slots``."""
    summed = np.bincount(slots, weights=values, minlength=n * n + 1)
    return summed[:n * n].reshape(n, n)


def reduced_dense_pair(T, n_full: int, stiffness, mass) -> tuple[np.ndarray, np.ndarray]:
    """Dense (T^T K T, T^T M T), T from ``rigid_elimination`` (None: nothing rigid), of K and M of size
    ``n_full`` given as entries ``stiffness``, ``mass`` = (rows, cols, values), repeated pairs
    summed; one ``np.bincount`` for both (M's slots follow K's)."""
    column, n = reduced_columns(T, n_full)
    size = n * n + 1
    slots = np.concatenate([dense_slots(column, n, stiffness[0], stiffness[1]),
                            dense_slots(column, n, mass[0], mass[1]) + size])
    summed = np.bincount(slots, weights=np.concatenate([stiffness[2], mass[2]]),
                         minlength=2 * size)
    return summed[:n * n].reshape(n, n), summed[size:size + n * n].reshape(n, n)


def assemble_reduced_dense(model: FrameModel, T) -> tuple[np.ndarray, np.ndarray]:
    """Dense (T^T K T, T^T M T) of ``assemble``'s K and M, with T from ``rigid_elimination``, scattered
    straight from the element entries (no sparse matrix built): for the small models the dense
    eigen solver takes, where scipy.sparse's bookkeeping costs more than the solve."""
    column, n = reduced_columns(T, model.n_dofs)
    rows, cols, values = rotated_entries(*placed_link_entries(model))
    k_rows, k_cols, k_vals = spring_entries(model)
    m_rows, m_cols, m_vals = point_mass_entries(model)
    link = dense_slots(column, n, rows, cols)
    size = n * n + 1  # M's slots follow K's: one bincount for both
    slots = np.concatenate([link, dense_slots(column, n, k_rows, k_cols),
                            link + size, dense_slots(column, n, m_rows, m_cols) + size])
    summed = np.bincount(slots, weights=np.concatenate([values[0], k_vals, values[1], m_vals]),
                         minlength=2 * size)
    return summed[:n * n].reshape(n, n), summed[size:size + n * n].reshape(n, n)


def rigid_elimination(model: FrameModel) -> sp.csr_matrix | None:
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


def eliminating_assembler(column: np.ndarray, n: int, dense: bool):
    """Global entries (rows, cols, values) of a full-size matrix -> its n x n T^T A T, dense or
    sparse CSR; ``column``, ``n`` from ``reduced_columns`` (T only renumbers and drops DOFs,
    so the entries are renumbered and summed, no product formed)."""
    if dense:
        return lambda rows, cols, vals: dense_sum(dense_slots(column, n, rows, cols), vals, n)

    def sparse(rows, cols, vals):
        r, c = column[rows], column[cols]
        keep = (r >= 0) & (c >= 0)
        return sp.csr_matrix((vals[keep], (r[keep], c[keep])), shape=(n, n))
    return sparse


def eliminated_pair(model: FrameModel, T, assemble, direct: bool):
    """(T^T K T, T^T M T) of ``model``: by ``assemble_reduced_dense`` when ``direct`` (small
    models), else through ``assemble`` (an ``eliminating_assembler``) from the entries."""
    if direct:
        return assemble_reduced_dense(model, T)
    rows, cols, values = rotated_entries(*placed_link_entries(model))
    springs, masses = spring_entries(model), point_mass_entries(model)
    return (assemble(*(np.concatenate(p) for p in zip((rows, cols, values[0]), springs))),
            assemble(*(np.concatenate(p) for p in zip((rows, cols, values[1]), masses))))
