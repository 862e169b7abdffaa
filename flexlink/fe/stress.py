"""Stress recovery of the in-plane frame: the normal stress at both extreme fibres of every
element end of every link, from the element's end forces.

Element end forces, local DOF order (u1, v1, rz1, u2, v2, rz2) as in ``link.py``:

    f_e = k_e T u_e - r_e

k_e the element's own stiffness in its section's beam theory (``beams.link_entries`` of one
element, so Euler-Bernoulli and Timoshenko alike), T the node rotation to the link frame
(``assembly.node_rotation``), u_e the element's global nodal displacements, and r_e the
element's own consistent load vector of the loads it carries between its nodes (the
d'Alembert loads of the rigid motion, ``preload.element_inertia_loads``). Without r_e the end
forces are those of an element loaded at its nodes only: for a rotating bar the axial force
would then be each element's mean, not its end values (an O(h) error); with it a 1D element's
end forces are exact wherever its nodal displacements are (linear axial, Hermite bending under
polynomial loads).

From the end forces, the stress resultants at the element's two ends (tension and sagging
positive, M = EI v''):

    N = (-f[0], f[3]),   M = (-f[2], f[5])

and the normal stress at the fibre y (measured along the link's local y, the in-plane normal):

    sigma(y) = N / A - M y / I,   at the extreme fibres y = +c and y = -c, c = depth / 2

(c = depth / 2 assumes a section symmetric about its centroidal axis: a rectangle or a tube;
a section given by area and second moment alone is taken so too). Shear stress (V Q / I b),
which vanishes at the extreme fibres, and stress concentrations at holes and pins are not
included.
"""

from __future__ import annotations

import functools

import numpy as np

from flexlink.fe.assembly import node_rotation
from flexlink.fe.beams import link_entries

FIBRES = (1.0, -1.0)  # y / c of the two extreme fibres: +y side first


@functools.lru_cache(maxsize=256)
def element_stiffness(h: float, section) -> np.ndarray:
    """k_e (6, 6) of one element of length h [m] in ``section``'s beam theory, local DOFs
    (u1, v1, rz1, u2, v2, rz2); read-only."""
    rows, cols, k, _ = link_entries(float(h), 1, section)
    out = np.zeros((6, 6))
    np.add.at(out, (rows, cols), k)
    out.flags.writeable = False
    return out


def element_displacements(link, u: np.ndarray) -> np.ndarray:
    """The local nodal displacements (e, 6, ...) of ``link``'s elements (a ``LinkMesh``) from
    the global ``u`` (n_dofs, ...) [m, rad]."""
    u = np.asarray(u, dtype=float)
    R = node_rotation(link.angle)
    nodal = u[3 * link.nodes[:, None] + np.arange(3)]  # (nodes, 3, ...)
    local = np.einsum("ij,nj...->ni...", R, nodal)
    return np.concatenate([local[:-1], local[1:]], axis=1)


def element_end_forces(model, u: np.ndarray, element_loads=None) -> tuple[np.ndarray, ...]:
    """Per link of ``model`` (a FrameModel) the end forces f_e = k_e T u_e - r_e (e, 6, ...)
    [N, N m] in the link frame, for global displacements ``u`` (n_dofs, ...); trailing axes of
    ``u`` (load cases, basis vectors) are kept. ``element_loads``: per link the consistent
    loads r_e (e, 6, ...) the elements carry between their nodes (None: none)."""
    out = []
    for i, link in enumerate(model.links):
        k = element_stiffness(link.length / link.elements, link.section)
        f = np.einsum("ij,ej...->ei...", k, element_displacements(link, u))
        if element_loads is not None:
            f = f - element_loads[i]
        out.append(f)
    return tuple(out)


def end_resultants(forces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(N, M) (e, 2, ...) at the start and end of each element from its end forces (e, 6, ...):
    axial force [N] tension positive, bending moment [N m] sagging positive (M = EI v'')."""
    N = np.stack([-forces[:, 0], forces[:, 3]], axis=1)
    M = np.stack([-forces[:, 2], forces[:, 5]], axis=1)
    return N, M


def fibre_stress(section, N: np.ndarray, M: np.ndarray) -> np.ndarray:
    """sigma (..., 2) [Pa] at the fibres y = +c and y = -c (``FIBRES``), c = depth / 2, of
    ``section`` carrying the axial force ``N`` [N] and bending moment ``M`` [N m] (same
    shapes): sigma = N / A - M y / I."""
    c = section.depth / 2.0
    axial = np.asarray(N, dtype=float) / section.area
    bending = np.asarray(M, dtype=float) * c / section.second_moment
    return np.stack([axial - f * bending for f in FIBRES], axis=-1)


def link_stresses(model, u: np.ndarray, element_loads=None) -> tuple[np.ndarray, ...]:
    """Per link the normal stress (e, 2 ends, ..., 2 fibres) [Pa] at both extreme fibres of
    every element end, for global displacements ``u`` (n_dofs, ...) and the elements' own
    loads ``element_loads`` (as ``element_end_forces``)."""
    out = []
    for link, f in zip(model.links, element_end_forces(model, u, element_loads)):
        N, M = end_resultants(f)
        out.append(fibre_stress(link.section, N, M))
    return tuple(out)


def end_positions(link) -> np.ndarray:
    """The distance [m] of each element end from the link's start joint, (e, 2)."""
    h = link.length / link.elements
    start = h * np.arange(link.elements)
    return np.stack([start, start + h], axis=1)


def fibre_offset(section) -> float:
    """c = depth / 2 [m]: the distance of the extreme fibres from the centroidal axis."""
    return section.depth / 2.0
