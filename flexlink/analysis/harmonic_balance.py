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

Solved by GMRES on the full Hill matrix. q is real, so Q_-k = conj Q_k: the unknowns are the
harmonics k = 0..H (Q_0 real), a real vector space (GMRES with real coefficients and the inner
product that counts each k > 0 twice, so norms are those of all 2H + 1 harmonics). The
product with the Hill matrix is done in the angle domain: q and q' are synthesised by real FFTs
on a grid of more than 2H + P angles, multiplied pointwise by the real S(theta) and D(theta),
and analysed back (exact: the product's harmonics up to H alias nowhere). It is right
preconditioned by the banded LU of the Hill matrix with the coefficients' harmonics cut to
|d| <= BAND (exact at constant coefficients), over the harmonics -BAND..H only: the rows below
0 stand in for the conjugate half. That LU is the cost, about 2 (H + BAND) n ((BAND + 1) n)^2
complex operations (half the whole -H..H band's), and its solves read it whole at every GMRES
step; so it is done in single precision (half the time and memory), scaled into that range,
and in double only if GMRES stalls with it. GMRES, in double, corrects the preconditioner's
round-off: its residual is that of the double-precision product, whatever the preconditioner.

H doubles from 2P until the estimate of the truncation error (``_tail``: the last harmonics
summed) is below the tolerance: a NumericalError if it is not by ``max_harmonics``.
"""

from __future__ import annotations

import dataclasses
import logging

import numpy as np
from scipy.fft import irfft, next_fast_len, rfft
from scipy.linalg import lapack, solve_triangular

from flexlink.analysis.fourier import fourier_values
from flexlink.errors import NumericalError

log = logging.getLogger(__name__)

BAND = 4  # coefficient harmonics in the preconditioner: 5-8 GMRES steps on case 3 (3: 11-19)
MAX_HARMONICS = 400  # the largest H tried by default
ITERATIONS = 100  # GMRES iterations at most per H (case 1 at 300 rev/min needs over 40)
PRECISIONS = (np.complex64, np.complex128)  # of the preconditioner's LU, in the order tried


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
        return fourier_values(self.coefficients, np.ravel(theta), derivative)


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
            return HarmonicSolution(coefficients=Q, error=error, residual=residual)
        if H >= max_harmonics:
            raise NumericalError(
                f"harmonic balance: the estimated error {error:.2g} is above {tolerance:.2g} "
                f"at {H} harmonics (the cap): the response is not smooth enough over the turn")
        # doubling (quadrupling when 1e4 times too large: one doubling gained 1 to 2 orders
        # on case 3 from 600 to 2000 rev/min): the spectrum's plateaus (frozen-frequency bands of the stiff
        # directions) make a fitted decay a poor guess, and the last solve costs as much as
        # all before it
        H = min(max_harmonics, (4 if error > 1e4 * tolerance else 2) * H)
        guess = np.zeros((H + 1, n), complex)
        guess[:Q.shape[0]] = Q


def _tail(Q: np.ndarray, P: int) -> float:
    """The error estimate of Q (H + 1, n), k = 0..H: twice the sum of |Q_k| + |Q_-k| over
    the last max(P, H / 8) harmonics (at most a quarter), relative to the largest |q(theta)|
    over the turn. The harmonics beyond H are coupled to those kept through the P harmonics
    of the coefficients; where the spectrum falls, those missing sum to no more than the last
    ones kept, and pollute the kept ones by as much again. Measured against solves with many
    more harmonics (case 3 at 600 and 2000 rev/min, H = 36 to 150; case 1 at 300 to 3000
    rev/min): 1.9 to 3e3 times the true error, never below it; not a proof (a stiff,
    lightly damped mode whose frozen frequency band holds harmonic H can hide a rise)."""
    H = Q.shape[0] - 1
    size = 2.0 * np.linalg.norm(Q, axis=1)  # |Q_k| + |Q_-k|, k = 0..H
    window = max(min(H // 4, max(P, H // 8)), 1)
    peak = np.linalg.norm(_synthesis(Q, 2 * H + 1), axis=1).max()
    return 2.0 * size[H - window + 1:].sum() / peak if peak > 0.0 else 0.0


def _solve(stiffness, damping, forcing, speed, H, guess):
    """Q (H + 1, n), k = 0..H, and the relative residual, by preconditioned GMRES over the
    real vector space of the real functions' harmonics k >= 0 (Q_0 real). The preconditioner
    in single precision first (half the LU's work and memory; GMRES, in double, corrects
    it: its residual is the true one), in double if its LU is singular or GMRES stalls."""
    P, n = stiffness.shape[0] - 1, stiffness.shape[-1]
    weights = np.full((H + 1, n, 2), 2.0)  # |Q_-k| = |Q_k|: k > 0 counts twice
    weights[0] = 1.0
    product = _hill_product(stiffness, damping, speed, H)
    rhs = np.zeros((H + 1, n), complex)
    m = min(P, H)
    rhs[:m + 1] = forcing[:m + 1]
    rhs[0] = rhs[0].real
    b = rhs.view(float).ravel()
    for precision in PRECISIONS:
        try:
            precondition = _band_preconditioner(stiffness, damping, speed, H, min(BAND, P),
                                                precision)
            x0 = precondition(b) if guess is None else guess.view(float).ravel()
            x, residual = _gmres(product, precondition, b, x0, weights.ravel())
        except NumericalError as error:
            if precision is PRECISIONS[-1]:
                raise
            log.info("%s with the %s preconditioner at %d harmonics: again in %s", error,
                     np.dtype(precision).name, H, np.dtype(PRECISIONS[-1]).name)
            continue
        return x.view(complex).reshape(H + 1, n), residual


def _hill_product(stiffness, damping, speed, H):
    """The Hill matrix times harmonics k = 0..H (real view of (H + 1, n) complex), as a
    function of that vector. In the angle domain: q and q' synthesised by real FFTs on more
    than 2H + P angles, multiplied pointwise by the real S(theta) and D(theta), analysed
    back (exact: the product's harmonics up to H alias nowhere)."""
    P, n = stiffness.shape[0] - 1, stiffness.shape[-1]
    M = next_fast_len(2 * H + P + 1, real=True)
    coefficients = _synthesis(np.concatenate([stiffness, damping], axis=2), M)  # (M, n, 2n)
    k = np.arange(H + 1)
    rate = (1j * speed * k)[:, None]
    dynamic = ((speed * k) ** 2)[:, None]

    def product(x):
        Q = x.view(complex).reshape(H + 1, n)
        q = _synthesis(np.concatenate([Q, rate * Q], axis=1), M)  # q, q' (M, 2n)
        y = np.matmul(coefficients, q[..., None])[..., 0]
        return (rfft(y, axis=0)[:H + 1] / M - dynamic * Q).view(float).ravel()
    return product


def _synthesis(coefficients, M):
    """Values (M, ...) at theta_j = 2 pi j / M of the real trigonometric polynomials whose
    harmonics k = 0..H ((H + 1, ...), those of -k their conjugates) are given, M > 2H."""
    return irfft(coefficients, n=M, axis=0) * M


def _band_preconditioner(stiffness, damping, speed, H, band, precision):
    """The preconditioner: a function of the real view of harmonics k = 0..H giving the
    solution of the Hill matrix with coefficient harmonics |d| <= band over the harmonics
    -band..H (the conjugates of the right-hand side's below 0), kept for k = 0..H with Q_0
    made real; factored and solved in ``precision`` (a complex dtype). The rows below k = 0
    stand for the conjugates of those above it, cut at -band: on case 3 no more GMRES steps
    than the whole band matrix over -H..H."""
    n = stiffness.shape[-1]
    low = min(band, H)
    gbtrf, gbtrs = lapack.get_lapack_funcs(("gbtrf", "gbtrs"), dtype=precision)
    ab, kl, unit = _band_matrix(stiffness, damping, speed, np.arange(-low, H + 1), band,
                                precision)
    lu, pivots, info = gbtrf(ab, kl, kl, overwrite_ab=True)
    if info != 0:
        raise NumericalError("harmonic balance: the banded preconditioner is singular "
                             f"({gbtrf.typecode}gbtrf info {info})")

    def precondition(x):
        r = x.view(complex).reshape(H + 1, n)
        scale = _power_of_two(np.abs(x).max())  # r / scale in range, exactly
        rhs = (np.concatenate([np.conj(r[low:0:-1]), r]) / scale).astype(precision).ravel()
        y, _ = gbtrs(lu, kl, kl, rhs, pivots, overwrite_b=True)
        Q = y.reshape(-1, n)[low:].astype(complex) * (scale / unit)
        Q[0] = Q[0].real
        return Q.view(float).ravel()
    return precondition


def _power_of_two(size: float) -> float:
    """The power of two nearest above ``size`` > 0 (1 at 0): a scale that divides exactly."""
    return float(np.ldexp(1.0, int(np.frexp(size)[1])))


def _band_matrix(stiffness, damping, speed, harmonics, band, precision):
    """The Hill matrix over ``harmonics`` (consecutive) with the coefficients' harmonics cut
    to |d| <= band, in LAPACK's band storage for gbtrf ((3 kl + 1, n len(harmonics)), the
    first kl rows free for the LU's fill) in ``precision``, kl = ku, and the power of two
    ``unit`` it is divided by (its largest entry between 1/2 and 1: in single precision's
    range whatever the units). The diagonal is summed in double and rounded once: -(Omega
    k)^2 + S_0 cancels near a frozen frequency."""
    n = stiffness.shape[-1]
    K, kl = len(harmonics), n * (band + 1) - 1
    d = np.arange(-band, band + 1)
    S = np.where((d >= 0)[:, None, None], stiffness[np.abs(d)], np.conj(stiffness[np.abs(d)]))
    D = np.where((d >= 0)[:, None, None], damping[np.abs(d)], np.conj(damping[np.abs(d)]))
    # column j of block column b (harmonic k_b) holds A[b + d, b][:, j] = (S_d + i Omega k_b
    # D_d)[:, j], less (Omega k_b)^2 at row j of d = 0, stacked over d: rows t = (d + band) n
    # + i from r = (b - band) n, at ab[2 kl + r - c, c] (c = b n + j): one strided slice per
    # j; the n - 1 rows of the kl + ku + 1 beyond the blocks are zero, the first kl rows free
    S = S.reshape(-1, n).T.copy()  # (n, (2 band + 1) n): column j of the stacked blocks
    D = D.reshape(-1, n).T.copy()
    rate = 1j * speed * harmonics
    diagonal = S[:, band * n:(band + 1) * n].diagonal()[:, None] \
        + D[:, band * n:(band + 1) * n].diagonal()[:, None] * rate - (speed * harmonics) ** 2
    unit = _power_of_two(max(np.abs(diagonal).max(), np.abs(S).max()
                             + np.abs(D).max() * np.abs(rate).max()))
    diagonal = diagonal / unit
    S, D, rate = (S / unit).astype(precision), (D / unit).astype(precision), \
        rate.astype(precision)
    ab = np.empty((3 * kl + 1, K * n), precision, order="F")
    for j in range(n):
        top = 2 * kl - band * n - j
        column = np.multiply.outer(D[j], rate)
        column += S[j][:, None]
        column[band * n + j] = diagonal[j]  # summed in double, rounded once
        ab[kl:top, j::n] = 0.0
        ab[top:top + column.shape[0], j::n] = column
        ab[top + column.shape[0]:, j::n] = 0.0
    for shift in range(1, band + 1):  # the blocks of rows beyond the first and last harmonics
        for j in range(n):
            top = 2 * kl - band * n - j
            ab[top + (band - shift) * n:top + (band - shift + 1) * n, j:shift * n:n] = 0.0
            ab[top + (band + shift) * n:top + (band + shift + 1) * n, (K - shift) * n + j::n] = 0.0
    return ab, kl, unit


def _gmres(product, precondition, b, x0, weights, rtol: float = 1e-12,
           iterations: int = ITERATIONS):
    """x with |b - A x| <= rtol |b| by GMRES right preconditioned (A P^-1 y = r, x = x0 +
    P^-1 y), and the relative residual reached, over real vectors with the inner product
    sum(weights u v). NumericalError if it stalls above 1e3 rtol."""
    def norm(v):
        return np.sqrt(weights @ (v * v))
    scale = norm(b)
    if scale == 0.0:  # no forcing: the periodic solution is rest
        return np.zeros_like(b), 0.0
    r = b - product(x0)
    beta = norm(r)
    if beta <= rtol * scale:
        return x0, beta / scale
    # the Krylov vectors and their preconditioned images, grown as needed (a few steps are
    # usual: ITERATIONS rows up front cost the heap its reuse of the LU's memory)
    V, Z = np.empty((2, min(16, iterations + 1), b.size))
    R = np.zeros((iterations + 1, iterations))  # the Hessenberg matrix, Givens-rotated
    turns = np.zeros((iterations, 2))  # (cos, sin) of each rotation
    g = np.zeros(iterations + 1)  # beta e1 rotated alike: |g[m + 1]| / scale is the residual
    g[0] = beta
    V[0] = r / beta
    for m in range(iterations):
        Z[m] = precondition(V[m])
        w = product(Z[m])
        for _ in range(2):  # classical Gram-Schmidt twice: orthogonal to round-off
            c = V[:m + 1] @ (weights * w)
            R[:m + 1, m] += c
            w = w - c @ V[:m + 1]
        below = norm(w)
        for i, (cos, sin) in enumerate(turns[:m]):
            R[i, m], R[i + 1, m] = cos * R[i, m] + sin * R[i + 1, m], \
                cos * R[i + 1, m] - sin * R[i, m]
        rho = np.hypot(R[m, m], below)
        if not rho > 0.0:  # 0: A P^-1 V[m] in the span of V[:m], singular; NaN: overflow
            m -= 1
            break
        turns[m] = R[m, m] / rho, below / rho
        R[m, m] = rho
        g[m], g[m + 1] = turns[m, 0] * g[m], -turns[m, 1] * g[m]
        if abs(g[m + 1]) <= rtol * scale or below == 0.0:
            break
        if m + 1 == len(V):
            V, Z = (np.concatenate([X, np.empty_like(X)]) for X in (V, Z))
        V[m + 1] = w / below
    residual = abs(g[m + 1]) / scale
    if not residual <= 1e3 * rtol:  # NaN too (a preconditioner out of its precision's range)
        raise NumericalError(f"harmonic balance: GMRES stalled at relative residual "
                             f"{residual:.2g} after {m + 1} iterations")
    return x0 + solve_triangular(R[:m + 1, :m + 1], g[:m + 1]) @ Z[:m + 1], residual
