"""The public eigen solver against closed forms, and its refusals: a matrix with a negative
eigenvalue and a backward error above the tolerance must raise, never return modes."""

import math

import numpy as np
import pytest
import scipy.sparse as sp

from flexlink.analysis.eigensolver import EigenSolver
from flexlink.analysis.solve import solve_modes
from flexlink.errors import NumericalError


def chain(k=1.0e4, m=2.0):
    """Two masses m [kg] between three springs k [N/m] (both ends to ground): omega^2 = k/m
    (in phase) and 3 k/m (out of phase)."""
    K = k * np.array([[2.0, -1.0], [-1.0, 2.0]])
    return K, m * np.eye(2)


@pytest.mark.parametrize("method", ["dense", "sparse"])
def test_two_mass_chain_closed_form(method):
    K, M = chain()
    if method == "sparse":  # ARPACK needs k < n - 1: a longer chain, first two modes
        n = 12
        K = 1.0e4 * (2 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1))
        M = 2.0 * np.eye(n)
        # fixed-fixed chain of n masses: omega_j = 2 sqrt(k/m) sin(j pi / (2 (n + 1)))
        expected = [2 * math.sqrt(1.0e4 / 2.0) * math.sin(j * math.pi / (2 * (n + 1))) for j in (1, 2)]
        K, M = sp.csr_matrix(K), sp.csr_matrix(M)
    else:
        expected = [math.sqrt(1.0e4 / 2.0), math.sqrt(3 * 1.0e4 / 2.0)]
    result = solve_modes(K, M, 2, lambda_ref=1.0e3, solver=EigenSolver(method))
    np.testing.assert_allclose(2 * np.pi * result.frequencies, expected, rtol=1e-12)
    assert result.backward_errors.max() < 1e-12  # a 2-by-2 or banded solve: round-off level


def test_backward_error_above_tolerance_raises():
    """Round-off leaves a backward error near 1e-17, never 0: a tolerance of 1e-30 must fail."""
    K, M = chain()
    with pytest.raises(NumericalError, match="backward error"):
        solve_modes(K, M, 2, lambda_ref=1.0e3, solver=EigenSolver("dense"), backward_tol=1e-30)


@pytest.mark.parametrize("method", ["dense", "sparse"])
def test_negative_eigenvalue_raises(method):
    """K with eigenvalue -0.5 (indefinite, e.g. a negative spring): K + lambda_ref M is still
    positive definite, so the eigen solve itself succeeds and only the sign check can object."""
    n = 2 if method == "dense" else 12
    K = np.diag(np.linspace(1.0, 3.0, n))
    K[0, 0] = -0.5
    Kin = K if method == "dense" else sp.csr_matrix(K)
    Min = np.eye(n) if method == "dense" else sp.identity(n, format="csr")
    with pytest.raises(NumericalError, match="negative eigenvalue"):
        solve_modes(Kin, Min, 2, lambda_ref=1.0, solver=EigenSolver(method))

