"""Co-rotational 2D frame element for large displacements and rotations with small strains
(Crisfield, "Non-linear Finite Element Analysis of Solids and Structures", vol. 1, ch. 7;
Battini's formulation of the planar Euler-Bernoulli element).

The element's rigid motion is carried by its chord; what is left, measured in the chord's
frame, is small and taken by the linear Euler-Bernoulli element. All functions act on e
elements at once.

DOF order per element (global): (u1, v1, rz1, u2, v2, rz2) [m, m, rad], the node
displacements from the initial, stress-free geometry ``X`` (e, 2, 2) [m] (node, xy), and the
node rotations from there (in the plane a rotation is additive, so rz is a total rotation).

Local (deformational) quantities, chord length L0 initially and L now, chord angle beta0 and
beta:
    u_l = L - L0                          (stretch)
    t1 = rz1 - (beta - beta0),  t2 = rz2 - (beta - beta0)   (end rotations from the chord,
                                                              wrapped to (-pi, pi])
    f_l = (N, m1, m2) = (EA u_l / L0, EI/L0 (4 t1 + 2 t2), EI/L0 (2 t1 + 4 t2))
with the element's strain energy  U = EA u_l^2 / (2 L0) + EI/L0 (2 t1^2 + 2 t1 t2 + 2 t2^2).
With c = cos beta, s = sin beta,
    r = (-c, -s, 0, c, s, 0),   z = (s, -c, 0, -s, c, 0),   d beta = z . du / L
    B = [r; (0, 0, 1, 0, 0, 0) - z / L; (0, 0, 0, 0, 0, 1) - z / L]
the internal force f = B^T f_l and the tangent stiffness
    K_t = B^T K_l B + N z z^T / L + (m1 + m2) (r z^T + z r^T) / L^2,
K_l the local stiffness [[EA/L0, 0, 0], [0, 4EI/L0, 2EI/L0], [0, 2EI/L0, 4EI/L0]].

Stress resultants at the element's ends (tension and sagging positive, M = EI v'' in the
chord frame): the end forces in the chord frame (``chord_end_forces``) read by
``fe.stress.end_resultants``, giving N at both ends and M = (-m1, m2).
"""

from __future__ import annotations

import dataclasses

import numpy as np


@dataclasses.dataclass(frozen=True)
class Chords:
    """Initial chords of e elements: L0 (e,) [m], beta0 (e,) [rad], EA (e,) [N], EI (e,)
    [N m^2]."""

    L0: np.ndarray
    beta0: np.ndarray
    EA: np.ndarray
    EI: np.ndarray

    def __post_init__(self):
        shapes = {np.shape(getattr(self, f.name)) for f in dataclasses.fields(self)}
        if len(shapes) != 1 or len(next(iter(shapes))) != 1:
            raise ValueError(f"Chords fields must share one shape (e,), got {shapes}")
        if not np.all(self.L0 > 0):
            raise ValueError("Chords.L0 must be positive")

    @classmethod
    def of(cls, X, EA, EI) -> Chords:
        """From the initial node positions ``X`` (e, 2, 2) [m] and the stiffnesses (e,)."""
        d = X[:, 1] - X[:, 0]
        e = len(X)
        return cls(np.hypot(d[:, 0], d[:, 1]), np.arctan2(d[:, 1], d[:, 0]),
                   np.broadcast_to(np.asarray(EA, float), (e,)).copy(),
                   np.broadcast_to(np.asarray(EI, float), (e,)).copy())


def _wrapped(angle):
    return np.mod(angle + np.pi, 2 * np.pi) - np.pi


@dataclasses.dataclass(frozen=True)
class ElementState:
    """What the elements carry at displacements u: local forces f_l (e, 3) = (N [N], m1, m2
    [N m]), chord length L (e,) [m] and angle beta (e,) [rad], r and z (e, 6), energy (e,) [J]."""

    f_local: np.ndarray
    L: np.ndarray
    beta: np.ndarray
    r: np.ndarray
    z: np.ndarray
    energy: np.ndarray


def element_state(chords: Chords, X, u) -> ElementState:
    """The elements' state at global displacements ``u`` (e, 6) from initial positions ``X``
    (e, 2, 2) [m]; see the module doc."""
    d = X[:, 1] - X[:, 0] + u[:, 3:5] - u[:, 0:2]
    L = np.hypot(d[:, 0], d[:, 1])
    c, s = d[:, 0] / L, d[:, 1] / L
    beta = np.arctan2(d[:, 1], d[:, 0])
    turn = _wrapped(beta - chords.beta0)
    t1, t2 = _wrapped(u[:, 2] - turn), _wrapped(u[:, 5] - turn)
    ul = L - chords.L0
    k = chords.EI / chords.L0
    f_local = np.stack([chords.EA * ul / chords.L0, k * (4 * t1 + 2 * t2),
                        k * (2 * t1 + 4 * t2)], axis=1)
    zero = np.zeros_like(c)
    r = np.stack([-c, -s, zero, c, s, zero], axis=1)
    z = np.stack([s, -c, zero, -s, c, zero], axis=1)
    energy = chords.EA * ul**2 / (2 * chords.L0) + 2 * k * (t1 * t1 + t1 * t2 + t2 * t2)
    return ElementState(f_local, L, beta, r, z, energy)


def _B(state: ElementState) -> np.ndarray:
    B = np.empty((len(state.L), 3, 6))
    B[:, 0] = state.r
    B[:, 1] = B[:, 2] = -state.z / state.L[:, None]
    B[:, 1, 2] += 1.0
    B[:, 2, 5] += 1.0
    return B


def internal_forces(state: ElementState) -> np.ndarray:
    """f = B^T f_l (e, 6) [N, N, N m, ...], global DOF order."""
    return np.einsum("eij,ei->ej", _B(state), state.f_local)


def tangent_stiffness(chords: Chords, state: ElementState) -> np.ndarray:
    """K_t (e, 6, 6) [N/m, N, N m/rad] in the global DOF order (module doc)."""
    B = _B(state)
    k = chords.EI / chords.L0
    Kl = np.zeros((len(k), 3, 3))
    Kl[:, 0, 0] = chords.EA / chords.L0
    Kl[:, 1, 1] = Kl[:, 2, 2] = 4 * k
    Kl[:, 1, 2] = Kl[:, 2, 1] = 2 * k
    r, z, L = state.r, state.z, state.L[:, None, None]
    N, m_sum = state.f_local[:, 0, None, None], (state.f_local[:, 1] + state.f_local[:, 2])
    rz = r[:, :, None] * z[:, None, :]
    return (np.einsum("eki,ekl,elj->eij", B, Kl, B) + N * z[:, :, None] * z[:, None, :] / L
            + m_sum[:, None, None] * (rz + np.swapaxes(rz, 1, 2)) / L**2)


def chord_end_forces(state: ElementState) -> np.ndarray:
    """The forces (e, 6) the nodes put on each element, in its chord frame, DOF order
    (u1, v1, rz1, u2, v2, rz2): (-N, V, m1, N, -V, m2), V = (m1 + m2) / L the shear that
    balances the end moments; ``fe.stress.end_resultants`` turns them into N and M."""
    N, m1, m2 = state.f_local.T
    V = (m1 + m2) / state.L
    return np.stack([-N, V, m1, N, -V, m2], axis=1)
