"""An adiabatic (interaction-picture) exponential integrator for the periodic equations of a
running linkage, whose expensive part does not depend on the crank speed.

With the crank angle theta as the independent variable the state x obeys

    dx/dtheta = (A0(theta) / Omega + A1(theta) + Omega A2(theta)) x,

A0 the speed-independent part (stiffness and modal damping), A1 the Coriolis part and A2 the
centrifugal and inertia part. Once per model, on a grid of crank angles, A0 = V Lambda V^-1 is
decomposed and tracked: the eigenvalues in a fixed order (A0 is real, every pair underdamped:
the half with positive imaginary part, sorted by it; a mode that loses its identity between
grid points is refused), the eigenvectors in a parallel-transport gauge (phases chosen so that
w_k^H v_{k+1} = w_{k+1}^H v_k between neighbours, a midpoint rule for diag(V^-1 V') = 0) and
one constant length per mode pair that balances the couplings' rows and columns. With
x = V exp(Phi / Omega) y, Phi = int Lambda dtheta,

    dy/dtheta = exp(-Phi / Omega) (P0 + P1 + Omega P2) exp(Phi / Omega) y,

P0 = -V^-1 V' (off the diagonal (V^-1 A0' V)_ij / (lambda_i - lambda_j), A0' exact from the
Fourier series), P1 = V^-1 A1 V, P2 = V^-1 A2 V: the stiff part Lambda / Omega has left the
equation; what is left turns with the factors exp((Phi_j - Phi_i) / Omega), fast for distant
modes at low speed.

Per speed each step [a, b] (mid point m on the grid) is referenced at m: its propagator in the
eigen-coordinates is E(b, m) exp(Omega_k) E(m, a), E(s, r) = exp((Phi(s) - Phi(r)) / Omega)
diagonal (no entry above 1: Re lambda < 0), and Omega_k the fourth-order Magnus exponent
written with the step's moments,

    Omega_k = B0 + [B1, B0],  B0 = int Q~ ds,  B1 = 1/h int (s - h/2) Q~ ds,

Q (P0 + P1 + Omega P2, the phase's curvature folded in) a parabola through a, m and b, and the
turning factor exp(kappa s), kappa the step's mean rate, integrated in closed form (a Filon
rule: exact however fast the factor turns). [B1, B0] stands for the second Magnus term only
between slow entries; a pair with an entry that turns within the step takes the exact
double integral of the mid-point Q instead (``_second_order``). The steps are bounded by the damping (Re(kappa)
h / 2 <= DAMPING_PHASE keeps the factors below e^2) and by the couplings' size (h ||Q|| <=
COUPLING_STEP), not by the stiffest frequency. The conjugate halves are folded into real
2 x 2 blocks, so a step costs real products of the state's size.

Accuracy (docs/critical-speeds.md, "Speed"): fourth order where the couplings are smooth
(the Mathieu equation); on Table II case 1's basis ln |mu| per turn within 5.5e-5 of fine
Magnus steps at 512 steps, 10 to 3000 rev/min.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from flexlink.analysis.floquet import FloquetResult, exponentials, floquet, ordered_product
from flexlink.errors import NumericalError

DAMPING_PHASE = 2.0  # max Re(kappa) h / 2 in a step [-]: the factors exp(kappa s) below e^2
COUPLING_STEP = 0.25  # max h ||Q||_1 in a step [-]: the smooth part's Magnus error
SLOW = 0.5  # |kappa| h / 2 below which an entry counts as slow in the second Magnus term
SERIES = 0.25  # |z| below which the moments J_p(z) are summed as a power series
STEP_CHUNK = 64  # steps formed at once: their arrays stay in a core's cache


# coefficients of w^m in J_p(z) / z^(p mod 2), w = z^2: k = 2 m + (p mod 2) in the series
_SERIES = np.array([[2.0 / (math.factorial(2 * m + p % 2) * (2 * m + p % 2 + p + 1))
                     for m in range(6)] for p in range(4)])


@dataclass(frozen=True)
class AdiabaticBasis:
    """The speed-independent part of the integrator, on a grid of crank angles.

    angles (m + 1,) [rad]: the grid over one turn (both ends; m even); eigenvalues (m + 1, n)
    [1/s]: the half of A0's with positive imaginary part, tracked; phase (m + 1, n) [rad/s x
    rad]: Phi = int lambda dtheta from angles[0]; coupling, speed_coupling (m + 1, n, 2 n):
    rows of P0 + P1 and of P2 for the tracked half, columns over the tracked half then its
    conjugates; start, end
    (2 n, 2 n): the real eigenbasis (Re V, Im V) at the two ends; coupling_norm,
    speed_norm (m + 1,): the largest row sums of |P0 + P1| and |P2| [1/rad, 1/rad per rad/s]."""

    angles: np.ndarray
    eigenvalues: np.ndarray
    phase: np.ndarray
    coupling: np.ndarray
    speed_coupling: np.ndarray
    start: np.ndarray
    end: np.ndarray
    coupling_norm: np.ndarray
    speed_norm: np.ndarray


def adiabatic_basis(angles, a0, a0_prime, a1, a2) -> AdiabaticBasis:
    """Decompose and track A0 over ``angles`` (m + 1,) [rad], equally spaced over one turn
    (both ends, m even). a0, a0_prime (dA0/dtheta), a1, a2: (m + 1, N, N) at the angles (units
    of the module docstring: A0 [1/s], A1 [1/rad], A2 [1/rad per rad/s]).
    NumericalError where an eigenvalue is real (an overdamped or static direction) or the
    tracking loses a mode between grid points (a veering faster than the grid)."""
    angles = np.asarray(angles, dtype=float)
    m, size = len(angles) - 1, a0.shape[-1]
    if m < 2 or m % 2 or a0.shape != (m + 1, size, size) or size % 2:
        raise NumericalError(f"need an even number of grid steps and (m + 1, N, N) matrices "
                             f"of even N, got {len(angles)} angles and {a0.shape}")
    n = size // 2
    values, vectors = np.linalg.eig(a0)
    upper = values.imag > 0.0
    if not np.all(upper.sum(axis=1) == n):
        k = int(np.flatnonzero(upper.sum(axis=1) != n)[0])
        raise NumericalError(f"A0 has a real eigenvalue at crank angle {angles[k]:.6g} rad: "
                             "the adiabatic integrator needs every direction underdamped")
    order = np.argsort(np.where(upper, values.imag, np.inf), axis=1)[:, :n]
    lam = np.take_along_axis(values, order, axis=1)
    half = np.take_along_axis(vectors, order[:, None, :], axis=2)
    full = np.concatenate([half, half.conj()], axis=2)
    left = np.linalg.inv(full)[:, :n]  # rows w_i^H of the tracked half, w_i^H v_i = 1
    # tracking: each vector's best overlap at the next angle is its own
    forward = np.einsum("kin,kni->ki", left[:-1], full[1:, :, :n])  # w_k^H v_{k+1}, raw
    overlap = np.abs(forward)
    rival = np.abs(left[:-1] @ full[1:, :, :n])
    rival[:, np.arange(n), np.arange(n)] = 0.0
    lost = overlap < 2.0 * rival.max(axis=2)
    if lost.any():
        k, i = np.argwhere(lost)[0]
        raise NumericalError(f"mode {i + 1} of A0 is lost between crank angles {angles[k]:.6g}"
                             f" and {angles[k + 1]:.6g} rad (a veering or crossing faster than "
                             f"the grid of {m} steps): use a finer grid")
    # parallel transport: (g_{k+1} / g_k)^2 = (w_{k+1}^H v_k) / (w_k^H v_{k+1}), raw vectors
    backward = np.einsum("kin,kni->ki", left[1:], full[:-1, :, :n])
    ratio = np.sqrt(backward / forward)
    ratio = np.where((ratio * forward).real < 0.0, -ratio, ratio)
    gauge = np.concatenate([np.ones((1, n)), np.cumprod(ratio, axis=0)])
    half = half * gauge[:, None, :]
    full = np.concatenate([half, half.conj()], axis=2)
    left = left / gauge[:, :, None]
    derivative = left @ a0_prime @ full  # (m + 1, n, 2 n)
    gap = np.concatenate([lam, lam.conj()], axis=1)[:, None, :] - lam[:, :, None]
    diagonal = np.zeros((n, 2 * n), dtype=bool)
    diagonal[np.arange(n), np.arange(n)] = True
    p0 = -np.where(diagonal, 0.0, derivative / np.where(diagonal, 1.0, gap))
    rows = [p0 + left @ a1 @ full, left @ a2 @ full]
    slope = derivative[:, np.arange(n), np.arange(n)]  # dlambda/dtheta
    start = np.concatenate([half[0].real, half[0].imag], axis=1)
    end = np.concatenate([half[-1].real, half[-1].imag], axis=1)
    # the eigenvectors' lengths are free: one constant length per mode pair (a diagonal
    # similarity by powers of two, exact) that balances the mean |Q| rows against its columns,
    # where the unit vectors of eig leave the stiff modes' rows many times their columns
    mean = np.abs(rows[0][..., :n]).mean(axis=0) + np.abs(rows[0][..., n:]).mean(axis=0)
    scale = sla.matrix_balance(mean + np.eye(n), permute=False, separate=True)[1][0]
    columns = np.concatenate([scale, scale])
    rows = [r * columns / scale[:, None] for r in rows]
    start, end = start * columns, end * columns
    h = angles[1] - angles[0]
    increments = 0.5 * h * (lam[:-1] + lam[1:]) + h * h / 12.0 * (slope[:-1] - slope[1:])
    phase = np.concatenate([np.zeros((1, n)), np.cumsum(increments, axis=0)])
    return AdiabaticBasis(angles=angles, eigenvalues=lam, phase=phase, coupling=rows[0],
                          speed_coupling=rows[1], start=start, end=end,
                          coupling_norm=np.abs(rows[0]).sum(axis=2).max(axis=1),
                          speed_norm=np.abs(rows[1]).sum(axis=2).max(axis=1))


def step_bounds(basis: AdiabaticBasis, speed: float, least: int = 16) -> np.ndarray:
    """Grid indices of the step ends at crank ``speed`` [rad/s]: equal steps (to the grid's
    even indices), at least ``least`` and as many as keep the mean h ||Q|| <= COUPLING_STEP
    and the damping factors below DAMPING_PHASE (equal steps measured better than steps
    crowded where ||Q|| peaks). NumericalError when the grid is too coarse for them."""
    m = len(basis.angles) - 1
    spread = basis.eigenvalues.real.max() - basis.eigenvalues.real.min()
    norm = basis.coupling_norm + speed * basis.speed_norm
    turn = basis.angles[-1] - basis.angles[0]
    count = max(least, int(np.ceil(turn * max(norm.mean() / COUPLING_STEP,
                                               spread / (2.0 * DAMPING_PHASE * speed)))))
    if count > m // 2:
        raise NumericalError(f"{count} steps per turn are needed at {speed:.6g} rad/s, the "
                             f"grid of {m} intervals gives at most {m // 2}: use a finer grid")
    return np.unique(2 * np.round(np.arange(count + 1) * (m / 2) / count).astype(int))


def adiabatic_monodromy(basis: AdiabaticBasis, speed: float, least: int = 16) -> FloquetResult:
    """Floquet multipliers over one turn (period 2 pi / speed) at crank ``speed`` [rad/s] > 0,
    by at least ``least`` steps (``step_bounds``): the monodromy of the original state."""
    bounds = step_bounds(basis, speed, least)
    product = np.eye(basis.start.shape[1])
    for first in range(0, len(bounds) - 1, STEP_CHUNK):
        steps = _step_exponentials(basis, speed, bounds[first:first + STEP_CHUNK + 1])
        product = ordered_product(steps) @ product
    return floquet(basis.end @ product @ np.linalg.inv(basis.start), 2.0 * np.pi / speed)


def _step_exponentials(basis, speed, bounds):
    """(steps, 2 n, 2 n): each step's propagator in the real eigen-coordinates, the k-th from
    bounds[k] to bounds[k + 1] (module docstring)."""
    mid = (bounds[:-1] + bounds[1:]) // 2
    h = basis.angles[bounds[1:]] - basis.angles[bounds[:-1]]

    def columns(values):  # per-index values of the whole eigenbasis' columns
        return np.concatenate([values, values.conj()], axis=-1)

    ends, middle = basis.phase[bounds] / speed, basis.phase[mid] / speed
    total = ends[1:] - ends[:-1]  # (steps, n)
    residual = 0.5 * (ends[:-1] + ends[1:]) - middle
    # entry (i, j) turns as exp(kappa_ij sigma), kappa_ij h / 2 = z_ij = (total_j - total_i) / 2:
    # its exponentials are products of one per column and one per row
    half_turn = np.exp(0.5 * total)
    z = 0.5 * (columns(total)[:, None, :] - total[:, :, None])  # (steps, n, size)
    up = columns(half_turn)[:, None, :] / half_turn[:, :, None]  # exp(z)
    down = columns(1.0 / half_turn)[:, None, :] * half_turn[:, :, None]  # exp(-z)
    bend = columns(np.exp(residual))[:, None, :] * np.exp(-residual)[:, :, None]
    at_ends = basis.coupling[bounds] + speed * basis.speed_coupling[bounds]
    qm = basis.coupling[mid] + speed * basis.speed_coupling[mid]
    qa, qb = at_ends[:-1] * bend, at_ends[1:] * bend
    hh = (0.5 * h)[:, None, None]
    # Q(sigma) = qm + slope sigma + curve sigma^2 on sigma in [-h/2, h/2], written per power
    # of hh: c1 = slope hh, c2 = curve hh^2
    c1 = 0.5 * (qb - qa)
    c2 = 0.5 * (qa + qb) - qm
    j = _moments(z, up, down)  # int_{-1}^{1} u^p exp(z u) du, p = 0..3
    b0 = hh * (qm * j[0] + c1 * j[1] + c2 * j[2])
    b1 = 0.5 * hh * (qm * j[1] + c1 * j[2] + c2 * j[3])
    rows, real = _second_order(qm, b0, b1, z, hh * j[0], down, hh)
    exponent = _real_form(b0 + rows) + real
    steps = exponentials(exponent)
    # the diagonal factors E(b, m) on the left and E(m, a) on the right, as 2 x 2 rotations
    steps = _scaled_rows(steps, np.exp(basis.phase[bounds[1:]] / speed - middle))
    return _scaled_columns(steps, np.exp(middle - ends[:-1]))


def _second_order(q, b0, b1, z, phi, down, hh):
    """The second Magnus term of a step, as tracked-half rows and a real-form part whose
    sum (``_real_form(rows) + real``) is the term. Between slow entries
    (|z| < SLOW) the fourth-order [B1, B0]; every pair with a fast entry, where [B1, B0]
    misses the secular part, by the exact double integral of the mid-point Q: with
    G(a, b) = int int_{s2 < s1} exp(a s1 + b s2) = (phi(a + b) - exp(-b h/2) phi(a)) / b and
    G(a, b) - G(b, a) = 2 G(a, b) - phi(a) phi(b) = phi(a) phi(b) - 2 G(b, a), written so that
    only a fast entry's kappa is divided by, the sum over the middle index is three
    commutators: 1/2 [phi o [Qd, F] + [Fe, Pd] + [Pf, Ps]], F = Q / kappa and Fe = F
    exp(-z) on the fast entries, P = Q phi, s and f the slow and fast parts, Qd = Qf + 2 Qs,
    Pd = Pf + 2 Ps (phi = int exp(kappa s) ds over the step). The commutators of
    conjugate-symmetric matrices are formed in the real form, where a product costs half the
    complex one; the Hadamard product with phi needs the rows."""
    slow = np.abs(z) < SLOW
    qs = np.where(slow, q, 0.0)
    ps = _real_form(qs * phi)
    f = np.where(slow, 0.0, q * hh / np.where(slow, 1.0, z))
    pf = _real_form((q - qs) * phi)
    outer = _complex_form(_commutator(_real_form(q + qs), _real_form(f)))
    real = (_commutator(_real_form(np.where(slow, b1, 0.0)), _real_form(np.where(slow, b0, 0.0)))
            + 0.5 * (_commutator(_real_form(f * down), pf + 2.0 * ps) + _commutator(pf, ps)))
    return 0.5 * phi * outer, real


def _commutator(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """[a, b] = a b - b a of stacked matrices."""
    return a @ b - b @ a


def _complex_form(real: np.ndarray) -> np.ndarray:
    """The tracked half's rows (steps, n, 2 n) of a real-form matrix, ``_real_form``'s
    inverse: P + R and P - R read from its blocks [[Re(P + R), Im(P - R)], [-Im(P + R),
    Re(P - R)]]."""
    n = real.shape[-1] // 2
    a, b = real[..., :n, :n], real[..., :n, n:]
    c, d = real[..., n:, :n], real[..., n:, n:]
    plus, minus = a - 1j * c, d + 1j * b  # P + R and P - R
    return np.concatenate([0.5 * (plus + minus), 0.5 * (plus - minus)], axis=-1)


def _moments(z: np.ndarray, up: np.ndarray, down: np.ndarray) -> np.ndarray:
    """J_p(z) = int_{-1}^{1} u^p exp(z u) du for p = 0..3, elementwise, given up = exp(z) and
    down = exp(-z): the recurrence J_p = (e^z - (-1)^p e^-z - p J_{p-1}) / z, and below
    |z| = SERIES, where it would lose up to p! / |z|^p of the digits (at most 6 / SERIES^3 =
    384 units of round-off), the power series J_p = sum over k + p even of
    2 z^k / (k! (k + p + 1)), summed in w = z^2 (six terms: SERIES^12 / 12! ~ 1e-16)."""
    small = np.abs(z) < SERIES
    inverse = 1.0 / np.where(small, 1.0, z)
    out = np.empty((4,) + z.shape, dtype=complex)
    odd, even = up - down, up + down
    out[0] = odd * inverse
    out[1] = (even - out[0]) * inverse
    out[2] = (odd - 2.0 * out[1]) * inverse
    out[3] = (even - 3.0 * out[2]) * inverse
    zs = z[small]
    w = zs * zs
    for p in range(4):
        total = _SERIES[p, -1]
        for c in _SERIES[p, -2::-1]:
            total = total * w + c
        out[p][small] = total * zs if p % 2 else total
    return out


def _real_form(rows: np.ndarray) -> np.ndarray:
    """The real (2 n, 2 n) form of a conjugate-symmetric matrix given by its tracked half's
    rows (steps, n, 2 n): with P, R the blocks on the tracked half and on its conjugates,
    [[Re(P + R), Im(P - R)], [-Im(P + R), Re(P - R)]] (the matrix in the coordinates of the
    real basis (Re V, Im V))."""
    n = rows.shape[1]
    p, r = rows[..., :n], rows[..., n:]
    out = np.empty(rows.shape[:-2] + (2 * n, 2 * n))
    np.add(p.real, r.real, out=out[..., :n, :n])
    np.subtract(p.imag, r.imag, out=out[..., :n, n:])
    np.add(p.imag, r.imag, out=out[..., n:, :n])
    np.negative(out[..., n:, :n], out=out[..., n:, :n])
    np.subtract(p.real, r.real, out=out[..., n:, n:])
    return out


def _scaled_rows(m: np.ndarray, e: np.ndarray) -> np.ndarray:
    """diag(e, conj e) m in the real form: each pair's rows turned and scaled."""
    n = e.shape[-1]
    c, s = e.real[..., None], e.imag[..., None]
    top, bottom = m[..., :n, :], m[..., n:, :]
    return np.concatenate([c * top + s * bottom, c * bottom - s * top], axis=-2)


def _scaled_columns(m: np.ndarray, e: np.ndarray) -> np.ndarray:
    """m diag(e, conj e) in the real form."""
    n = e.shape[-1]
    c, s = e.real[..., None, :], e.imag[..., None, :]
    left, right = m[..., :n], m[..., n:]
    return np.concatenate([c * left - s * right, s * left + c * right], axis=-1)
