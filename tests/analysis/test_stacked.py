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


def test_refusals_name_the_first_pose_and_count_them():
    K, M = pencils()
    bad = K.copy()
    bad[3, 0, 0] = np.nan  # one pose of five
    with pytest.raises(NumericalError, match=r"NaN.*at pose 3 of the sweep \(1 pose\(s\) in all\)"):
        stacked_modes(bad, M, np.ones(len(K)), checked=4)
    singular = M.copy()
    singular[1] = -np.eye(M.shape[1])  # not positive definite
    with pytest.raises(NumericalError, match="mass matrix of the sweep is not positive definite"):
        stacked_modes(K, singular, np.ones(len(K)), checked=4)


def test_a_given_mass_factor_gives_the_same_modes():
    # any F with F^-1 M F^-T = I will do: here the symmetric square root M^(1/2)
    K, M = pencils(poses=3, n=6)
    w, Q = np.linalg.eigh(M)
    inverse_root = Q @ (Q.transpose(0, 2, 1) / np.sqrt(w)[:, :, None])
    given = stacked_modes(K, M, np.ones(3), checked=6, factor=inverse_root)
    for p in range(3):
        # the eigenvalues of one pencil: round-off of a condition ~ 1e2 problem
        np.testing.assert_allclose(given.eigenvalues[p], la.eigh(K[p], M[p])[0], rtol=1e-12)
        X = given.vectors[p]
        np.testing.assert_allclose(X.T @ M[p] @ X, np.eye(6), atol=1e-12)


def test_a_mode_between_the_physical_and_round_off_zero_is_refused():
    # diagonal pencils: eigenvalues are the diagonal. lambda_max = 1e6, so the round-off floor
    # is 100 eps 1e6 ~ 2.2e-8; an eigenvalue of 1e-9 sits below it but above 1e-6 lambda_ref
    # when lambda_ref = 1e-6, so nobody can tell it from a mechanism
    K = np.stack([np.diag([1.0, 2.0, 1e6]), np.diag([1e-9, 1.0, 1e6]), np.diag([1.0, 2.0, 1e6])])
    M = np.stack([np.eye(3)] * 3)
    with pytest.raises(NumericalError, match=r"round-off floor.*at pose 1 .*\(1 pose"):
        stacked_modes(K, M, np.full(3, 1e-6), checked=3)
    # the same poses with lambda_ref = 1: 1e-9 is then below the physical threshold 1e-6, a
    # mechanism mode, counted
    modes = stacked_modes(K, M, np.ones(3), checked=3)
    np.testing.assert_array_equal(modes.mechanisms, [0, 1, 0])
    # zero per pose: the larger of the physical threshold and the round-off floor
    np.testing.assert_allclose(modes.zero, 1e-6, rtol=1e-15)


def test_round_off_warning_names_the_poses(caplog):
    # eps lambda_max / lambda_1 = 2.2e-16 * 1e12 / 1 ~ 2e-4 > 1e-6 at pose 1 only (its round-off
    # floor, 2.2e-2, stays below its lowest eigenvalue, 1)
    K = np.stack([np.diag([1.0, 2.0, 3.0]), np.diag([1.0, 2.0, 1e12])])
    M = np.stack([np.eye(3), np.eye(3)])
    with caplog.at_level("WARNING", logger="flexlink.analysis.stacked"):
        stacked_modes(K, M, np.array([1e-6, 1e-6]), checked=3)
    assert "at 1 of 2 poses" in caplog.text
