"""The stacked eigen solve of a Craig-Bampton sweep: the same modes as one LAPACK call per pose,
and the same refusals as a single solve."""

import numpy as np
import pytest
import scipy.linalg as la

from flexlink.analysis.stacked import stacked_modes
from flexlink.errors import NumericalError


def pencils(poses=5, n=12, seed=1):
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(poses, n, n))
    B = rng.normal(size=(poses, n, n))
    K = A @ A.transpose(0, 2, 1) + n * np.eye(n)
    M = B @ B.transpose(0, 2, 1) + n * np.eye(n)
    return K, M


def test_same_modes_as_one_solve_per_pose():
    K, M = pencils()
    modes = stacked_modes(K, M, lambda_ref=np.ones(len(K)), checked=K.shape[1])
    for p in range(len(K)):
        vals, vecs = la.eigh(K[p], M[p])
        # eigenvalues to round-off of the largest (the pencils have condition ~ 1e2)
        np.testing.assert_allclose(modes.eigenvalues[p], vals, rtol=1e-12, atol=1e-13 * vals[-1])
        X = modes.vectors[p]
        np.testing.assert_allclose(X.T @ M[p] @ X, np.eye(len(vals)), atol=1e-12)
        np.testing.assert_allclose(np.abs(X.T @ M[p] @ vecs), np.eye(len(vals)), atol=1e-8)
    assert not modes.mechanisms.any()


def test_mechanism_counted_and_negative_refused():
    K, M = pencils()
    x = np.ones(K.shape[1])
    P = np.eye(len(x)) - np.outer(x, x) / (x @ x)
    K0 = P @ K @ P  # x is now a zero mode of every pose
    assert (stacked_modes(K0, M, np.ones(len(K)), checked=4).mechanisms == 1).all()
    K0[2] -= 1e3 * np.outer(x, x)
    with pytest.raises(NumericalError, match="pose 2"):
        stacked_modes(K0, M, np.ones(len(K)), checked=4)
