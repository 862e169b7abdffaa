"""The truncation correction of a Craig-Bampton sweep: the eigenvalues of the reduced pencils
with each link's truncated fixed-interface modes put back.

Eliminating the truncated coordinates exactly leaves the nonlinear eigenproblem
    (K - lambda M - lambda^2 G(lambda)) x = 0,   G(lambda) = sum_k c_k c_k^T / (k_k - lambda m_k)
on the kept ones (c_k: a truncated mode's mass coupling with its link's boundary DOFs; it has no
stiffness coupling). Per link, G is the series sum_j lambda^j F_j of 6 x 6 matrices
(``ReducedLink.flexibility``; the terms left out are below CUTOFF^(-2 SERIES) of the first).

In the basis of the reduced pencil's modes (x = X a, X^T M X = I, X^T K X = diag(w)) it reads
    (diag(w) - lambda I - lambda^2 X^T G(lambda) X) a = 0.
For each mode i asked for, from a = e_i: lambda from the Rayleigh functional of x (the root of
w(a) - lambda - lambda^2 x^T G(lambda) x / a^T a, Newton), then the other components of a from
the same equations at that lambda, a_j = lambda^2 (X^T G X a)_j / (w_j - lambda) (a_i = 1), and
the Rayleigh functional again, ``UPDATES`` times. The Rayleigh functional is stationary at the
exact vector, so its error is of second order in the error of x; each update shrinks that error
by about max_j |a_j| (below 1e-2 for the Table II cases at CUTOFF 3). The relative change of
lambda in the last update tells whether it converged: a close pair of modes (w_j near lambda) or
too small a basis shows there, and the sweep then solves the pose again on a larger basis.

Length scaling (``craig_bampton`` module docstring): with r = L / L_ref, F_j at length L is
D Gamma^j F_j,ref D, with D and Gamma diagonal on the link's boundary DOFs (Gamma = r^2 on the
axial ones, r^4 on the bending ones; F_j couples no axial with a bending DOF, so Gamma^j may
sit on one side), so all poses share each link's reference matrices and every product with
them is one matrix product per link over all poses and modes at once.
"""

from __future__ import annotations

import numpy as np

from flexlink.fe.craig_bampton import SERIES, CraigBamptonPlan

UPDATES = 2  # eigenvector updates (module docstring)
CONVERGED = 1e-8  # largest relative change of an eigenvalue in the last update accepted

_AXIAL = np.array([True, False, False, True, False, False])  # a link's boundary DOFs u, v, rz
_ROTATION = np.array([False, False, True, False, False, True])


def _boundary_rows(plan: CraigBamptonPlan, angles: np.ndarray, d: np.ndarray,
                   vectors: np.ndarray) -> np.ndarray:
    """D u for every reduced mode (P, 6 L, n): each link's boundary DOFs of each mode, turned
    into the link's frame and scaled by D (``d`` (L, 6, P)); grounded DOFs are 0."""
    columns = plan.boundary_columns.ravel()
    u = vectors[:, np.maximum(columns, 0)] * (columns >= 0)[:, None]
    u = u.reshape(len(u), -1, 6, u.shape[-1])  # (P, L, 6, n), global frame
    c = np.cos(angles)[:, :, None]
    s = np.sin(angles)[:, :, None]
    local = u.copy()
    for x in (0, 3):  # each end's u and v
        local[:, :, x] = c * u[:, :, x] + s * u[:, :, x + 1]
        local[:, :, x + 1] = c * u[:, :, x + 1] - s * u[:, :, x]
    return (local * d.transpose(2, 0, 1)[..., None]).reshape(len(u), -1, u.shape[-1])


def _horner(lam: np.ndarray, terms: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """sum_j lam^j terms_j and its derivative in lam; ``terms`` (SERIES, ...)."""
    value, slope = terms[-1], np.zeros_like(lam)
    for t in terms[-2::-1]:
        slope = slope * lam + value
        value = value * lam + t
    return value, slope


def _rayleigh_functional(rayleigh: np.ndarray, terms: np.ndarray, lam: np.ndarray,
                         iterations: int = 3) -> np.ndarray:
    """lambda [rad^2/s^2] (P, k) solving rayleigh - lambda - lambda^2 sum_j lambda^j terms_j = 0
    by Newton from ``lam``: ``rayleigh`` (P, k) = x^T K x / x^T M x, ``terms`` (SERIES, P, k)
    = u^T F_j u / x^T M x."""
    for _ in range(iterations):
        S, dS = _horner(lam, terms)
        lam = lam + (rayleigh - lam - lam**2 * S) / (1 + 2 * lam * S + lam**2 * dS)
    return lam


def corrected(plan: CraigBamptonPlan, angles: np.ndarray, lengths: np.ndarray,
              eigenvalues: np.ndarray, vectors: np.ndarray, pick: np.ndarray,
              updates: int = UPDATES) -> tuple[np.ndarray, np.ndarray]:
    """(eigenvalues [rad^2/s^2] (P, k) of the modes ``pick`` (P, k) with the truncated modes
    put back, the relative change of each in the last update (P, k); module docstring).

    ``angles`` [rad], ``lengths`` [m]: (P, links) as ``CraigBamptonPlan.stacked`` takes them;
    ``eigenvalues`` (P, n) and ``vectors`` (P, n, n): every mode of each reduced pencil, with
    X^T M X = I (``stacked.stacked_modes``)."""
    poses, n, _ = vectors.shape
    k, links = pick.shape[1], len(plan.links)
    r = np.asarray(lengths, dtype=float).T[:, None, :] / plan.reference_lengths[:, None, None]
    d = r * np.where(_ROTATION[:, None], r, 1.0) * np.where(_AXIAL[:, None], r**0.5, r**1.5)
    g_power = np.broadcast_to(  # Gamma^j, (L, SERIES, 6, P, k)
        np.where(_AXIAL[:, None], r**2, r**4)[:, None, :, :, None]
        ** np.arange(SERIES)[:, None, None, None], (links, SERIES, 6, poses, k)).copy()
    Xb = _boundary_rows(plan, angles, d, vectors)  # (P, 6 L, n): D u of every mode
    w = np.asarray(eigenvalues, dtype=float)[:, :, None]

    def functional(a, lam):
        """lambda of x = X a (Newton from ``lam``) and F_j,ref D u (L, SERIES, 6, P, k)."""
        u = np.ascontiguousarray((Xb @ a).transpose(1, 0, 2)).reshape(links, 6, poses, k)
        Fu = (plan.flexibility @ u.reshape(links, 6, -1)).reshape(links, SERIES, 6, poses, k)
        norm = (a * a).sum(axis=1)
        terms = np.einsum("ljapk,ljapk,lapk->jpk", Fu, g_power, u) / norm
        return _rayleigh_functional((a * a * w).sum(axis=1) / norm, terms, lam), Fu

    a = np.zeros((poses, n, k))
    np.put_along_axis(a, pick[:, None, :], 1.0, axis=1)
    lam, Fu = functional(a, np.take_along_axis(w[:, :, 0], pick, axis=1))
    change = np.zeros_like(lam)
    for _ in range(updates):
        # X^T G x: G x = D sum_j lambda^j Gamma^j F_j,ref D u in each link's frame
        lam_power = lam ** np.arange(SERIES)[:, None, None]
        Gx = np.einsum("ljapk,ljapk,jpk->lapk", Fu, g_power, lam_power)
        h = Xb.transpose(0, 2, 1) @ Gx.reshape(6 * links, poses, k).transpose(1, 0, 2)
        gap = w - lam[:, None, :]
        a = lam[:, None, :] ** 2 * h / np.where(gap == 0, 1.0, gap)
        np.put_along_axis(a, pick[:, None, :], 1.0, axis=1)
        before = lam
        lam, Fu = functional(a, lam)
        change = np.abs(lam - before) / np.abs(lam)
    return lam, change
