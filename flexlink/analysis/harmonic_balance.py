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

Solved by scipy's GMRES on the full Hill matrix. q is real, so Q_-k = conj Q_k: the unknowns
are the harmonics k = 0..H (Q_0 real), a real vector space (GMRES in real arithmetic). The
product with the Hill matrix is done in the angle domain: q and q' are synthesised by real
FFTs on a grid of more than 2H + P angles, multiplied pointwise by the real S(theta) and
D(theta), and analysed back (exact: the product's harmonics up to H alias nowhere). It is
right preconditioned by LAPACK's band LU (double precision) of the Hill matrix with the
coefficients' harmonics cut to |d| <= band (exact at constant coefficients), over the
harmonics -band..H only: the rows below 0 stand in for the conjugate half. That LU is the
cost, about 2 (H + band) n ((band + 1) n)^2 complex operations (half the whole -H..H band's).

The band starts at BAND, enough where the coefficients vary gently over the turn (Table II
case 3: 5 to 8 GMRES steps). Where they vary fast, the cut coefficients misplace the frozen
frequencies (on the aluminium four-bar at |d| <= 4 by up to 200 %, at |d| <= 16 by 0.5 %), and
a lightly damped harmonic near them makes the cut Hill matrix a poor inverse: GMRES stagnates.
Then the band doubles, up to the coefficients' whole band P (the Hill matrix itself, but for
its rows below -P), and the band that served is kept for the larger H.

GMRES aims at a relative residual of RTOL; a solve is accepted on its estimated error, the
preconditioner applied to the residual (|P^-1 r| <= SOLVE_ERROR |Q|, P^-1 being near A^-1
where GMRES converges), not on the residual alone: where the basis holds vectors far stiffer
than those the response lies along, the residual of the answer rounded to double precision is
already above RTOL (on the aluminium four-bar at 300 rev/min and 36 harmonics a pivoted band
LU of the whole Hill matrix leaves 3e-9; GMRES stops at 1.8e-9, its error estimated at 9e-12).
A NaN fails the test.

H doubles from 2P until the estimate of the truncation error (``_tail``: the last harmonics
summed) is below the tolerance: a NumericalError if it is not by ``max_harmonics``.
"""

from __future__ import annotations

import dataclasses
import logging

import numpy as np
from scipy.fft import irfft, next_fast_len, rfft
from scipy.linalg import lapack
from scipy.sparse.linalg import LinearOperator, gmres

from flexlink.errors import NumericalError

log = logging.getLogger(__name__)

BAND = 4  # coefficient harmonics in the preconditioner: 5-8 GMRES steps on case 3 (3: 11-19)
MAX_HARMONICS = 400  # the largest H tried by default
ITERATIONS = 20  # GMRES iterations at most per band (case 3 takes 5 to 8 at BAND)
RTOL = 1e-12  # GMRES' relative residual
SOLVE_ERROR = 1e-8  # the largest estimated relative error of a solve: a tenth of the
# default tolerance


@dataclasses.dataclass(frozen=True)
class HarmonicSolution:
    """The periodic solution: coefficients (H + 1, n) complex, Q_k for k = 0..H (Q_-k =
    conj Q_k), in the units of q; error [-]: the estimated truncation error (the tail
    beyond H) relative to max over theta of |q(theta)| (Euclidean norm over the n
    coordinates); residual [-]: the final |g - A Q| / |g| (over harmonics k = 0..H)."""

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
    H, guess, band = max(2 * P, 8), None, min(BAND, P)
    while True:
        Q, residual, band = _solve(stiffness, damping, forcing, speed, H, guess, band)
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


def _solve(stiffness, damping, forcing, speed, H, guess, band):
    """Q (H + 1, n), k = 0..H, the relative residual and the preconditioner's band that
    reached it, by GMRES right preconditioned by the band LU of ``_band_preconditioner``
    over the real vector space of the real functions' harmonics k >= 0 (Q_0 real). From
    ``band`` the bands of ``_bands`` are tried in turn, the next where GMRES' answer is
    refused (NumericalError where it is with the last, the coefficients' whole band)."""
    P, n = stiffness.shape[0] - 1, stiffness.shape[-1]
    product = _hill_product(stiffness, damping, speed, H)
    rhs = np.zeros((H + 1, n), complex)
    m = min(P, H)
    rhs[:m + 1] = forcing[:m + 1]
    rhs[0] = rhs[0].real
    b = rhs.view(float).ravel()
    x0 = np.zeros_like(b) if guess is None else guess.view(float).ravel()
    bands = _bands(P, band)
    for band in bands:
        last = band == bands[-1]
        precondition = _band_preconditioner(stiffness, damping, speed, H, band)
        try:
            x, residual = _gmres(product, precondition, b, x0)
        except NumericalError as error:
            if last:
                raise
            log.info("%s with the band %d preconditioner at %d harmonics: band %d next",
                     error, band, H, bands[bands.index(band) + 1])
            continue
        return x.view(complex).reshape(H + 1, n), residual, band


def _bands(P: int, first: int) -> list[int]:
    """The coefficient harmonics kept in the preconditioner, in the order tried: ``first``,
    then doubling, up to all P (the preconditioner is then the Hill matrix but for its rows
    below k = -P)."""
    bands = [min(first, P)]
    while bands[-1] < P:
        bands.append(min(2 * bands[-1], P))
    return bands


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


def _band_preconditioner(stiffness, damping, speed, H, band):
    """The preconditioner: a function of the real view of harmonics k = 0..H giving the
    solution of the Hill matrix with coefficient harmonics |d| <= band over the harmonics
    -band..H (the conjugates of the right-hand side's below 0), kept for k = 0..H with Q_0
    made real; LAPACK's band LU (gbtrf, double precision), factored once, solved at every
    GMRES step. The rows below k = 0 stand for the conjugates of those above it, cut at
    -band: on case 3 no more GMRES steps than the whole band matrix over -H..H."""
    n = stiffness.shape[-1]
    low = min(band, H)
    gbtrf, gbtrs = lapack.get_lapack_funcs(("gbtrf", "gbtrs"), dtype=complex)
    ab, kl = _band_matrix(stiffness, damping, speed, np.arange(-low, H + 1), band)
    lu, pivots, info = gbtrf(ab, kl, kl, overwrite_ab=True)
    if info != 0:
        raise NumericalError(f"harmonic balance: the band {band} preconditioner is singular "
                             f"(zgbtrf info {info})")

    def precondition(x):
        r = x.view(complex).reshape(H + 1, n)
        y, _ = gbtrs(lu, kl, kl, np.concatenate([np.conj(r[low:0:-1]), r]).ravel(), pivots,
                     overwrite_b=True)
        Q = y.reshape(-1, n)[low:]
        Q[0] = Q[0].real
        return Q.view(float).ravel()
    return precondition


def _band_matrix(stiffness, damping, speed, harmonics, band):
    """The Hill matrix over ``harmonics`` (consecutive) with the coefficients' harmonics cut
    to |d| <= band, in LAPACK's band storage for gbtrf ((3 kl + 1, n len(harmonics)) complex,
    the first kl rows free for the LU's fill), and kl = ku."""
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
    ab = np.empty((3 * kl + 1, K * n), complex, order="F")
    for j in range(n):
        top = 2 * kl - band * n - j
        column = np.multiply.outer(D[j], rate)
        column += S[j][:, None]
        column[band * n + j] -= (speed * harmonics) ** 2
        ab[kl:top, j::n] = 0.0
        ab[top:top + column.shape[0], j::n] = column
        ab[top + column.shape[0]:, j::n] = 0.0
    for shift in range(1, band + 1):  # the blocks of rows beyond the first and last harmonics
        for j in range(n):
            top = 2 * kl - band * n - j
            ab[top + (band - shift) * n:top + (band - shift + 1) * n, j:shift * n:n] = 0.0
            ab[top + (band + shift) * n:top + (band + shift + 1) * n, (K - shift) * n + j::n] = 0.0
    return ab, kl


def _gmres(product, precondition, b, x0, rtol: float = RTOL, iterations: int = ITERATIONS):
    """x with |b - A x| <= rtol |b| and the relative residual reached, by scipy's GMRES
    right preconditioned (A P^-1 y = b - A x0, x = x0 + P^-1 y) in ``iterations`` steps at
    most. The residual r is recomputed from x, and the error of x estimated as |P^-1 r|
    (P^-1 near A^-1 where GMRES converges): NumericalError where that is above SOLVE_ERROR
    |x|, or not a number (an overflow)."""
    scale = np.linalg.norm(b)
    if scale == 0.0:  # no forcing: the periodic solution is rest
        return np.zeros_like(b), 0.0
    operator = LinearOperator((b.size, b.size), dtype=float,
                              matvec=lambda y: product(precondition(y)))
    steps = []  # one entry per GMRES iteration
    y, _ = gmres(operator, b - product(x0) if x0.any() else b, rtol=0.0,
                 atol=rtol * scale, restart=iterations, maxiter=1, callback=steps.append,
                 callback_type="pr_norm")
    x = x0 + precondition(y)
    r = b - product(x)
    residual = np.linalg.norm(r) / scale
    error = np.linalg.norm(precondition(r)) / np.linalg.norm(x)
    if not error <= SOLVE_ERROR:
        raise NumericalError(f"harmonic balance: GMRES stalled at relative residual "
                             f"{residual:.2g} after {len(steps)} iterations (estimated "
                             f"relative error {error:.2g})")
    log.debug("GMRES: relative residual %.2g after %d iterations, estimated relative error "
              "%.2g", residual, len(steps), error)
    return x, residual
