"""The quadratic eigen solver against closed forms: uncoupled gyroscopic pairs (each a 2-DOF
rotor whose roots solve a biquadratic), in every solver path (whole pencil, dense Arnoldi,
sparse Arnoldi), and the inertia count of the stiffness."""

import numpy as np
import pytest
import scipy.sparse as sp

from flexlink.analysis.quadratic import FULL_MAX, DENSE_MAX, negative_eigenvalues, quadratic_modes


def gyroscopic_pairs(k1, k2, g):
    """Block-diagonal M = I, K = diag(k1_i, k2_i), G = g_i [[0, -1], [1, 0]] per block, and the
    exact roots: s^2 = -(k1 + k2 + g^2) / 2 +- sqrt((k1 + k2 + g^2)^2 / 4 - k1 k2)."""
    n = 2 * len(k1)
    K = sp.diags(np.ravel(np.column_stack([k1, k2])))
    rows = np.ravel(np.column_stack([2 * np.arange(len(k1)), 2 * np.arange(len(k1)) + 1]))
    cols = np.ravel(np.column_stack([2 * np.arange(len(k1)) + 1, 2 * np.arange(len(k1))]))
    G = sp.csr_matrix((np.ravel(np.column_stack([-g, g])), (rows, cols)), shape=(n, n))
    b = k1 + k2 + g * g
    disc = np.sqrt(b * b / 4 - k1 * k2 + 0j)
    s2 = np.concatenate([-b / 2 + disc, -b / 2 - disc])
    roots = np.sqrt(s2 + 0j)
    return sp.identity(n, format="csr"), G, K.tocsr(), np.sort(np.abs(roots.imag))


@pytest.mark.parametrize("blocks", [FULL_MAX // 4 - 1, 20, DENSE_MAX // 2 + 10],
                         ids=["whole pencil", "dense Arnoldi", "sparse Arnoldi"])
def test_gyroscopic_pairs_match_the_biquadratic(blocks):
    rng = np.random.default_rng(3)
    k1, k2 = rng.uniform(50, 5000, blocks), rng.uniform(50, 5000, blocks)
    g = rng.uniform(0, 40, blocks)
    M, G, K, exact = gyroscopic_pairs(k1, k2, g)
    modes = quadratic_modes(M, G, K, 6)
    # conservative gyroscopic system: purely imaginary roots, to round-off
    np.testing.assert_allclose(np.abs(modes.eigenvalues.imag), exact[:6], rtol=1e-12)
    assert np.all(np.abs(modes.growth_rates) < 1e-10 * np.abs(modes.eigenvalues))
    assert modes.stable and modes.backward_errors.max() < 1e-13


def test_divergence_is_a_real_pair():
    # k1 < 0 without enough gyroscopic stiffening: s^2 has a positive root
    M, G, K, _ = gyroscopic_pairs(np.array([-100.0, 400.0]), np.array([900.0, 1600.0]),
                                  np.array([1.0, 0.0]))
    modes = quadratic_modes(M, G, K, 4)
    b = -100 + 900 + 1.0
    sigma = np.sqrt(-b / 2 + np.sqrt(b * b / 4 + 100 * 900))  # the real root, exact
    real = modes.eigenvalues[np.abs(modes.eigenvalues.imag) < 1e-12 * np.abs(modes.eigenvalues)]
    np.testing.assert_allclose(np.sort(real.real), [-sigma, sigma], rtol=1e-12)
    assert modes.growth_rates[0] > 0  # the growing root is listed first of its pair
    assert modes.negative_stiffness == 1 and not modes.stable


def test_negative_eigenvalue_count_sparse_and_dense():
    rng = np.random.default_rng(5)
    n = 300
    off = rng.uniform(-1, 1, n - 1)
    A = sp.diags([off, rng.uniform(1, 3, n), off], [-1, 0, 1]).tocsr()
    A = A - sp.diags(np.where(np.arange(n) % 37 == 0, 6.0, 0.0))  # a few negative directions
    expected = int((np.linalg.eigvalsh(A.toarray()) < 0).sum())
    assert expected > 0
    assert negative_eigenvalues(A) == expected
    assert negative_eigenvalues(A.toarray()) == expected
    assert negative_eigenvalues(sp.identity(n, format="csr")) == 0
    # only the symmetric part counts: a skew part (the circulatory term) changes nothing
    skew = sp.diags([np.ones(n - 1), -np.ones(n - 1)], [-1, 1])
    assert negative_eigenvalues(A + 5 * skew) == expected
