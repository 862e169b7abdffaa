"""The eigen solver a caller passes in, as scikit-fem's ``solve(..., solver=...)``: which of
the dense (LAPACK) and sparse (ARPACK shift-invert) solvers takes a problem, chosen once at the
edge and handed down, never a method string threaded through the stages.

Both solve the lowest ``k`` eigenpairs of K v = lambda M v about a shift below zero, so that
K - shift M is positive definite even when K is singular (mechanism or rigid-body modes).
"""

from __future__ import annotations

import dataclasses
import enum

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from flexlink.choices import parse_choice
from flexlink.errors import NumericalError

# AUTO of a single solve: dense up to here. Measured with `flexlink converge` on case 1:
# dense 3.5 ms vs sparse 4.1 ms at 152 DOFs, 7.8 vs 5.2 ms at 296, 37 vs 7 ms at 584.
AUTO_DENSE_MAX = 250
DENSE_REFUSE = 20000  # DOFs; a dense solve would need > 3 GB and minutes: refused


class Method(enum.StrEnum):
    """DENSE or SPARSE; AUTO: dense up to the solver's ``dense_max`` DOFs, sparse above."""

    AUTO = "auto"
    DENSE = "dense"
    SPARSE = "sparse"


def _dense(K, M, k, shift):
    # The same spectral transformation as the sparse path, done densely: solve
    # M v = mu (K - shift M) v for the k largest mu, then lambda = shift + 1/mu. LAPACK's error is
    # about eps times the largest eigenvalue of the pencil it sees; here that is the lowest mode,
    # so the low modes come out accurate to round-off. Plain eigh(K, M) loses about
    # eps * lambda_max / lambda_1 (1e-7 relative on a 32-element four-bar).
    Kd = K.toarray() if sp.issparse(K) else np.asarray(K)
    Md = M.toarray() if sp.issparse(M) else np.asarray(M)
    n = Kd.shape[0]
    try:
        mu, vecs = la.eigh(Md, Kd - shift * Md, subset_by_index=[n - k, n - 1])
    except la.LinAlgError as exc:
        raise NumericalError(f"dense eigen solve failed: {exc}; K - shift M is not positive "
                             "definite (K indefinite?)") from exc
    order = np.argsort(-mu)
    return shift + 1.0 / mu[order], vecs[:, order]


def _sparse(K, M, k, shift):
    # Shift-invert about a negative shift: the modes nearest the shift from above are the
    # lowest ones, and the factorisation of K - shift M cannot break down.
    # ARPACK's own start vector is random anew at every call (scipy >= 1.16), which moves the
    # eigenvalues in their last bits from run to run; a fixed one makes every run, serial or on
    # any worker, give the same bits. Uniform in (-1, 1), as ARPACK draws its own.
    start = np.random.default_rng(0).uniform(-1.0, 1.0, K.shape[0])
    try:
        vals, vecs = spla.eigsh(sp.csc_matrix(K), k=k, M=sp.csc_matrix(M), sigma=shift,
                                which="LM", v0=start)
    except (RuntimeError, spla.ArpackError) as exc:
        raise NumericalError(f"sparse eigen solve failed: {exc}") from exc
    order = np.argsort(vals)
    return vals[order], vecs[:, order]


SOLVERS = {Method.DENSE: _dense, Method.SPARSE: _sparse}


@dataclasses.dataclass(frozen=True)
class EigenSolver:
    """Which solver takes a problem: ``method``; with AUTO, dense up to ``dense_max`` solved
    DOFs and sparse above. ``method`` may be given as its text (checked here: this is where a
    Python caller chooses)."""

    method: Method = Method.AUTO
    dense_max: int = AUTO_DENSE_MAX

    def __post_init__(self):
        object.__setattr__(self, "method", parse_choice(Method, self.method, "method"))

    def pick(self, n_solved: int, k: int) -> Method:
        """DENSE or SPARSE for the lowest ``k`` modes of a problem of ``n_solved`` DOFs."""
        method = self.method
        if method is Method.AUTO:
            method = Method.DENSE if n_solved <= self.dense_max or k >= n_solved - 1 else Method.SPARSE
        if method is Method.DENSE and n_solved > DENSE_REFUSE:
            raise NumericalError(f"dense solve refused for {n_solved} DOFs (limit {DENSE_REFUSE}): "
                                 f"it needs {8 * 2 * n_solved * n_solved / 1e9:.1f} GB; use "
                                 "method='sparse'")
        if method is Method.SPARSE and k >= n_solved - 1:
            method = Method.DENSE  # ARPACK needs k < n - 1
        return method

    def assembles_dense(self, n: int) -> bool:
        """Whether a model of ``n`` DOFs (constraints eliminated) is worth assembling straight
        into dense matrices: this solver may take it densely and it is small enough that
        scipy.sparse's bookkeeping would cost more than the solve."""
        return self.method is not Method.SPARSE and n <= self.dense_max


def lowest_pairs(method: Method, K, M, k: int, shift: float):
    """The lowest ``k`` eigenpairs of (K, M) by ``method`` (DENSE or SPARSE) about ``shift``
    [rad^2/s^2] (below zero): (eigenvalues ascending, vectors (n, k))."""
    return SOLVERS[method](K, M, k, shift)


DEFAULT_SOLVER = EigenSolver()  # AUTO: dense up to AUTO_DENSE_MAX DOFs, the single-pose optimum
