"""The Mathieu equation as a reference, written once for every test that needs it:

    q'' + 2 c q' + (delta + epsilon cos t) q = 0          (additive form)
    q'' + 2 c q' + delta (1 + epsilon cos t) q = 0        (multiplicative form)

Its k-th instability tongue emanates from delta = k^2 / 4 (a parametric resonance at twice the
natural frequency over k). On a tongue's edge, undamped, a solution is periodic: of period 4 pi
for odd k (half-integer harmonics), 2 pi for even k. Writing q = sum a_n exp(i n t / 2) over n
of k's parity turns the equation into

    (delta - n^2 / 4) a_n + e / 2 (a_{n-2} + a_{n+2}) = 0,   e = epsilon (additive) or
                                                                 delta epsilon (multiplicative)

so the edges are eigenvalues of Hill's infinite tridiagonal matrix (symmetric, or a symmetric
pencil for the multiplicative form), the two nearest k^2 / 4. No time integration enters, and
the truncation error falls faster than any power of the order (the coefficients decay like
epsilon^j / (j!)^2).
"""

import numpy as np
import scipy.linalg as sla


def first_order_matrix(delta: float, epsilon: float, c: float = 0.0, speed: float = 1.0):
    """A(t) of the additive form in first-order form x = (q, q'), with cos(speed t): a
    function of t (a number or an array of times) giving (..., 2, 2)."""
    def a(t):
        out = np.zeros(np.shape(t) + (2, 2))
        out[..., 0, 1] = 1.0
        out[..., 1, 0] = -(delta + epsilon * np.cos(speed * np.asarray(t, dtype=float)))
        out[..., 1, 1] = -2.0 * c
        return out
    return a


def hill_edges(epsilon: float, k: int = 1, multiplicative: bool = False,
               order: int = 30) -> tuple[float, float]:
    """(lower, upper) delta on the edges of the k-th tongue (k >= 1), undamped, from Hill's
    determinant truncated at |n| <= 2 order + k."""
    n = np.arange(-(2 * order + k), 2 * order + k + 1, 2).astype(float)
    diagonal = np.diag(n**2 / 4.0)
    shift = np.eye(n.size, k=1) + np.eye(n.size, k=-1)
    if multiplicative:  # n^2/4 a = delta (I + epsilon/2 S) a: a definite pencil for epsilon < 1
        values = sla.eigh(diagonal, np.eye(n.size) + epsilon / 2.0 * shift, eigvals_only=True)
    else:
        values = np.linalg.eigvalsh(diagonal - epsilon / 2.0 * shift)
    nearest = np.sort(values[np.argsort(np.abs(values - k * k / 4.0))[:2]])
    return float(nearest[0]), float(nearest[1])
