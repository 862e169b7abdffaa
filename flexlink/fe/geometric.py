"""Geometric (stress) stiffness K_g(N) of the 2D frame element under an axial force N.

An element carrying a tension N [N] (compression negative) stores the extra energy of its
transverse slope, (1/2) int_0^h N v'^2 dx, the quadratic part of the axial strain
u' + v'^2 / 2 times N. With v interpolated from the element's DOFs, v' = dNv^T q, that energy is
(1/2) q^T K_g q with K_g = N int_0^h dNv dNv^T dx (constant N over the element: the element's
mean axial force, see ``preload.axial_forces``). Two forms, both in the local DOF order
(u1, v1, rz1, u2, v2, rz2), zero in the axial rows:

"consistent": the cubic Hermite v of the Euler-Bernoulli element (Przemieniecki, Theory of
Matrix Structural Analysis, 1968, sec. 15; Cook et al., Concepts and Applications of FEA, 4th
ed., sec. 18.3), on (v1, rz1, v2, rz2):
    K_g = N / (30 h) [[ 36,   3h, -36,   3h],
                      [ 3h, 4h^2, -3h, -h^2],
                      [-36,  -3h,  36,  -3h],
                      [ 3h, -h^2, -3h, 4h^2]]
  For Timoshenko elements the same integral with that element's own v (``timoshenko.py``,
  interdependent interpolation with shear parameter Phi), by 4-point Gauss quadrature (exact:
  dNv is quadratic); at Phi = 0 it is the matrix above.

"string": the chord rotation only, v linear between the nodes, on (v1, v2):
    K_g = N / h [[1, -1], [-1, 1]]
  which is what OpenSees's PDelta coordinate transformation adds; offered so flexlink and
  OpenSees can be compared element for element. Both forms converge to the same limit as the
  mesh is refined (the string form at order h^2, missing the bending part of v').

The axial stretch term (1/2) N u'^2 is left out of both: it is N / EA of the axial stiffness.
"""

from __future__ import annotations

import enum
import functools

import numpy as np

from flexlink.fe.beams import shear_parameter
from flexlink.fe.chain import rotated_chain
from flexlink.fe.timoshenko import WEIGHTS, XI, shape_functions

BENDING = np.array([1, 2, 4, 5])


class GeometricForm(enum.StrEnum):
    """Which K_g: the element's own cubic v (``CONSISTENT``) or the chord only (``STRING``)."""

    CONSISTENT = "consistent"
    STRING = "string"


@functools.lru_cache(maxsize=256)
def unit_geometric_stiffness(h: float, form: GeometricForm, phi: float = 0.0) -> np.ndarray:
    """K_g / N, 6 x 6 [1/m], of one element of length h [m]; ``phi`` the Timoshenko shear
    parameter 12 EI / (kGA h^2) (0: Euler-Bernoulli). Read-only (cached)."""
    out = np.zeros((6, 6))
    if form is GeometricForm.STRING:
        out[np.ix_([1, 4], [1, 4])] = np.array([[1.0, -1.0], [-1.0, 1.0]]) / h
        out.flags.writeable = False
        return out
    if phi == 0.0:
        block = np.array([[36.0, 3 * h, -36.0, 3 * h],
                          [3 * h, 4 * h * h, -3 * h, -h * h],
                          [-36.0, -3 * h, 36.0, -3 * h],
                          [3 * h, -h * h, -3 * h, 4 * h * h]]) / (30.0 * h)
    else:
        _, dNv, _, _ = shape_functions(XI, h, phi)
        block = (dNv * (WEIGHTS * h)) @ dNv.T
    out[np.ix_(BENDING, BENDING)] = block
    out.flags.writeable = False
    return out


def geometric_stiffness(h: float, forces: np.ndarray, form: GeometricForm,
                        phi: float = 0.0) -> np.ndarray:
    """(e, 6, 6) K_g of elements of length h [m] under axial ``forces`` (e,) [N, tension > 0]."""
    return np.asarray(forces, dtype=float)[:, None, None] * unit_geometric_stiffness(h, form, phi)


def geometric_entries(model, forces, form: GeometricForm):
    """Global entries (rows, cols, values (E,)) of K_g for every link of ``model`` (a
    FrameModel), rotated to the pose; ``forces``: per link the (elements,) axial forces [N]."""
    mats = []
    for link, N in zip(model.links, forces):
        h = link.length / link.elements
        mats.append(geometric_stiffness(h, N, form, shear_parameter(link.section, h))[None])
    rows, cols, values = rotated_chain(model.links, mats)
    return rows, cols, values[0]
