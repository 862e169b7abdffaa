"""The periodic solution of a damped, forced linear system with periodic coefficients, by
harmonic balance.

In the crank angle theta = Omega t (d/dt = Omega d/dtheta, ' = d/dtheta) the system reads

    Omega^2 q'' + Omega D(theta) q' + S(theta) q = g(theta),

D [1/s], S [1/s^2] (n, n) and g (n,) [q/s^2] trigonometric polynomials of degree P, given by
their Fourier coefficients c_d, d = 0..P (c_-d = conj c_d: the functions are real). With
q = sum_{|k| <= H} Q_k exp(i k theta) each harmonic balances:

    -(Omega k)^2 Q_k + sum_d [S_d + i Omega (k - d) D_d] Q_{k-d} = g_k,   |k| <= H.

Why harmonic balance: the coefficients are exact trigonometric polynomials (sampled poses
interpolated by their Fourier series), so the solution is analytic in theta and the error
falls spectrally with H (faster than any power of 1/H, with plateaus where the crank harmonics
cross a lightly damped frozen frequency); H is set by how fast the coefficients and the
response vary over the turn, not by the stiffest frequency of the system over the speed, as
the steps of a time integration over the turn are (~ omega_max / Omega).

Solved by GMRES on the full Hill matrix, right preconditioned by the LU of the same matrix with
the coefficients' harmonics cut to |d| <= BAND (banded, exact at constant coefficients). The
product with the Hill matrix is done in the angle domain: q and q' are synthesised on a grid
of more than 2H + P angles, multiplied pointwise by S(theta) and D(theta), and analysed back
(exact: the product's harmonics up to H alias nowhere).

H doubles from 2P until the estimate of the truncation error (``_tail``: the last harmonics
summed) is below the tolerance: a NumericalError if it is not by ``max_harmonics``.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.fft import next_fast_len
from scipy.linalg import lapack

from flexlink.errors import NumericalError

BAND = 4  # coefficient harmonics in the preconditioner: 4-8 GMRES steps on case 3 (3: 11-19)
MAX_HARMONICS = 400  # the largest H tried by default
ITERATIONS = 100  # GMRES iterations at most per H (case 1 at 300 rev/min needs over 40)


@dataclasses.dataclass(frozen=True)
class HarmonicSolution:
    """The periodic solution: coefficients (H + 1, n) complex, Q_k for k = 0..H (Q_-k =
    conj Q_k), in the units of q; error [-]: the estimated truncation error (the tail
    beyond H) relative to max over theta of |q(theta)| (Euclidean norm over the n
    coordinates); residual [-]: GMRES' final |g - A Q| / |g|."""

    coefficients: np.ndarray
    error: float
    residual: float

    @property
    def harmonics(self) -> int:
        return self.coefficients.shape[0] - 1

    def at(self, theta, derivative: int = 0) -> np.ndarray:
        """d^j q / dtheta^j (m, n) at angles theta (m,) [rad], j = ``derivative``."""
        k = np.arange(self.harmonics + 1)
        weights = np.full(k.shape, 2.0)
        weights[0] = 1.0
        scaled = (weights * (1j * k) ** derivative)[:, None] * self.coefficients
        return (np.exp(1j * np.outer(np.asarray(theta, dtype=float), k)) @ scaled).real


def fourier_coefficients(samples: np.ndarray) -> np.ndarray:
    """c_d, d = 0..P ((P + 1, ...) complex) of the trigonometric polynomial through samples
    (N, ...) at N = 2P + 1 equal steps from angle 0."""
    N = samples.shape[0]
    if N % 2 == 0:
        raise ValueError(f"an odd count of samples is needed, got {N}")
    return np.fft.rfft(samples, axis=0) / N


def harmonic_balance(stiffness: np.ndarray, damping: np.ndarray, forcing: np.ndarray,
                     speed: float, tolerance: float = 1e-7,
                     max_harmonics: int = MAX_HARMONICS) -> HarmonicSolution:
    """The periodic q(theta) of Omega^2 q'' + Omega D q' + S q = g (module docstring).

    stiffness, damping: (P + 1, n, n) Fourier coefficients of S [1/s^2] and D [1/s]; forcing:
    (P + 1, n) of g; speed: Omega [rad/s] > 0; tolerance: the error estimate to reach [-].
    NumericalError if it is not reached by ``max_harmonics`` harmonics, or if GMRES stalls."""
    P, n = stiffness.shape[0] - 1, stiffness.shape[-1]
    if damping.shape != stiffness.shape or forcing.shape != (P + 1, n):
        raise ValueError(f"damping {damping.shape} and forcing {forcing.shape} must match "
                         f"stiffness {stiffness.shape}")
    H, guess = max(2 * P, 8), None
    while True:
        Q, residual = _solve(stiffness, damping, forcing, speed, H, guess)
        error = _tail(Q, P)
        if error <= tolerance:
            return HarmonicSolution(coefficients=Q[H:], error=error, residual=residual)
        if H >= max_harmonics:
            raise NumericalError(
                f"harmonic balance: the estimated error {error:.2g} is above {tolerance:.2g} "
                f"at {H} harmonics (the cap): the response is not smooth enough over the turn")
        # doubling (quadrupling when 1e4 times too large: one doubling gained 1 to 2 orders
        # on case 3 from 600 to 2000 rev/min): the spectrum's plateaus (frozen-frequency bands of the stiff
        # directions) make a fitted decay a poor guess, and the last solve costs as much as
        # all before it
        H_next = min(max_harmonics, (4 if error > 1e4 * tolerance else 2) * H)
        guess = np.zeros((2 * H_next + 1, n), complex)
        guess[H_next - H:H_next + H + 1] = Q
        H = H_next


def _tail(Q: np.ndarray, P: int) -> float:
    """The error estimate of Q (2H + 1, n), k = -H..H: twice the sum of |Q_k| + |Q_-k| over
    the last max(P, H / 8) harmonics (at most a quarter), relative to the largest |q(theta)|
    over the turn. The harmonics beyond H are coupled to those kept through the P harmonics
    of the coefficients; where the spectrum falls, those missing sum to no more than the last
    ones kept, and pollute the kept ones by as much again. Measured against solves with many
    more harmonics (case 3 at 600 and 2000 rev/min, H = 36 to 150; case 1 at 300 to 3000
    rev/min): 1.9 to 3e3 times the true error, never below it; not a proof (a stiff,
    lightly damped mode whose frozen frequency band holds harmonic H can hide a rise)."""
    H = Q.shape[0] // 2
    size = np.linalg.norm(Q, axis=1)
    size = size[H:] + size[H::-1]  # |Q_k| + |Q_-k|, k = 0..H
    window = max(min(H // 4, max(P, H // 8)), 1)
    peak = np.linalg.norm(_synthesis(Q, 2 * H + 1).real, axis=1).max()
    return 2.0 * size[H - window + 1:].sum() / peak if peak > 0.0 else 0.0


def _solve(stiffness, damping, forcing, speed, H, guess):
    """Q (2H + 1, n), k = -H..H, and the relative residual, by preconditioned GMRES."""
    P, n = stiffness.shape[0] - 1, stiffness.shape[-1]
    k = np.arange(-H, H + 1)
    M = next_fast_len(2 * H + P + 1)
    S, D = (_on_grid(c, M).astype(complex) for c in (stiffness, damping))  # cast once
    dynamic = (speed * k) ** 2

    def product(x):
        Q = x.reshape(2 * H + 1, n)
        q = _synthesis(Q, M)
        dq = _synthesis(1j * speed * k[:, None] * Q, M)
        y = (S @ q[..., None] + D @ dq[..., None])[..., 0]
        return (_analysis(y, H) - dynamic[:, None] * Q).ravel()

    lu, pivots, kl = _band_lu(stiffness, damping, speed, H, min(BAND, P))

    def precondition(r):
        x, info = lapack.zgbtrs(lu, kl, kl, r, pivots)
        return x

    rhs = np.zeros((2 * H + 1, n), complex)
    m = min(P, H)
    rhs[H:H + m + 1] = forcing[:m + 1]
    rhs[H - m:H] = np.conj(forcing[m:0:-1])
    x0 = precondition(rhs.ravel()) if guess is None else guess.ravel()
    x, residual = _gmres(product, precondition, rhs.ravel(), x0)
    return x.reshape(2 * H + 1, n), residual


def _on_grid(coefficients, M):
    """Values (M, ...) at theta_j = 2 pi j / M of the real trigonometric polynomial."""
    padded = np.zeros((M // 2 + 1,) + coefficients.shape[1:], complex)
    padded[:coefficients.shape[0]] = coefficients
    return np.fft.irfft(padded * M, n=M, axis=0)


def _synthesis(Q, M):
    """sum_k Q_k exp(i k theta_j) (M, n) complex at theta_j = 2 pi j / M."""
    H = Q.shape[0] // 2
    padded = np.zeros((M,) + Q.shape[1:], complex)
    padded[:H + 1], padded[M - H:] = Q[H:], Q[:H]
    return np.fft.ifft(padded, axis=0) * M


def _analysis(y, H):
    """Harmonics -H..H (2H + 1, n) of samples y (M, n) at M equal angles."""
    c = np.fft.fft(y, axis=0) / y.shape[0]
    return np.concatenate([c[-H:], c[:H + 1]])


def _band_lu(stiffness, damping, speed, H, band):
    """LU (LAPACK zgbtrf) of the Hill matrix with coefficient harmonics |d| <= band: the
    preconditioner. Returns (lu, pivots, kl)."""
    n = stiffness.shape[-1]
    K = 2 * H + 1
    kl = n * (band + 1) - 1
    ab = np.zeros((3 * kl + 1, K * n), complex)
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    k = np.arange(-H, H + 1)
    for d in range(-band, band + 1):
        S_d = stiffness[d] if d >= 0 else np.conj(stiffness[-d])
        D_d = damping[d] if d >= 0 else np.conj(damping[-d])
        rows = np.arange(max(0, d), min(K, K + d))  # harmonic index a; column b = a - d
        cols = rows - d
        block = S_d[None] + 1j * speed * k[cols][:, None, None] * D_d[None]
        if d == 0:
            block = block - ((speed * k[rows]) ** 2)[:, None, None] * np.eye(n)
        # A[r, c] sits at ab[2 kl + r - c, c]
        ab[2 * kl + d * n + i - j, cols[:, None, None] * n + j] = block
    lu, pivots, info = lapack.zgbtrf(ab, kl, kl)
    if info != 0:
        raise NumericalError("harmonic balance: the banded preconditioner is singular "
                             f"(zgbtrf info {info})")
    return lu, pivots, kl


def _gmres(product, precondition, b, x0, rtol: float = 1e-12, iterations: int = ITERATIONS):
    """x with |b - A x| <= rtol |b| by GMRES right preconditioned (A P^-1 y = r, x = x0 +
    P^-1 y), and the relative residual reached. NumericalError if it stalls above 1e3 rtol."""
    scale = np.linalg.norm(b)
    if scale == 0.0:  # no forcing: the periodic solution is rest
        return np.zeros_like(b), 0.0
    r = b - product(x0)
    beta = np.linalg.norm(r)
    if beta <= rtol * scale:
        return x0, beta / scale
    V = np.empty((iterations + 1, b.size), complex)
    Z = np.empty((iterations, b.size), complex)
    h = np.zeros((iterations + 1, iterations), complex)
    V[0] = r / beta
    e1 = np.zeros(iterations + 1, complex)
    e1[0] = beta
    for m in range(iterations):
        Z[m] = precondition(V[m])
        w = product(Z[m])
        for _ in range(2):  # classical Gram-Schmidt twice: orthogonal to round-off
            c = V[:m + 1].conj() @ w
            h[:m + 1, m] += c
            w = w - c @ V[:m + 1]
        h[m + 1, m] = np.linalg.norm(w)
        y, *_ = np.linalg.lstsq(h[:m + 2, :m + 1], e1[:m + 2], rcond=None)
        residual = np.linalg.norm(h[:m + 2, :m + 1] @ y - e1[:m + 2]) / scale
        if residual <= rtol or h[m + 1, m] == 0.0:
            break
        V[m + 1] = w / h[m + 1, m]
    if residual > 1e3 * rtol:
        raise NumericalError(f"harmonic balance: GMRES stalled at relative residual "
                             f"{residual:.2g} after {m + 1} iterations")
    return x0 + y @ Z[:m + 1], residual
