"""Many small dense eigenproblems at once: the poses of a Craig-Bampton sweep.

A stack of pencils (K_p, M_p), each n x n with M_p positive definite, is solved as numpy solves
a stack: M_p = L_p L_p^T (Cholesky), A_p = L_p^-1 K_p L_p^-T, A_p = V_p diag(w_p) V_p^T (eigh),
X_p = L_p^-T V_p, so X_p^T M_p X_p = I (any factor M_p = L_p L_p^T will do; a caller that
knows the structure of M passes a cheaper one). One call per step for all poses replaces a
Python-level solve per pose, whose fixed cost is several times the arithmetic at a few dozen
DOFs.

Each answer is checked as ``solve.solve_modes`` checks one (same thresholds): finite, no
eigenvalue below -zero, normwise backward error <= 1e-10, M-orthogonality to 1e-6, and no
eigenvalue between the physical threshold and the round-off floor (where a mechanism mode cannot
be told from an elastic one). A failure is a NumericalError naming the first pose concerned.
"""

from __future__ import annotations

import dataclasses
import logging

import numpy as np

from flexlink.analysis.solve import (BACKWARD_TOL, ORTHOGONALITY_TOL, ROUNDOFF_WARN, ZERO_TOL,
                                     backward_errors, negative_message, not_finite_message,
                                     orthogonality_message, roundoff_floor)
from flexlink.errors import NumericalError

log = logging.getLogger(__name__)


@dataclasses.dataclass(frozen=True)
class StackedModes:
    """Every eigenpair of each pose, ascending: eigenvalues (P, n) [rad^2/s^2], vectors
    (P, n, n) with X^T M X = I; ``zero`` (P,): the threshold below which a mode is a
    rigid-body/mechanism mode [rad^2/s^2]."""

    eigenvalues: np.ndarray
    vectors: np.ndarray
    zero: np.ndarray

    @property
    def mechanisms(self) -> np.ndarray:
        """(P,) number of rigid-body/mechanism modes per pose (they sit lowest)."""
        return (self.eigenvalues < self.zero[:, None]).sum(axis=1)


def _fail(message: str, bad: np.ndarray) -> NumericalError:
    return NumericalError(f"{message} at pose {int(np.argmax(bad))} of the sweep "
                          f"({int(bad.sum())} pose(s) in all)")


def stacked_modes(K: np.ndarray, M: np.ndarray, lambda_ref: np.ndarray, checked: int,
                  factor: np.ndarray | None = None) -> StackedModes:
    """All modes of each pencil of the stacks ``K``, ``M`` (P, n, n); ``lambda_ref`` (P,): each
    pose's own eigenvalue scale [rad^2/s^2] (``pose.in_plane_eigen_scale``); the lowest
    ``checked`` modes of each pose are checked (module docstring). ``factor``: F^-1 (P, n, n)
    with F^-1 M F^-T = I when the caller knows a cheaper one (``CraigBamptonPlan.mass_factor``);
    by default the inverse of M's Cholesky factor."""
    if factor is None:
        try:
            factor = np.linalg.inv(np.linalg.cholesky(M))
        except np.linalg.LinAlgError:
            raise NumericalError("a reduced mass matrix of the sweep is not positive "
                                 "definite") from None
    Li = factor  # L^-1
    A = Li @ K @ Li.transpose(0, 2, 1)
    finite = np.isfinite(A).all(axis=(1, 2))
    if not finite.all():  # checked before LAPACK, whose LinAlgError on them would name no pose
        raise _fail(not_finite_message(), ~finite)
    vals, V = np.linalg.eigh((A + A.transpose(0, 2, 1)) / 2)
    X = Li.transpose(0, 2, 1) @ V
    diagonal = np.einsum("pii->pi", K) / np.einsum("pii->pi", M)
    lambda_max = diagonal.max(axis=1)
    zero = np.maximum(ZERO_TOL * lambda_ref, roundoff_floor(lambda_max))
    negative = vals[:, 0] < -zero
    if negative.any():
        raise _fail(negative_message(vals[:, 0].min()), negative)
    k = min(checked, vals.shape[1])
    x, lam = X[:, :, :k], vals[:, :k]
    KX, MX = K @ x, M @ x
    backward = backward_errors(KX, MX, x, lam, np.abs(K).sum(axis=1).max(axis=1),
                               np.abs(M).sum(axis=1).max(axis=1))
    if backward.max() > BACKWARD_TOL:
        raise _fail(f"eigen backward error {backward.max():.3g} exceeds {BACKWARD_TOL:g}",
                    backward.max(axis=1) > BACKWARD_TOL)
    ortho = np.abs(x.transpose(0, 2, 1) @ MX - np.eye(k)).max(axis=(1, 2))
    if ortho.max() > ORTHOGONALITY_TOL:
        raise _fail(orthogonality_message(ortho.max()), ortho > ORTHOGONALITY_TOL)
    unsure = (lam >= ZERO_TOL * lambda_ref[:, None]) & (lam < zero[:, None])
    if unsure.any():
        raise _fail("a mode lies below the round-off floor of this mesh (100 eps lambda_max), "
                    "so it cannot be told from a mechanism mode; use fewer elements per link",
                    unsure.any(axis=1))
    elastic = np.where(lam >= zero[:, None], lam, np.inf).min(axis=1)
    roundoff = np.finfo(float).eps * lambda_max / elastic
    if roundoff.max() > ROUNDOFF_WARN:
        log.warning("eigenvalues carry up to %.1g relative round-off (eps lambda_max / "
                    "lambda_1) at %d of %d poses", roundoff.max(),
                    int((roundoff > ROUNDOFF_WARN).sum()),
                    len(roundoff))
    return StackedModes(eigenvalues=vals, vectors=X, zero=zero)
