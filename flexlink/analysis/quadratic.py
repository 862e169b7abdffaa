"""The quadratic eigenproblem (s^2 M + s G + K) x = 0 of small vibrations about a steady motion.

M symmetric positive definite [kg], G skew (gyroscopic) [kg/s], K the effective stiffness [N/m]:
symmetric plus, with an angular acceleration, a skew circulatory part. A solution x e^{st} has
frequency Im(s) / (2 pi) [Hz] and growth rate Re(s) [1/s]; conservative systems (G skew, K
symmetric) have Re(s) = 0 while K is positive definite.

First-order form. With z = (x, y), y = s x, the pencil A z = s B z,
    A = [[0, I], [-K, -G]],  B = [[I, 0], [0, M]],
is solved for mu = 1/s, the largest eigenvalues of C = A^-1 B:
    C (x, y) = (-K^-1 (G x + M y), x),
the same spectral transformation as the symmetric solver's (``solve.py``): the lowest modes are
the largest mu, so ARPACK finds them first and they come out accurate to round-off. Only K is
factorised (once). Eigenvalues come in conjugate pairs; each mode is reported once, Im(s) >= 0.
Each (s, x) is checked by its normwise backward error
||(s^2 M + s G + K) x|| / ((|s|^2 ||M||_1 + |s| ||G||_1 + ||K||_1) ||x||).

Stability is reported, never hidden behind a frequency: a mode grows when Re(s) exceeds
GROWTH_TOL |s| (round-off of a neutral mode stays far below), and the symmetric part of K
losing positive definiteness (static divergence, buckling under the preload or centrifugal
softening) is reported with the number of its negative eigenvalues.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.sparse.csgraph import reverse_cuthill_mckee

from flexlink.errors import NumericalError

GROWTH_TOL = 1e-8  # Re(s) / |s| above which a mode is reported as growing
BACKWARD_TOL = 1e-10  # normwise backward error a mode must meet
DENSE_MAX = 250  # DOFs: dense LU up to here, sparse LU above (as eigensolver.AUTO_DENSE_MAX)
FULL_MAX = 24  # DOFs: below this the whole first-order pencil is solved densely
# Ritz residual ARPACK stops at, relative: a few ulps above its machine-precision default, which
# spends a restart more; the backward-error check and the Rayleigh refinement stay as they are
ARPACK_TOL = 1e-13


@dataclasses.dataclass(frozen=True)
class QuadraticModes:
    """Lowest modes by |s|: eigenvalues s (k,) complex [1/s], shapes (n, k) complex with
    x^H M x = 1, backward errors (k,), and the stiffness check: ``negative_stiffness`` is the
    number of negative eigenvalues of (K + K^T) / 2 (0: positive definite)."""

    eigenvalues: np.ndarray
    shapes: np.ndarray
    backward_errors: np.ndarray
    negative_stiffness: int

    @property
    def frequencies(self) -> np.ndarray:
        """[Hz]"""
        return np.abs(self.eigenvalues.imag) / (2 * math.pi)

    @property
    def growth_rates(self) -> np.ndarray:
        """Re(s) [1/s]; positive grows."""
        return self.eigenvalues.real

    @property
    def growing(self) -> np.ndarray:
        """Per mode: does it grow (Re(s) > GROWTH_TOL |s|)?"""
        return self.eigenvalues.real > GROWTH_TOL * np.abs(self.eigenvalues)

    @property
    def stable(self) -> bool:
        return self.negative_stiffness == 0 and not self.growing.any()


def _norm1(A) -> float:
    return float(abs(A).sum(axis=0).max()) if A.shape[0] else 0.0


def _factor(K):
    """A solve function for K (vector right-hand sides); NumericalError when K is singular."""
    if sp.issparse(K):
        try:
            lu = spla.splu(sp.csc_matrix(K))
        except RuntimeError as exc:
            raise NumericalError(f"the effective stiffness is singular ({exc}): the frame is a "
                                 "mechanism or sits exactly at a divergence speed") from None
        return lu.solve
    lu, piv = la.lu_factor(K, check_finite=True)
    pivots = np.abs(np.diagonal(lu))
    if pivots.min() <= np.finfo(float).eps * pivots.max():
        raise NumericalError("the effective stiffness is singular: the frame is a mechanism or "
                             "sits exactly at a divergence speed")
    getrs = la.get_lapack_funcs("getrs", (lu,))  # lu_solve without its per-call checks
    return lambda b: getrs(lu, piv, b)[0]


def negative_eigenvalues(K) -> int:
    """How many eigenvalues of the symmetric part of ``K`` are negative: 0 when its Cholesky
    factorisation exists (banded after a reverse Cuthill-McKee ordering, for sparse K), else
    counted from its eigenvalues."""
    Ks = (K + K.T) / 2
    try:
        if sp.issparse(Ks):
            Ks = sp.csr_matrix(Ks)
            perm = reverse_cuthill_mckee(Ks, symmetric_mode=True)
            B = Ks[perm][:, perm].tocoo()
            upper = B.col >= B.row
            width = int((B.col - B.row)[upper].max(initial=0))
            bands = np.zeros((width + 1, Ks.shape[0]))  # LAPACK upper band storage
            bands[width + B.row[upper] - B.col[upper], B.col[upper]] = B.data[upper]
            la.cholesky_banded(bands, lower=False)
        else:
            la.cholesky(Ks)
        return 0
    except la.LinAlgError:
        dense = Ks.toarray() if sp.issparse(Ks) else Ks
        return int((np.linalg.eigvalsh(dense) < 0).sum())


def _first_order_modes(M, G, K, k: int, start=None):
    """(s, x) of the k largest mu = 1/s of C, all of them for tiny problems; ``start``: a
    real start vector (2n,) for ARPACK, e.g. built from the static modes."""
    n = K.shape[0]
    if n <= DENSE_MAX:
        M, G, K = (A.toarray() if sp.issparse(A) else np.asarray(A) for A in (M, G, K))
    solve = _factor(K)
    GM = sp.hstack([G, M]).tocsr() if sp.issparse(K) else np.hstack([G, M])  # [G M] z = G x + M y
    if 2 * n <= FULL_MAX or k >= 2 * n - 1:
        C = np.zeros((2 * n, 2 * n))
        C[:n] = -np.column_stack([solve(col) for col in GM.T])
        C[n:, :n] = np.eye(n)
        mu, Z = la.eig(C)
        order = np.argsort(-np.abs(mu))[:k]
        return 1.0 / mu[order], Z[:n, order]
    C = spla.LinearOperator((2 * n, 2 * n), dtype=float,
                            matvec=lambda z: np.concatenate([-solve(GM @ z), z[:n]]))
    if start is None:
        start = np.random.default_rng(0).uniform(-1.0, 1.0, 2 * n)  # fixed: same bits every run
    try:
        mu, Z = spla.eigs(C, k=k, which="LM", v0=start, tol=ARPACK_TOL)
    except spla.ArpackNoConvergence as exc:
        # ARPACK can miss its own stopping test on exactly paired eigenvalues (G = 0) with every
        # wanted vector converged; those are kept (the backward-error check judges them)
        if len(exc.eigenvalues) < k:
            raise NumericalError(f"quadratic eigen solve failed: {exc}") from exc
        mu, Z = exc.eigenvalues, exc.eigenvectors
    except (RuntimeError, spla.ArpackError) as exc:
        raise NumericalError(f"quadratic eigen solve failed: {exc}") from exc
    return 1.0 / mu, Z[:n]


def _one_per_pair(s, X):
    """Each conjugate pair once, as its member with Im(s) >= 0, by |s|; real eigenvalues (a
    divergence: +-sigma) are kept apart, as two modes."""
    if not np.all(np.isfinite(s)):
        raise NumericalError("quadratic eigen solve returned NaN or infinite eigenvalues")
    flip = s.imag < 0
    s, X = np.where(flip, s.conj(), s), np.where(flip, X.conj(), X)
    # by |s|; within a tie (a divergence's +-sigma) the growing root first
    size = np.round(np.log(np.maximum(np.abs(s), np.finfo(float).tiny)) * 1e8)
    order = np.lexsort((-s.real, size))
    s, X = s[order], X[:, order]
    unit = X / np.linalg.norm(X, axis=0)
    keep = []
    for j in range(len(s)):  # drop the second member of a pair: same s, parallel vector
        if not any(abs(s[j] - s[i]) <= 1e-8 * abs(s[j]) and abs(np.vdot(unit[:, i], unit[:, j]))
                   > 1 - 1e-6 for i in keep):
            keep.append(j)
    return s[keep], X[:, keep]


def _refined(M, G, s, X, stiffness):
    """Each s as the root nearest it of a s^2 + b s + c = 0, a = x^H M x, b = x^H G x and
    c = ``stiffness(X)`` = x^H K x (per column) computed without K's round-off."""
    a, b = (np.einsum("ij,ij->j", X.conj(), A @ X) for A in (M, G))
    c = np.asarray(stiffness(X))
    root = np.sqrt(b * b - 4 * a * c)
    roots = np.stack([(-b + root) / (2 * a), (-b - root) / (2 * a)])
    return roots[np.argmin(np.abs(roots - s), axis=0), np.arange(len(s))]


def quadratic_modes(M, G, K, n_modes: int, guess=None, stiffness=None) -> QuadraticModes:
    """The lowest ``n_modes`` modes (by |s|) of (s^2 M + s G + K) x = 0, each conjugate pair
    once. M, G, K dense or sparse, reduced (no constrained DOFs), K non-singular. ``guess``:
    optional (shapes (n, j), angular frequencies (j,)) near the wanted modes, such as the static
    ones; the Krylov search starts from their sum (fewer iterations, same answer).
    ``stiffness``: optional X (n, k) -> x^H K x per column, free of the round-off of K's large
    entries (the strain energy from element deformations, ``fe.energy``); each s is then the
    root nearest it of its quadratic Rayleigh quotient with that stiffness, accurate to the
    square of the vector's error, as the symmetric solver's energy refinement. Raises
    NumericalError when K is singular or a mode fails its backward-error check."""
    n = K.shape[0]
    if n == 0:
        raise NumericalError("the model has no free DOFs: every DOF is constrained")
    k = min(2 * n_modes, 2 * n)  # both members of each pair
    start = None
    if guess is not None:  # z = (x, s x) of the modes, summed (real part and imaginary part)
        shapes, omega = guess
        start = np.concatenate([shapes.sum(axis=1), (shapes * omega).sum(axis=1)])
    while True:
        s, X = _one_per_pair(*_first_order_modes(M, G, K, k, start))
        if len(s) >= min(n_modes, n) or k >= 2 * n:
            break
        k = min(k + 2, 2 * n)  # a pair split at the end of the list: ask for one more pair
    s, X = s[:n_modes], X[:, :n_modes]
    X = X / np.sqrt(np.einsum("ij,ij->j", X.conj(), M @ X).real)
    # phase: largest component real and positive, so shapes compare across runs
    big = np.abs(X).argmax(axis=0)
    X = X * np.exp(-1j * np.angle(X[big, np.arange(X.shape[1])]))
    if stiffness is not None:
        s = _refined(M, G, s, X, stiffness)
    R = M @ X * s**2 + G @ X * s + K @ X
    scale = (np.abs(s) ** 2 * _norm1(M) + np.abs(s) * _norm1(G) + _norm1(K))
    backward = np.linalg.norm(R, axis=0) / (scale * np.linalg.norm(X, axis=0))
    if backward.max() > BACKWARD_TOL:
        raise NumericalError(f"quadratic eigen backward error {backward.max():.3g} exceeds "
                             f"{BACKWARD_TOL:g} (mode {int(backward.argmax()) + 1})")
    return QuadraticModes(eigenvalues=s, shapes=X, backward_errors=backward,
                          negative_stiffness=negative_eigenvalues(K))
