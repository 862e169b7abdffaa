"""One reduced basis for every pose of a turn, checked against each pose's own modes.

Given a frame's stiffness and mass at P poses in coordinates that keep their meaning over the
turn (``K``, ``M``: (P, n, n)), the basis is built as the cycle map's Craig-Bampton basis is
judged, by what it reproduces:

1. snapshots: the lowest ``n_modes`` modes of every other pose (0, 2, 4, ...), mass normalised;
2. their proper orthogonal decomposition in the reference pose's mass inner product (SVD of
   L^T X with M_0 = L L^T): the leading ``size`` left singular vectors span the basis;
3. rotated to the reference pose's Ritz vectors (K_0 diagonal, ascending), mass normalised;
4. checked: at every pose, sampled or not, the lowest ``n_modes`` Ritz frequencies in the basis
   against the pose's own, as the largest relative excess (Ritz values are upper bounds).

With ``size`` None the basis grows from ``n_modes`` until the check holds to ``tolerance``.
The poses between the snapshots are what makes the check a check: at a snapshot pose a wide
enough basis holds the pose's modes exactly.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import scipy.linalg as sla

from flexlink.errors import InputError, NumericalError

DEFAULT_TOLERANCE = 1e-3  # relative frequency excess; shifts a tongue by 0.1 % of its speed


@dataclasses.dataclass(frozen=True)
class PoseBasis:
    """vectors (n, size): M_0-orthonormal, K_0-orthogonal, in ascending Ritz frequency;
    frequencies (size,): their Ritz frequencies at the reference pose [Hz]; exact, ritz
    (P, n_modes): each pose's lowest frequencies, full model and basis [Hz]; snapshot_poses:
    the poses whose modes were taken; tolerance: the relative excess asked for."""

    vectors: np.ndarray
    frequencies: np.ndarray
    exact: np.ndarray
    ritz: np.ndarray
    snapshot_poses: np.ndarray
    tolerance: float

    @property
    def size(self) -> int:
        return self.vectors.shape[1]

    @property
    def error(self) -> float:
        """max over poses and the lowest modes of (f_basis - f_full) / f_full [-]."""
        return float(np.max(np.abs(self.ritz - self.exact) / self.exact))

    @property
    def checked(self) -> bool:
        return self.error <= self.tolerance


def lowest_modes(K: np.ndarray, M: np.ndarray, count: int) -> tuple[np.ndarray, np.ndarray]:
    """(eigenvalues (P, count) [rad^2/s^2], shapes (P, n, count), mass normalised) of each
    pose's K, M; NumericalError when a pose has a zero or negative eigenvalue (a mechanism
    or a lost constraint there)."""
    values = np.empty((K.shape[0], count))
    shapes = np.empty((K.shape[0], K.shape[1], count))
    for p in range(K.shape[0]):
        values[p], shapes[p] = sla.eigh(K[p], M[p], subset_by_index=[0, count - 1])
    scale = np.abs(values).max()
    if np.any(values[:, 0] <= 1e-9 * scale):
        p = int(np.argmin(values[:, 0]))
        raise NumericalError(f"pose {p} of the turn has a zero or negative stiffness "
                             f"eigenvalue ({values[p, 0]:.3g} (rad/s)^2): a mechanism mode or "
                             "a toggle pose; the turn has no reduced basis there")
    return values, shapes


def pose_basis(K: np.ndarray, M: np.ndarray, n_modes: int, size: int | None = None,
               tolerance: float = DEFAULT_TOLERANCE, reference: int = 0) -> PoseBasis:
    """The basis of the module docstring from K, M (P, n, n), pose ``reference`` the one whose
    Ritz vectors it is given in; ``size`` None: the smallest that passes the check (or every
    snapshot direction, unchecked, when none does)."""
    if n_modes < 1:
        raise InputError(f"n_modes must be at least 1, got {n_modes}")
    values, shapes = lowest_modes(K, M, n_modes)
    exact = np.sqrt(values) / (2.0 * np.pi)
    snapshots = np.arange(0, K.shape[0], 2)
    L = np.linalg.cholesky(M[reference])
    X = np.concatenate(shapes[snapshots], axis=1)
    U, s, _ = np.linalg.svd(L.T @ X, full_matrices=False)
    U = U[:, s > s[0] * 1e-10]  # directions round-off made
    directions = sla.solve_triangular(L.T, U, lower=False)  # M_0-orthonormal
    if size is not None and not n_modes <= size <= directions.shape[1]:
        raise InputError(f"basis size {size} is outside [{n_modes}, {directions.shape[1]}] "
                         "(the lowest modes to check, the snapshot directions)",
                         field="--basis", expected=f"an integer in [{n_modes}, "
                                                   f"{directions.shape[1]}]")
    Kd = directions.T @ K @ directions
    Md = directions.T @ M @ directions
    candidates = [size] if size is not None else range(n_modes, directions.shape[1] + 1)
    for r in candidates:
        ritz = _ritz_frequencies(Kd[:, :r, :r], Md[:, :r, :r], n_modes)
        if np.max(np.abs(ritz - exact) / exact) <= tolerance:
            break
    vectors, frequencies = _reference_ritz(directions[:, :r], K[reference])
    return PoseBasis(vectors=vectors, frequencies=frequencies, exact=exact, ritz=ritz,
                     snapshot_poses=snapshots, tolerance=tolerance)


def _ritz_frequencies(Kr: np.ndarray, Mr: np.ndarray, count: int) -> np.ndarray:
    """The lowest ``count`` frequencies [Hz] of each (P, r, r) pencil."""
    L = np.linalg.cholesky(Mr)
    Linv = np.linalg.inv(L)
    values = np.linalg.eigvalsh(Linv @ Kr @ np.swapaxes(Linv, -1, -2))[:, :count]
    return np.sqrt(np.clip(values, 0.0, None)) / (2.0 * np.pi)


def _reference_ritz(V: np.ndarray, K0: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """V (M_0-orthonormal) turned to the reference pose's Ritz vectors, and their [Hz]. The
    Ritz values are at least K_0's lowest eigenvalue, which ``lowest_modes`` has required to be
    positive, so their square roots are real."""
    values, Q = np.linalg.eigh(V.T @ K0 @ V)
    return V @ Q, np.sqrt(values) / (2.0 * np.pi)
