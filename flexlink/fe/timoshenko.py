"""A straight link as a chain of 2D Timoshenko frame elements (shear strain, rotary inertia).

Same local DOF order as ``link.py``: (u, v, rz) per node, nodes from the link's start (x = 0)
to its end; here rz is the rotation psi of the cross-section, which differs from the slope v'
by the shear strain gamma = v' - psi.

Bending uses the "interdependent interpolation" element (Friedman and Kosmatka, Computers &
Structures 47, 1993): cubic v and quadratic psi that solve the homogeneous static Timoshenko
equations exactly, with the shear parameter Phi = 12 EI / (k G A h^2) of an element of length h.
Because the static solution is exact the element cannot lock in shear, and with Phi -> 0 it
becomes the Hermite Euler-Bernoulli element. Per element of length h, xi = x / h:
    K = int_0^h EI psi'^2 + kGA (v' - psi)^2 dx      (closed form: EI / (h^3 (1 + Phi)) times
        [12, 6h, -12, 6h; 6h, (4 + Phi) h^2, -6h, (2 - Phi) h^2; ...])
    M = int_0^h rhoA v^2 + rhoI psi^2 dx             (consistent, with rotary inertia rhoI)
both integrated by 4-point Gauss quadrature, exact for these polynomials (degree <= 6).
Axial: linear, EA / h (1, -1; -1, 1), rhoA h / 6 (2, 1; 1, 2), as in ``link.py``.
"""

from __future__ import annotations

import functools

import numpy as np

_GAUSS_X, _GAUSS_W = np.polynomial.legendre.leggauss(4)
XI = (_GAUSS_X + 1.0) / 2.0  # points on [0, 1]
WEIGHTS = _GAUSS_W / 2.0


def shape_functions(xi: np.ndarray, h: float, phi: float):
    """(Nv, dNv, Npsi, dNpsi), each (4, len(xi)): the bending DOFs (v1, psi1, v2, psi2) -> v,
    dv/dx, psi, dpsi/dx at ``xi`` = x / h; h [m], phi the shear parameter [-]."""
    x = np.asarray(xi, dtype=float)
    c = 1.0 / (1.0 + phi)
    Nv = c * np.array([2 * x**3 - 3 * x**2 - phi * x + 1 + phi,
                       h * (x**3 - (2 + phi / 2) * x**2 + (1 + phi / 2) * x),
                       -2 * x**3 + 3 * x**2 + phi * x,
                       h * (x**3 - (1 - phi / 2) * x**2 - phi / 2 * x)])
    dNv = c / h * np.array([6 * x**2 - 6 * x - phi + 0 * x,
                            h * (3 * x**2 - (4 + phi) * x + 1 + phi / 2),
                            -6 * x**2 + 6 * x + phi,
                            h * (3 * x**2 - (2 - phi) * x - phi / 2)])
    Npsi = c * np.array([6 / h * (x**2 - x),
                         3 * x**2 - (4 + phi) * x + 1 + phi,
                         -6 / h * (x**2 - x),
                         3 * x**2 - (2 - phi) * x])
    dNpsi = c / h * np.array([6 / h * (2 * x - 1),
                              6 * x - (4 + phi),
                              -6 / h * (2 * x - 1),
                              6 * x - (2 - phi)])
    return Nv, dNv, Npsi, dNpsi


def element_matrices(h: float, EA: float, EI: float, kGA: float, rhoA: float, rhoI: float):
    """(K, M), 6 x 6, of one element of length h [m] in the DOF order (u1, v1, rz1, u2, v2, rz2).
    EA, kGA [N], EI [N m^2], rhoA [kg/m], rhoI [kg m]."""
    phi = 12.0 * EI / (kGA * h * h)
    Nv, dNv, Npsi, dNpsi = shape_functions(XI, h, phi)
    w = WEIGHTS * h
    gamma = dNv - Npsi
    kb = EI * (dNpsi * w) @ dNpsi.T + kGA * (gamma * w) @ gamma.T
    mb = rhoA * (Nv * w) @ Nv.T + rhoI * (Npsi * w) @ Npsi.T
    K, M = np.zeros((6, 6)), np.zeros((6, 6))
    axial, bending = [0, 3], [1, 2, 4, 5]
    K[np.ix_(axial, axial)] = EA / h * np.array([[1.0, -1.0], [-1.0, 1.0]])
    M[np.ix_(axial, axial)] = rhoA * h / 6.0 * np.array([[2.0, 1.0], [1.0, 2.0]])
    K[np.ix_(bending, bending)] = kb
    M[np.ix_(bending, bending)] = mb
    return K, M


@functools.lru_cache(maxsize=256)
def timoshenko_entries(length: float, elements: int, EA: float, EI: float, kGA: float,
                  rhoA: float, rhoI: float):
    """K and M of a uniform link of ``elements`` equal elements as one list of local entries
    (rows, cols, k_values, m_values), read-only; repeated (row, col) pairs sum. Units as in
    ``element_matrices``."""
    h = float(length) / int(elements)
    K, M = element_matrices(h, EA, EI, kGA, rhoA, rhoI)
    local = np.arange(6)
    shift = 3 * np.arange(int(elements))[:, None]
    rows = (np.repeat(local, 6)[None, :] + shift).ravel()
    cols = (np.tile(local, 6)[None, :] + shift).ravel()
    k = np.tile(K.ravel(), int(elements))
    m = np.tile(M.ravel(), int(elements))
    keep = (k != 0) | (m != 0)
    out = rows[keep], cols[keep], k[keep], m[keep]
    for a in out:
        a.flags.writeable = False
    return out


def twice_bending_energy(EI: float, kGA: float, h: float, a, b):
    """Twice the bending + shear strain energy of elements of length h [m] whose end rotations
    relative to their chord are ``a`` and ``b`` [rad]: EI / (h (1 + Phi)) ((4 + Phi)(a^2 + b^2)
    + 2 (2 - Phi) a b), the closed-form stiffness written without the cancellation of K."""
    phi = 12.0 * EI / (kGA * h * h)
    return EI / (h * (1.0 + phi)) * ((4.0 + phi) * (a * a + b * b) + 2.0 * (2.0 - phi) * a * b)
