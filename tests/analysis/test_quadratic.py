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


def test_stiffness_refinement_solves_the_quadratic_rayleigh_quotient():
    # Given x^H K x from elsewhere (here K's own form scaled by 1 + 1e-11, a stand-in for an
    # energy free of K's round-off), each s must be the root nearest it of
    # a s^2 + b s + c = 0 with a = x^H M x = 1, b = x^H G x, c = that stiffness: to round-off,
    # where the unrefined s misses c by 1e-11 relative.
    rng = np.random.default_rng(7)
    k1, k2, g = rng.uniform(50, 5000, 5), rng.uniform(50, 5000, 5), rng.uniform(1, 40, 5)
    M, G, K, exact = gyroscopic_pairs(k1, k2, g)

    def stiffness(X):
        return (1 + 1e-11) * np.einsum("ij,ij->j", X.conj(), K @ X)

    plain = quadratic_modes(M, G, K, 4)
    modes = quadratic_modes(M, G, K, 4, stiffness=stiffness)
    X, s = modes.shapes, modes.eigenvalues
    a = np.einsum("ij,ij->j", X.conj(), M @ X)
    b = np.einsum("ij,ij->j", X.conj(), G @ X)
    residual = np.abs(a * s**2 + b * s + stiffness(X)) / np.abs(stiffness(X))
    assert residual.max() < 1e-14
    # the nearest root: the refined s moved by about 1e-11 relative, not to the other root
    shift = np.abs(s - plain.eigenvalues) / np.abs(plain.eigenvalues)
    assert 1e-13 < shift.min() and shift.max() < 1e-10
    np.testing.assert_allclose(np.abs(s.imag), exact[:4], rtol=1e-10)


@pytest.mark.parametrize("n_modes", [1, 3, 5, 8])
def test_as_many_modes_as_asked_each_pair_once(n_modes):
    # four 2-DOF gyroscopic blocks: 8 DOFs, 8 modes with Im(s) > 0; asking for more gives all 8
    M, G, K, exact = gyroscopic_pairs(np.array([100.0, 400.0, 900.0, 1600.0]),
                                      np.array([150.0, 650.0, 1000.0, 2500.0]),
                                      np.array([3.0, 2.0, 5.0, 1.0]))
    modes = quadratic_modes(M.toarray(), G.toarray(), K.toarray(), n_modes)
    expected = exact[:min(n_modes, 8)]
    np.testing.assert_allclose(np.abs(modes.eigenvalues.imag), expected, rtol=1e-12)
    assert modes.shapes.shape == (8, len(expected))
    # mass-normalised shapes, x^H M x = 1 (to round-off)
    np.testing.assert_allclose(np.einsum("ij,ij->j", modes.shapes.conj(), modes.shapes).real,
                               1.0, rtol=1e-13)


def test_every_mode_of_a_pencil_beyond_the_whole_pencil_size():
    # 12 blocks, 24 DOFs: past FULL_MAX, yet asking for every mode needs the whole pencil
    # (ARPACK cannot return all eigenvalues of an operator)
    blocks = FULL_MAX // 2
    rng = np.random.default_rng(11)
    M, G, K, exact = gyroscopic_pairs(rng.uniform(50, 5000, blocks), rng.uniform(50, 5000, blocks),
                                      rng.uniform(0, 40, blocks))
    modes = quadratic_modes(M, G, K, 2 * blocks)
    np.testing.assert_allclose(np.abs(modes.eigenvalues.imag), exact, rtol=1e-11)


def test_backward_errors_and_phase_are_as_documented():
    # the normwise backward error recomputed from its definition, and each shape's largest
    # component real and positive (so shapes compare across runs)
    rng = np.random.default_rng(13)
    blocks = 20
    M, G, K, _ = gyroscopic_pairs(rng.uniform(50, 5000, blocks), rng.uniform(50, 5000, blocks),
                                  rng.uniform(0, 40, blocks))
    M = M @ sp.diags(rng.uniform(0.5, 2.0, 2 * blocks))  # unequal masses: ||M||_1 != 1
    modes = quadratic_modes(M, G, K, 5)
    s, X = modes.eigenvalues, modes.shapes
    norm1 = [np.abs(A.toarray()).sum(axis=0).max() for A in (M, G, K)]
    for j in range(len(s)):
        x = X[:, j]
        # the residual is round-off (~1e-16 relative): summed in the solver's order, so that
        # the two quotients agree to their own round-off
        r = (M @ x) * s[j] ** 2 + (G @ x) * s[j] + K @ x
        expected = np.linalg.norm(r) / ((abs(s[j]) ** 2 * norm1[0] + abs(s[j]) * norm1[1]
                                         + norm1[2]) * np.linalg.norm(x))
        assert modes.backward_errors[j] == pytest.approx(expected, rel=1e-9, abs=0)
        big = np.argmax(np.abs(x))
        assert x[big].real > 0 and abs(x[big].imag) <= 1e-14 * abs(x[big])
