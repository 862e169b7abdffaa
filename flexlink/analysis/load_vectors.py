"""The static answers to a turn's loads, as directions to add to a modal basis (load-dependent
Ritz vectors, the static correction of a truncated modal basis).

A basis of the lowest modes holds a load's dynamic answer near its resonances and misses the
part of its static answer that lies along the modes left out; a slow load is answered by the
frame's statics, K^-1 f, not by its lowest modes. Given each pose's stiffness ``K`` (P, n, n)
and loads ``loads`` (sets, P, n), in coordinates that keep their meaning over the turn (the
co-rotating DOFs of ``analysis.pose_basis``), the static answers X = K_p^-1 f_p of every pose
and load set are:

1. made M_0-orthogonal to the basis V (M_0-orthonormal): X - V V^T M_0 X, twice (the second
   pass takes out what round-off left of V in the first);
2. compressed by SVD in M_0's inner product (of L^T X, M_0 = L L^T), keeping the directions
   whose singular value is at least ``threshold`` times the largest singular value of the
   static answers themselves (before step 1). The dropped directions hold at most that share
   of the static answers in the mass norm (the 2-norm of the snapshot matrix: its largest
   unit combination's M_0 norm), so every pose's static answer to its loads lies in the
   basis with the kept ones to ``threshold`` of the largest answer in that norm; the basis's
   own static answer (a Galerkin solve, the best in K's norm) is as close, as read in the
   displacements; the strains, derivatives, weigh the dropped stiff directions more
   (THRESHOLD).

With the vectors added, the basis solves the quasi-static limit of the forced periodic
equations at every sampled pose (to ``threshold``), and the dynamic answer keeps the part of
the loads' static answer the modes left out.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

# relative singular value kept, in the mass norm. Strain weighs the stiff directions more
# than that norm does: on Table II case 1 (2 modes, 4 elements a link) a cut at 1e-6 leaves
# 5e-5 of the static midspan curvature, 1e-8 leaves 1.5e-6, 1e-10 2e-10. On case 3 (6 modes)
# 1e-8 keeps 9 directions, and the midspan strain peaks move by under 0.03 % of the record's
# from 1e-7 to 1e-10 (tests/studies/test_time_domain_record.py)
THRESHOLD = 1e-8


def static_load_directions(K: np.ndarray, M0: np.ndarray, loads: np.ndarray, V: np.ndarray,
                           threshold: float = THRESHOLD) -> np.ndarray:
    """(n, k): the M_0-orthonormal directions of the module docstring, M_0-orthogonal to
    ``V`` (n, r), from each pose's K (P, n, n) and ``loads`` (sets, P, n); k = 0 where the
    loads vanish or their static answers lie in V's span to ``threshold``."""
    if not 0.0 < threshold < 1.0:
        raise ValueError(f"threshold must lie in (0, 1), got {threshold}")
    forcing = np.moveaxis(np.asarray(loads, dtype=float), 0, -1)  # (P, n, sets)
    X = np.concatenate(np.linalg.solve(K, forcing), axis=1)  # (n, P * sets)
    L = np.linalg.cholesky(M0)
    largest = np.linalg.norm(L.T @ X, 2) if X.size else 0.0
    if largest == 0.0:
        return np.zeros((len(M0), 0))
    for _ in range(2):
        X = X - V @ (V.T @ (M0 @ X))
    U, s, _ = np.linalg.svd(L.T @ X, full_matrices=False)
    W = sla.solve_triangular(L.T, U[:, s >= threshold * largest], lower=False)
    return W - V @ (V.T @ (M0 @ W))  # M_0-orthogonal to V to round-off
