"""One reduced basis for a turn of poses, checked against each pose's own lowest modes."""
import numpy as np
import pytest
import scipy.linalg as sla

from flexlink.analysis.pose_basis import pose_basis
from flexlink.errors import InputError

POSES, N, MODES = 13, 24, 3


@pytest.fixture(scope="module")
def turn():
    """A chain of 24 unit masses whose springs stiffen and soften around the turn, each spring
    with its own phase: the low modes change shape from pose to pose (a fixed modal basis
    cannot follow them), smoothly in the crank angle."""
    rng = np.random.default_rng(7)
    base, depth, phase = rng.uniform(1.0, 2.0, N + 1), rng.uniform(0.3, 0.8, N + 1), \
        rng.uniform(0.0, 2 * np.pi, N + 1)
    theta = 2 * np.pi * np.arange(POSES) / POSES
    k = base * (1.0 + depth * np.cos(theta[:, None] + phase))  # (P, springs) [N/m]
    K = np.zeros((POSES, N, N))
    i = np.arange(N)
    K[:, i, i] = k[:, :-1] + k[:, 1:]
    K[:, i[:-1], i[:-1] + 1] = K[:, i[:-1] + 1, i[:-1]] = -k[:, 1:-1]
    M = np.broadcast_to(np.eye(N), K.shape).copy()
    return K, M


def frequencies(K, M, count):
    return np.sqrt(sla.eigh(K, M, eigvals_only=True, subset_by_index=[0, count - 1])) / (2 * np.pi)


def test_check_numbers_are_each_poses_own_and_the_basis_ones(turn):
    # the oracle: scipy's eigen solve of every pose, full and projected on the returned basis
    K, M = turn
    basis = pose_basis(K, M, MODES)
    V = basis.vectors
    for p in range(POSES):
        assert np.allclose(basis.exact[p], frequencies(K[p], M[p], MODES), rtol=1e-12)
        assert np.allclose(basis.ritz[p], frequencies(V.T @ K[p] @ V, V.T @ M[p] @ V, MODES),
                           rtol=1e-10)
    # Rayleigh-Ritz: a subspace only over-estimates (to round-off, 1e-12 relative)
    assert np.all(basis.ritz >= basis.exact * (1 - 1e-12))


def test_basis_is_the_reference_ritz_vectors(turn):
    K, M = turn
    basis = pose_basis(K, M, MODES)
    V = basis.vectors
    assert np.allclose(V.T @ M[0] @ V, np.eye(basis.size), atol=1e-12)
    assert np.allclose(V.T @ K[0] @ V, np.diag((2 * np.pi * basis.frequencies) ** 2),
                       atol=1e-10)
    assert np.all(np.diff(basis.frequencies) >= 0)


def test_the_smallest_basis_that_passes_is_chosen(turn):
    K, M = turn
    basis = pose_basis(K, M, MODES, tolerance=1e-3)
    assert basis.checked and basis.error <= 1e-3
    smaller = pose_basis(K, M, MODES, size=basis.size - 1)
    assert smaller.error > 1e-3
    # the poses between the snapshots are checked too: that is where the error is made
    between = np.setdiff1d(np.arange(POSES), basis.snapshot_poses)
    errors = np.abs(smaller.ritz - smaller.exact) / smaller.exact
    assert errors[between].max() > 1e-3


def test_the_reference_modes_alone_do_not_follow_the_turn(turn):
    # a basis of n directions cannot hold every pose's lowest n modes when they turn
    K, M = turn
    assert not pose_basis(K, M, MODES, size=MODES).checked


def test_a_size_outside_the_snapshots_is_refused(turn):
    K, M = turn
    with pytest.raises(InputError, match="basis size"):
        pose_basis(K, M, MODES, size=MODES - 1)
