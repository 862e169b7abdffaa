"""Sensor placement by Effective Independence (Kammer, J. Guidance 14(2), 1991).

Candidate channels (a point and a direction each) read the k target mode shapes as the rows
of Phi (candidates, k). With unit, uncorrelated sensor noise the Fisher information of the
modal coordinates is A = Phi^T Phi; the share of candidate c in the rank of A is the diagonal
of the projector
    E_D = diag(Phi A^-1 Phi^T),   0 <= E_D <= 1,  sum E_D = k,
and removing the candidate of smallest E_D loses the least of det A. Effective Independence
removes candidates one at a time until the count asked for is left, so the modes stay as
linearly independent, and as distinguishable (low autoMAC), as the candidates allow. A
candidate on a nodal line of every target mode has E_D = 0 and goes first.
"""

from __future__ import annotations

import numpy as np

from flexlink.errors import InputError


def independence(Phi: np.ndarray) -> np.ndarray:
    """E_D (candidates,) of the rows of ``Phi`` (candidates, k), by a thin QR factorisation
    (Phi = Q R, so E_D is the squared row norms of Q), without forming A^-1."""
    Q, _ = np.linalg.qr(Phi)
    return np.einsum("ij,ij->i", Q, Q)


def effective_independence(Phi: np.ndarray, count: int) -> np.ndarray:
    """Indices (ascending) of the ``count`` rows of ``Phi`` (candidates, k) kept by removing
    the row of least effective independence one at a time. Needs k <= count <= candidates
    and Phi of full column rank (every target mode seen by the candidates)."""
    Phi = np.asarray(Phi, dtype=float)
    n, k = Phi.shape
    if not k <= count <= n:
        raise InputError(f"{count} sensors for {k} target modes out of {n} candidates",
                         source="command line", field="--count",
                         expected=f"at least as many sensors as target modes ({k}) and at most "
                                  f"the candidates ({n})")
    if np.linalg.matrix_rank(Phi) < k:
        raise InputError("the candidate sensors cannot tell the target modes apart (their "
                         "shapes at the candidates are linearly dependent)",
                         source="command line", field="--modes",
                         expected="fewer target modes, or more candidates (--stations)")
    kept = np.arange(n)
    while len(kept) > count:
        worst = int(np.argmin(independence(Phi[kept])))
        kept = np.delete(kept, worst)
    return kept


def fisher_determinant(Phi: np.ndarray) -> float:
    """det(Phi^T Phi) of the readings ``Phi`` (sensors, k): the Fisher information of the k
    modal coordinates for unit sensor noise, in (shape units)^(2k)."""
    Phi = np.asarray(Phi, dtype=float)
    return float(np.linalg.det(Phi.T @ Phi))
