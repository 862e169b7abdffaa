"""Floquet analysis of a linear periodic system x' = A(t) x with period T.

The monodromy matrix Phi(T) (the fundamental matrix after one period, Phi(0) = I) is built by
a fixed-step fourth-order Magnus integrator with two Gauss-Legendre nodes per step:

    Omega_k = h/2 (A1 + A2) + sqrt(3)/12 h^2 [A2, A1],   Phi_{k+1} = expm(Omega_k) Phi_k,

with A1, A2 = A(t_k + (1/2 -+ sqrt(3)/6) h). Why Magnus rather than RK4: the step is the
exponential of a matrix in the same Lie algebra as A, so an undamped (Hamiltonian) system keeps
a symplectic monodromy and its stable multipliers stay on the unit circle to round-off; an RK4
step would add a spurious growth or decay of order h^4 per step, exactly what the stability test
|mu| > 1 must not see. The error of Phi(T) falls as steps^-4.

The Floquet multipliers are the eigenvalues of Phi(T). The solution grows when the largest
modulus exceeds one; ln|mu|_max is the growth per period, ln|mu|_max / T the growth rate [1/s].
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from flexlink.errors import NumericalError

_GAUSS_OFFSET = np.sqrt(3.0) / 6.0


@dataclass(frozen=True)
class FloquetResult:
    """The monodromy matrix of one period and its multipliers.

    monodromy: (n, n) Phi(T); multipliers: (n,) complex eigenvalues, largest modulus first;
    period: T [s]; log_largest: ln |mu|_max [-] where it is known apart from the multipliers
    (a bound exp(T r) that underflows to 0 at a slow enough speed keeps its exponent T r here),
    else None.
    """

    monodromy: np.ndarray
    multipliers: np.ndarray
    period: float
    log_largest: float | None = None

    @property
    def largest_modulus(self) -> float:
        """max |mu| [-]: above one the periodic system is unstable."""
        return float(np.abs(self.multipliers[0]))

    @property
    def growth_per_period(self) -> float:
        """ln |mu|_max [-]: the logarithmic growth of the fastest solution over one period."""
        if self.log_largest is not None:
            return float(self.log_largest)
        return float(np.log(self.largest_modulus))

    @property
    def growth_rate(self) -> float:
        """ln |mu|_max / T [1/s]: the exponential growth rate of the fastest solution."""
        return self.growth_per_period / self.period


def first_order(mass: np.ndarray, damping: np.ndarray, stiffness: np.ndarray) -> np.ndarray:
    """A of x' = A x for M q'' + C q' + K q = 0 with x = (q, q'): [[0, I], [-M^-1 K, -M^-1 C]].

    mass, damping, stiffness: (..., n, n), any leading batch shape; returns (..., 2n, 2n)."""
    mass, damping, stiffness = np.broadcast_arrays(mass, damping, stiffness)
    n = mass.shape[-1]
    solved = np.linalg.solve(mass, np.concatenate([stiffness, damping], axis=-1))
    a = np.zeros(mass.shape[:-2] + (2 * n, 2 * n))
    a[..., :n, n:] = np.eye(n)
    a[..., n:, :n] = -solved[..., :n]
    a[..., n:, n:] = -solved[..., n:]
    return a


# Paterson-Stockmeyer blocks of the degree-12 Taylor polynomial over the powers I, x, x^2,
# x^3, x^4: block b sums x^i / (4 b + i)! for i < 4, the last block also x^4 / 12!
_TAYLOR = np.array([[1.0 / math.factorial(4 * b + i) for i in range(4)] + [0.0]
                    for b in range(3)])
_TAYLOR[2, 4] = 1.0 / math.factorial(12)


def exponentials(omega: np.ndarray) -> np.ndarray:
    """expm of each (n, n) matrix in omega (m, n, n): scaling and squaring with a degree-12
    Taylor polynomial, all steps at once, the polynomial in Paterson-Stockmeyer form (five
    products instead of eleven). Scaled to norm <= 1/2, the neglected Taylor terms are below
    0.5^13 / 13! ~ 2e-14 relative. The powers I, x, x^2, x^3, x^4 are written into one array
    and the three blocks formed by one product with the coefficients; the Horner steps
    write into the powers no longer needed: the cost is the matrix products, not passes over
    temporaries. Against scipy.linalg.expm on the stability map's own stacks:
    ``benchmarks/exponentials.py``."""
    norm = np.abs(omega).sum(axis=-2).max() if omega.size else 0.0
    squarings = max(0, int(np.ceil(np.log2(norm / 0.5)))) if norm > 0.5 else 0
    m, n = omega.shape[0], omega.shape[-1]
    powers = np.empty((5, m, n, n))
    powers[0] = np.eye(n)
    np.multiply(omega, 2.0**-squarings, out=powers[1])
    np.matmul(powers[1], powers[1], out=powers[2])
    np.matmul(powers[2], powers[1], out=powers[3])
    np.matmul(powers[2], powers[2], out=powers[4])
    blocks = np.tensordot(_TAYLOR, powers, axes=1)  # (3, m, n, n)
    inner, result = powers[1], powers[2]
    np.matmul(powers[4], blocks[2], out=inner)
    inner += blocks[1]
    np.matmul(powers[4], inner, out=result)
    result += blocks[0]
    for _ in range(squarings):
        result = result @ result
    return result


CHUNK = 1024  # Magnus steps formed at once: bounded memory, few numpy calls


def monodromy(system: Callable[[np.ndarray], np.ndarray], period: float,
              steps: int, order: int = 4,
              on_steps: Callable[[int], None] | None = None) -> FloquetResult:
    """Phi(T) of x' = A(t) x over one period by `steps` Magnus steps of ``order`` 4 or 2.

    system: times (m,) [s] -> (m, n, n) A at those times, periodic with `period` [s];
    steps: fixed steps per period. The steps are formed CHUNK at a time and each chunk's
    exponentials multiplied pairwise (a product tree: log2(CHUNK) stacked products instead of
    CHUNK single ones, the same product in the same order). ``on_steps``: called with the
    count of steps done after each chunk (a progress bar's update)."""
    return floquet(propagators(system, period, 1, steps, order, on_steps)[0], period)


def propagators(system: Callable[[np.ndarray], np.ndarray], period: float, intervals: int,
                steps: int, order: int = 4,
                on_steps: Callable[[int], None] | None = None) -> np.ndarray:
    """(intervals, n, n): the fundamental matrix of each of ``intervals`` equal consecutive
    intervals of [0, period] [s] (the k-th maps x(t_k) to x(t_{k+1})), each by ``steps``
    Magnus steps; their product, later on the left, is Phi(period). Short intervals are
    formed several at a time, so a fine output grid costs no more calls than one period.

    ``order`` 4: the two-node fourth-order step (module docstring). ``order`` 2: the
    exponential midpoint step expm(h A(t_k + h/2)), the Magnus series' first term. Its
    exponent holds no commutator, so a step many periods of the stiffest mode long is still
    the exact flow of the equations frozen at its midpoint (decaying where they decay): its
    error follows how much A changes over the step, not how large A is. The fourth-order
    step's commutator grows as h^3 ||A|| ||A'||, and past h max|eig A| of a few tens it
    injects growth that is not in the equations (overflow within one turn)."""
    if not (np.isfinite(period) and period > 0.0):
        raise NumericalError(f"period must be a positive finite time in s, got {period}")
    if order not in (2, 4):
        raise NumericalError(f"Magnus order must be 2 or 4, got {order}")
    if steps < 1 or intervals < 1:
        raise NumericalError(f"steps and intervals must be at least 1, got {steps}, "
                             f"{intervals}")
    h = period / (intervals * steps)
    # a diagonal similarity D^-1 A D by powers of two (exact) that balances the rows and
    # columns: in x = (q, q') the stiffness block is omega^2 where the identity block is 1, so
    # unbalanced, a step's norm needs many more squarings in the exponential
    d = sla.matrix_balance(np.asarray(system(np.array([0.0])), dtype=float)[0],
                           permute=False, separate=True)[1][0]
    ratio = d[None, :] / d[:, None]
    out = np.empty((intervals, len(d), len(d)))
    if steps > CHUNK:
        for k in range(intervals):
            phi = None
            for first in range(k * steps, (k + 1) * steps, CHUNK):
                last = min((k + 1) * steps, first + CHUNK)
                chunk = ordered_product(_steps(system, h, first, last, ratio, order))
                phi = chunk if phi is None else chunk @ phi
                if on_steps is not None:
                    on_steps(last - first)
            out[k] = phi
    else:
        group = CHUNK // steps
        for k in range(0, intervals, group):
            count = min(group, intervals - k)
            factors = _steps(system, h, k * steps, (k + count) * steps, ratio, order)
            out[k:k + count] = ordered_product(factors.reshape(count, steps, len(d), len(d)))
            if on_steps is not None:
                on_steps(count * steps)
    return out / ratio


def _steps(system, h: float, first: int, last: int, ratio: np.ndarray,
           order: int = 4) -> np.ndarray:
    """The balanced exponentials of Magnus steps first..last-1 (of length h [s] from t = 0),
    of ``order`` 4 or 2 (``propagators``)."""
    starts = h * np.arange(first, last)
    if order == 2:
        return exponentials(h * _sampled(system, starts + 0.5 * h) * ratio)
    a1 = _sampled(system, starts + (0.5 - _GAUSS_OFFSET) * h)
    a2 = _sampled(system, starts + (0.5 + _GAUSS_OFFSET) * h)
    omega = 0.5 * h * (a1 + a2) + (np.sqrt(3.0) / 12.0) * h * h * (a2 @ a1 - a1 @ a2)
    return exponentials(omega * ratio)


def _sampled(system, times: np.ndarray) -> np.ndarray:
    """A at ``times`` (m,), checked to be (m, n, n)."""
    a = np.asarray(system(times), dtype=float)
    if a.ndim != 3 or a.shape[0] != len(times) or a.shape[1] != a.shape[2]:
        raise NumericalError(f"system must return ({len(times)}, n, n) matrices, got "
                             f"{a.shape}")
    return a


def ordered_product(factors: np.ndarray) -> np.ndarray:
    """F_{m-1} ... F_1 F_0 of factors (..., m, n, n) along the axis of m, the later factor on
    the left (any leading batch axes: one product each)."""
    while factors.shape[-3] > 1:
        m = factors.shape[-3]
        factors = np.concatenate([factors[..., 1::2, :, :] @ factors[..., 0:m - 1:2, :, :],
                                  factors[..., m - m % 2:, :, :]], axis=-3)
    return factors[..., 0, :, :]


def floquet(phi: np.ndarray, period: float) -> FloquetResult:
    """The multipliers of a monodromy matrix, largest modulus first. NumericalError where
    the matrix is not finite (a growth over the period beyond the floating-point range)."""
    if not np.all(np.isfinite(phi)):
        raise NumericalError("the monodromy matrix overflowed over one period: a growth "
                             "beyond the floating-point range")
    mu = np.linalg.eigvals(phi)
    order = np.argsort(-np.abs(mu), kind="stable")
    return FloquetResult(monodromy=phi, multipliers=mu[order], period=float(period))
