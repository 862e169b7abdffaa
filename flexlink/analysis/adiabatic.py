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
double integral of the mid-point Q instead (``_second_order``). The steps are cells of the
grid's dyadic hierarchy: equal ones, as many as the damping needs (Re(kappa) h / 2 <=
DAMPING_PHASE keeps the factors below e^2), each halved where the couplings are large (h ||Q||
> COUPLING_STEP) or Q departs from its parabola (RESOLUTION: a veering's narrow peak), not
set by the stiffest frequency (``step_bounds``). The conjugate halves are folded into real
2 x 2 blocks, so a step costs real products of the state's size: a conjugate-symmetric
matrix is carried by its tracked columns (its rows over the tracked half and the
conjugates, its columns over the tracked half) for the elementwise work, and its real form
is in the basis (Re v_1, Im v_1, Re v_2, ...), whose row pairs read as complex numbers are
two sums of those columns (``_real_form``). A step costs 13 products of the state's size:
4 for the second term's commutators, 2 for the one Hadamard-weighted commutator, 6 for the
exponential and 1 for the ordered product.

Accuracy (docs/critical-speeds.md, "Speed"): fourth order where the couplings are smooth
(the Mathieu equation); on Table II case 1's basis ln |mu| per turn within 5.8e-4 of fine
Magnus steps from 64 steps refined (about 135), 1.5e-4 from 128 (about 250), 10 to 3000
rev/min.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from flexlink.analysis.floquet import FloquetResult, exponentials, floquet, ordered_product
from flexlink.errors import NumericalError

DAMPING_PHASE = 2.0  # max Re(kappa) h / 2 in a step [-]: the factors exp(kappa s) below e^2
COUPLING_STEP = 2.0  # max h ||Q||_1 over a step's grid points [-]: below pi, where the Magnus
# series converges
RESOLUTION = 1e-3  # max h ||Q - its parabola|| at a step's quarter points [-]: a step that
# does not resolve Q (a veering's narrow peak of -V^-1 V') is halved
RESOLUTION_STEPS = 128  # the least count RESOLUTION holds at: at k times as many, RESOLUTION / k^4
SLOW = 0.5  # |kappa| h / 2 below which an entry counts as slow in the second Magnus term
SERIES = 0.25  # |z| below which the moments J_p(z) are summed as a power series
STEP_CHUNK = 32  # steps formed at once: on case 1 as fast as 64 and 14 % faster than 16


# coefficients of w^m in J_p(z) / z^(p mod 2), w = z^2: k = 2 m + (p mod 2) in the series
_SERIES = np.array([[2.0 / (math.factorial(2 * m + p % 2) * (2 * m + p % 2 + p + 1))
                     for m in range(6)] for p in range(4)])


@dataclass(frozen=True)
class AdiabaticBasis:
    """The speed-independent part of the integrator, on a grid of crank angles.

    angles (m + 1,) [rad]: the grid over one turn (both ends; m / 2 a power of two);
    eigenvalues (m + 1, n) [1/s]: the half of A0's with positive imaginary part, tracked;
    phase (m + 1, n) [rad/s x rad]: Phi = int lambda dtheta from angles[0]; coupling, speed_coupling (2 n, m + 1, n):
    the tracked columns of P0 + P1 and of P2 (rows over the tracked half then its
    conjugates; the grid's axis between the rows and the columns, as the steps' arrays have
    it); end (2 n, 2 n): the real eigenbasis (Re v_1, Im v_1, Re v_2, ...) at the turn's
    end, start_inverse: the inverse of that at its start; peak, defect (2, 2^(L + 1)) over the grid's dyadic cells (``_dyadic_bounds``),
    of P0 + P1 (row 0) and of P2 (row 1, per rad/s): h times the largest row sum of |Q| over a
    cell's grid points, and h times that of Q's departure from its parabola at the cell's
    quarter points [-]."""

    angles: np.ndarray
    eigenvalues: np.ndarray
    phase: np.ndarray
    coupling: np.ndarray
    speed_coupling: np.ndarray
    start_inverse: np.ndarray
    end: np.ndarray
    peak: np.ndarray
    defect: np.ndarray


def adiabatic_basis(angles, a0, a0_prime, a1, a2) -> AdiabaticBasis:
    """Decompose and track A0 over ``angles`` (m + 1,) [rad], equally spaced over one turn
    (both ends, m / 2 a power of two). a0, a0_prime (dA0/dtheta), a1, a2: (m + 1, N, N) at
    the angles (units of the module docstring: A0 [1/s], A1 [1/rad], A2 [1/rad per rad/s]).
    NumericalError where an eigenvalue is real (an overdamped or static direction) or the
    tracking loses a mode between grid points (a veering faster than the grid)."""
    angles = np.asarray(angles, dtype=float)
    m, size = len(angles) - 1, a0.shape[-1]
    if m < 2 or (m // 2) & (m // 2 - 1) or m % 2 or a0.shape != (m + 1, size, size) \
            or size % 2:
        raise NumericalError(f"need 2^k grid steps (k >= 1) and (m + 1, N, N) matrices of "
                             f"even N, got {len(angles)} angles and {a0.shape}")
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
    # the eigenvectors' lengths are free: one constant length per mode pair (a diagonal
    # similarity by powers of two, exact) that balances the mean |Q| rows against its columns,
    # where the unit vectors of eig leave the stiff modes' rows many times their columns
    mean = np.abs(rows[0][..., :n]).mean(axis=0) + np.abs(rows[0][..., n:]).mean(axis=0)
    scale = sla.matrix_balance(mean + np.eye(n), permute=False, separate=True)[1][0]
    columns = np.concatenate([scale, scale])
    rows = [r * columns / scale[:, None] for r in rows]
    h = angles[1] - angles[0]
    increments = 0.5 * h * (lam[:-1] + lam[1:]) + h * h / 12.0 * (slope[:-1] - slope[1:])
    phase = np.concatenate([np.zeros((1, n)), np.cumsum(increments, axis=0)])
    coupling, speed_coupling = (_tracked_columns(r).transpose(1, 0, 2).copy() for r in rows)
    bounds = [_dyadic_bounds(c, angles) for c in (coupling, speed_coupling)]
    return AdiabaticBasis(angles=angles, eigenvalues=lam, phase=phase, coupling=coupling,
                          speed_coupling=speed_coupling,
                          start_inverse=np.linalg.inv(_real_basis(half[0]) * np.repeat(scale, 2)),
                          end=_real_basis(half[-1]) * np.repeat(scale, 2),
                          peak=np.stack([b[0] for b in bounds]),
                          defect=np.stack([b[1] for b in bounds]))


def _row_norms(columns: np.ndarray) -> np.ndarray:
    """The largest row sum of |M| (...) of conjugate-symmetric matrices M given by their
    tracked columns (2 n, ..., n): row i of M is row i of the columns and the conjugates of
    row n + i's."""
    n = columns.shape[-1]
    sums = np.abs(columns).sum(axis=-1)
    return (sums[:n] + sums[n:]).max(axis=0)


def _dyadic_bounds(columns: np.ndarray, angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(peak, defect) of Q given by its tracked columns (2 n, m + 1, n) on the grid ``angles``,
    per dyadic cell of the grid in heap order (cell i = 2^l + k is the k-th of the 2^l equal
    cells of level l, its halves are cells 2 i and 2 i + 1; levels down to cells of 2 grid
    intervals, entry 0 unused): h max ||Q|| over the cell's grid points and h (||Q - p|| at
    its first quarter point + the same at its third), p the parabola through the cell's ends
    and mid point (zero for the finest cells, which have no quarter points)."""
    m = len(angles) - 1
    finest = m // 2
    peak, defect = np.zeros(2 * finest), np.zeros(2 * finest)
    norms = _row_norms(columns)
    count = 1
    while count <= finest:
        length = m // count
        starts = np.arange(count) * length
        h = angles[starts + length] - angles[starts]
        peak[count:2 * count] = h * np.maximum(np.maximum.reduceat(norms[:-1], starts),
                                               norms[starts + length])
        if length >= 4:
            points = np.take(columns, starts[:, None] + np.arange(5) * (length // 4), axis=1)
            a, first, b, third, c = np.moveaxis(points, 2, 0)
            slope, curve = 0.25 * (c - a), 0.125 * (a + c - 2.0 * b)
            departure = np.abs(first - (b - slope + curve)) + np.abs(third - (b + slope + curve))
            defect[count:2 * count] = h * _row_norms(departure)
        count *= 2
    return peak, defect


def _tracked_columns(rows: np.ndarray) -> np.ndarray:
    """The tracked columns M[:, :n] (..., 2 n, n) of conjugate-symmetric matrices M given by
    their tracked rows M[:n] (..., n, 2 n) = [P, R]: [P; conj R]."""
    n = rows.shape[-2]
    return np.concatenate([rows[..., :n], rows[..., n:].conj()], axis=-2)


def _real_basis(vectors: np.ndarray) -> np.ndarray:
    """(N, 2 n): the real basis (Re v_1, Im v_1, Re v_2, Im v_2, ...) of eigenvectors (N, n)."""
    return np.stack([vectors.real, vectors.imag], axis=-1).reshape(len(vectors), -1)


def step_bounds(basis: AdiabaticBasis, speed: float, least: int = 16) -> np.ndarray:
    """Grid indices of the step ends at crank ``speed`` [rad/s]: dyadic cells of the grid,
    first equal, at least ``least`` and as many as keep the damping factors below
    DAMPING_PHASE (rounded up to a power of two), then each halved, down to two grid
    intervals, while h ||Q|| exceeds COUPLING_STEP or Q's departure from its parabola
    RESOLUTION (both bounded by the triangle inequality over Q's two parts: a few steps more
    where a veering makes Q peak, rather than finer steps everywhere). NumericalError when the
    grid is too coarse for the equal steps, or its finest cells for COUPLING_STEP."""
    finest = basis.peak.shape[1] // 2
    spread = basis.eigenvalues.real.max() - basis.eigenvalues.real.min()
    turn = basis.angles[-1] - basis.angles[0]
    count = max(least, int(np.ceil(turn * spread / (2.0 * DAMPING_PHASE * speed))))
    count = 1 << (count - 1).bit_length()
    if count > finest:
        raise NumericalError(f"{count} steps per turn are needed at {speed:.6g} rad/s, the "
                             f"grid of {2 * finest} intervals gives at most {finest}: use a "
                             "finer grid")
    peak, defect = basis.peak[0] + speed * basis.peak[1], basis.defect[0] + speed * basis.defect[1]
    resolution = RESOLUTION * (RESOLUTION_STEPS / least) ** 4
    cells = np.arange(count, 2 * count)
    while True:
        split = ((peak[cells] > COUPLING_STEP) | (defect[cells] > resolution)) & (cells < finest)
        if not split.any():
            break
        cells = np.concatenate([cells[~split], 2 * cells[split], 2 * cells[split] + 1])
    if (peak[cells] > COUPLING_STEP).any():
        raise NumericalError(f"the couplings need steps shorter than the grid's at {speed:.6g} "
                             f"rad/s (h ||Q|| up to {peak[cells].max():.3g} on the finest "
                             f"cells, above {COUPLING_STEP:g}): use a finer grid")
    level = np.frexp(cells)[1] - 1
    starts = (cells - (1 << level)) * (2 * finest >> level)
    return np.append(np.sort(starts), 2 * finest)


def adiabatic_monodromy(basis: AdiabaticBasis, speed: float, least: int = 16) -> FloquetResult:
    """Floquet multipliers over one turn (period 2 pi / speed) at crank ``speed`` [rad/s] > 0,
    by at least ``least`` steps (``step_bounds``): the monodromy of the original state.

    The diagonal factors between two steps' exponentials are merged, E(m_k, b_k) E(b_k,
    m_(k-1)) into one (a column scaling of the later step), and E(b_last, m_last) multiplies
    the product once."""
    bounds = step_bounds(basis, speed, least)
    ends = basis.phase[bounds] / speed  # Phi / Omega at the step ends and mid points [-]
    middle = basis.phase[(bounds[:-1] + bounds[1:]) // 2] / speed
    before = np.concatenate([ends[:1], middle[:-1]])  # m_(k-1), b_0 for the first step
    turns = np.exp(middle - before)
    product = np.eye(basis.end.shape[1])
    for first in range(0, len(bounds) - 1, STEP_CHUNK):
        last = min(first + STEP_CHUNK, len(bounds) - 1)
        steps = _step_exponentials(basis, speed, bounds[first:last + 1], ends[first:last + 1],
                                   middle[first:last])
        product = ordered_product(_scaled_columns(steps, turns[first:last])) @ product
    end = _scaled_columns(basis.end.copy(), np.exp(ends[-1] - middle[-1]))
    return floquet(end @ product @ basis.start_inverse, 2.0 * np.pi / speed)


def _step_exponentials(basis, speed, bounds, ends, middle):
    """(steps, 2 n, 2 n): exp(Omega_k) of each step, the k-th from bounds[k] to bounds[k + 1],
    in the real eigen-coordinates (module docstring); ends (steps + 1, n), middle (steps, n):
    Phi / Omega at the step ends and mid points.

    The steps' tracked columns are arrays (2 n, steps, n) and their real forms (2 n, steps,
    2 n): the steps' axis between the rows and the columns keeps every elementwise pass over
    long contiguous runs (a per-step value is spread over a row's n columns), the real form's
    row pairs included, and each step's matrix is still a strided view that the matrix
    products take as it is."""
    n = ends.shape[1]
    mid = (bounds[:-1] + bounds[1:]) // 2
    hh = np.repeat(0.5 * (basis.angles[bounds[1:]] - basis.angles[bounds[:-1]]), n)
    hh = hh.reshape(1, -1, n).astype(complex)  # complex: no casting pass in the products
    total = ends[1:] - ends[:-1]  # (steps, n)
    residual = 0.5 * (ends[:-1] + ends[1:]) - middle
    # entry (r, j) of the tracked columns turns as exp(kappa_rj sigma), kappa_rj h / 2 = z_rj
    # = (total_j - total_r) / 2, r over the tracked half and its conjugates: its exponentials
    # are products of one per column and one per row
    half_turn = np.exp(0.5 * total)
    z = 0.5 * (total - _per_row(total))  # (2 n, steps, n)
    per_row = _per_row(half_turn)
    up = half_turn / per_row  # exp(z)
    down = (1.0 / half_turn) * per_row  # exp(-z)
    bend = np.exp(residual) * _per_row(0.5 * np.exp(-residual))
    points = np.concatenate([bounds, mid])
    q = np.take(basis.coupling, points, axis=1)
    q += speed * np.take(basis.speed_coupling, points, axis=1)
    at_ends, qm = q[:, :len(bounds)], q[:, len(bounds):]
    # Q(sigma) = qm + slope sigma + curve sigma^2 on sigma in [-h/2, h/2], written per power
    # of hh: c1 = slope hh, c2 = curve hh^2 (the ends' Q times the phase's curvature, bend)
    c1 = (at_ends[:, 1:] - at_ends[:, :-1]) * bend
    c2 = (at_ends[:, 1:] + at_ends[:, :-1]) * bend - qm
    size = np.abs(z)
    # 1 / z = conj(z) / |z|^2 (a complex division costs several products), where |z| >=
    # SERIES: the only entries divided by
    inverse = np.where(size < SERIES, 1.0, size)
    inverse *= inverse
    np.divide(1.0, inverse, out=inverse)
    inverse = z.conj() * inverse
    j = _moments(z, size < SERIES, inverse, up, down)  # int_{-1}^{1} u^p exp(z u) du
    b0 = hh * (qm * j[0] + c1 * j[1] + c2 * j[2])
    b1 = 0.5 * hh * (qm * j[1] + c1 * j[2] + c2 * j[3])
    phi = hh * j[0]
    columns, real = _second_order(qm, b0, b1, size < SLOW, hh * inverse, phi, down)
    columns += b0
    real += _real_form(columns)
    return exponentials(real.transpose(1, 0, 2))


def _per_row(values: np.ndarray) -> np.ndarray:
    """(2 n, steps, 1): per-mode values (steps, n) on the rows of the tracked columns, the
    tracked half then its conjugates."""
    return np.concatenate([values, values.conj()], axis=-1).T[:, :, None]


def _second_order(q, b0, b1, slow, step, phi, down):
    """The second Magnus term of a step, as tracked columns and a real-form part whose sum
    (``_real_form(columns) + real``) is the term. Between slow entries (|z| < SLOW) the
    fourth-order [B1, B0]; every pair with a fast entry, where [B1, B0] misses the secular
    part, by the exact double integral of the mid-point Q: with G(a, b) = int int_{s2 < s1}
    exp(a s1 + b s2) = (phi(a + b) - exp(-b h/2) phi(a)) / b and G(a, b) - G(b, a) =
    2 G(a, b) - phi(a) phi(b) = phi(a) phi(b) - 2 G(b, a), written so that only a fast
    entry's kappa is divided by, the sum over the middle index is three commutators:
    1/2 [phi o [Qd, F] + [Fe, Pd] + [Pf, Ps]], F = Q / kappa and Fe = F exp(-z) on the fast
    entries, P = Q phi, s and f the slow and fast parts, Qd = Qf + 2 Qs, Pd = Pf + 2 Ps
    (phi = int exp(kappa s) ds over the step). The last two are one commutator,
    [Fe, Pd] + [Pf, Ps] = [Fe - Ps, Pd] (bilinear and antisymmetric; Pd = Q phi + Ps). The
    commutators of conjugate-symmetric matrices are formed in the real form, where a product
    costs half the complex one; the Hadamard product with phi needs the columns. Arrays as
    in ``_step_exponentials``; slow: |z| < SLOW; step: 1 / kappa = hh / z on the fast
    entries."""
    qs = np.where(slow, q, 0.0)
    qd = q + qs
    f = np.where(slow, 0.0, q * step)
    factors = np.empty((6,) + q.shape, dtype=complex)  # [B1s, (Fe - Ps) / 2, Qd; B0s, Pd, F]
    np.multiply(b1, slow, out=factors[0])
    np.multiply(f, down, out=factors[1])
    factors[1] -= qs * phi
    factors[1] *= 0.5
    factors[2] = qd
    np.multiply(b0, slow, out=factors[3])
    np.multiply(qd, phi, out=factors[4])
    factors[5] = f
    forms = _real_form(factors).transpose(0, 2, 1, 3)  # (6, steps, 2 n, 2 n) views
    left, right = forms[:3], forms[3:]
    brackets, reverse = np.empty((2, 3) + forms.shape[2:3] + forms.shape[1:2] + forms.shape[3:])
    np.matmul(left, right, out=brackets.transpose(0, 2, 1, 3))
    np.matmul(right, left, out=reverse.transpose(0, 2, 1, 3))
    brackets -= reverse
    brackets[0] += brackets[1]
    outer = _complex_form(brackets[2])
    outer *= 0.5 * phi
    return outer, brackets[0]


def _moments(z, small, inverse, up, down):
    """J_p(z) = int_{-1}^{1} u^p exp(z u) du for p = 0..3 (4, ...), elementwise, given
    small = |z| < SERIES, inverse = 1 / z where not small, up = exp(z) and down = exp(-z):
    the recurrence J_p = (e^z - (-1)^p e^-z - p J_{p-1}) / z, and below |z| = SERIES, where
    it would lose up to p! / |z|^p of the digits (at most 6 / SERIES^3 = 384 units of
    round-off), the power series J_p = sum over k + p even of 2 z^k / (k! (k + p + 1)),
    summed in w = z^2 (six terms: SERIES^12 / 12! ~ 1e-16)."""
    out = np.empty((4,) + z.shape, dtype=complex)
    odd, even = up - down, up + down
    np.multiply(odd, inverse, out=out[0])
    np.multiply(even - out[0], inverse, out=out[1])
    np.multiply(odd - 2.0 * out[1], inverse, out=out[2])
    np.multiply(even - 3.0 * out[2], inverse, out=out[3])
    where = np.flatnonzero(small)  # flat indices: cheaper to gather and scatter than a mask
    zs = z.take(where)
    w = zs * zs
    series = np.empty((4, len(zs)), dtype=complex)
    series[:] = _SERIES[:, -1:]
    for c in _SERIES[:, -2::-1].T:
        series *= w
        series += c[:, None]
    series[1::2] *= zs
    for p in range(4):
        np.put(out[p], where, series[p])
    return out


def _real_form(columns: np.ndarray) -> np.ndarray:
    """The real (2 n, 2 n) forms of conjugate-symmetric matrices given by their tracked
    columns (..., 2 n, steps, n) = [P; conj R]: (..., 2 n, steps, 2 n), each step's matrix in
    the coordinates of the real basis (Re v_1, Im v_1, Re v_2, ...), whose 2 x 2 block (i, j)
    is [[Re(P + R), Im(P - R)], [-Im(P + R), Re(P - R)]]_ij. Its row pair i read as complex
    numbers (one per column pair) is P + conj R and i (P - conj R)."""
    n = columns.shape[-1]
    top, bottom = columns[..., :n, :, :], columns[..., n:, :, :]
    out = np.empty(top.shape[:-2] + (2,) + top.shape[-2:], dtype=complex)
    np.add(top, bottom, out=out[..., 0, :, :])
    np.subtract(top, bottom, out=out[..., 1, :, :])
    out[..., 1, :, :] *= 1j
    return out.view(float).reshape(columns.shape[:-1] + (2 * n,))


def _complex_form(real: np.ndarray) -> np.ndarray:
    """The tracked columns (2 n, steps, n) of real forms (2 n, steps, 2 n) (C-contiguous),
    ``_real_form``'s inverse: with A, B the row pairs read as complex numbers,
    P = (A - i B) / 2 and conj R = (A + i B) / 2."""
    n = real.shape[-1] // 2
    pairs = real.view(complex).reshape((n, 2) + real.shape[1:2] + (n,))
    turned = 1j * pairs[:, 1]
    out = np.empty((2 * n,) + real.shape[1:2] + (n,), dtype=complex)
    np.subtract(pairs[:, 0], turned, out=out[:n])
    np.add(pairs[:, 0], turned, out=out[n:])
    out *= 0.5
    return out


def _scaled_columns(m: np.ndarray, e: np.ndarray) -> np.ndarray:
    """m diag(e, conj e) in the real form, in place: each column pair read as complex numbers
    is multiplied by its e (m (..., 2 n, 2 n) C-contiguous, e (..., n))."""
    pairs = m.view(complex)
    pairs *= e[..., None, :]
    return m
