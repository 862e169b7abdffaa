"""Element matrices and assembly of the second model family: out-of-plane bending and St Venant
torsion of flat strip links (the scene-level driver is ``analysis.outofplane``).

A flat strip lying in the mechanism plane bends far more easily out of that plane (about its
weak axis, I = width thickness^3 / 12) and twists (St Venant, GJ) than it bends in plane. For a
linkage lying in one plane with doubly symmetric sections these motions decouple, to first
order, from the in-plane ones, so they form their own eigenproblem.

Global DOFs: node i owns 3i (w [m], out of plane), 3i+1 (rx [rad]), 3i+2 (ry [rad]), rotations
about the global in-plane axes. Local DOFs per node, link frame (x along the link, y in plane,
z out of plane): (w, tx, ty), tx = twist about the link axis, ty = rotation about local y.
A rotation ty about y moves a point at x along the link by -ty x in z, so dw/dx = -ty.

Element matrices (closed forms, Przemieniecki; Cook et al. "Concepts and Applications of FEA"),
element length l, DOF order (w1, w1', w2, w2') for bending and (tx1, tx2) for torsion:
    bending  K = EI/l^3 [[12, 6l, -12, 6l], [6l, 4l^2, -6l, 2l^2], [-12, -6l, 12, -6l],
                         [6l, 2l^2, -6l, 4l^2]]
             M = rhoA l/420 [[156, 22l, 54, -13l], [22l, 4l^2, 13l, -3l^2],
                             [54, 13l, 156, -22l], [-13l, -3l^2, -22l, 4l^2]]   (consistent)
    torsion  K = GJ/l [[1, -1], [-1, 1]],  M = rho Ip l/6 [[2, 1], [1, 2]]
with I = b t^3/12 (b = width, t = thickness), Ip = A (b^2 + t^2)/12 the polar second moment
of the section (rotary inertia per unit length rho Ip), and the thin-strip St Venant constant
J = b t^3/3 (1 - 0.63 t/b) (Roark, rectangle, b >= t). G is the laminate's in-plane shear
modulus, which governs the twisting of a thin strip.

Joints (bearing springs, between coincident link-end nodes or to ground, and the weld of a
welded ground joint, built by ``joints.springs_of_joints`` as for the planar model): the
translational stiffness Kt [N/m] resists w; a tilt stiffness Ktilt
[N m/rad] resists rx and ry (a pin or bearing whose axis is the plane normal resists being
tilted out of the plane). Scene keys: ``joints.Ktilt`` (or ``joints.<J>.Ktilt``), default
"rigid" (an ideal revolute joint transmits both bending moments); "rigid" is an exact
constraint (``assembly.rigid_elimination``). The drive acts about the plane normal, so it has no
out-of-plane part. Lumped joint masses act on w.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import scipy.sparse as sp

from flexlink.errors import InputError
from flexlink.fe.assembly import reduced_dense_pair, springs_stiffness_entries
from flexlink.fe.joints import JointDofs, Springs, joint_mass_entries
from flexlink.fe.model import FrameModel, Section

DOF_NAMES = ("w", "rx", "ry")
# out-of-plane joints: Kt on w, Ktilt on rx and ry; the drive acts about the plane normal only
OUT_OF_PLANE_JOINTS = JointDofs(bearing_labels=("w", "rx", "ry"), weld_labels=("w", "rx", "ry"),
                                drive_dof=None)


@dataclasses.dataclass(frozen=True)
class StripProperties:
    """Out-of-plane properties of a rectangular strip: EI [N m^2] (weak axis), GJ [N m^2],
    rhoA [kg/m], rhoIp [kg m] (rotary inertia about the strip axis per unit length)."""

    EI: float
    GJ: float
    rhoA: float
    rhoIp: float

    @classmethod
    def of(cls, s: Section) -> StripProperties:
        """From a ``Section.rectangle`` (in-plane depth = width b, thickness t = area / b)."""
        b = s.depth
        t = s.area / b
        thin, thick = min(b, t), max(b, t)
        J = thick * thin**3 / 3.0 * (1.0 - 0.63 * thin / thick)
        return cls(EI=s.E * b * t**3 / 12.0, GJ=s.G * J, rhoA=s.density * s.area,
                   rhoIp=s.density * s.area * (b * b + t * t) / 12.0)


# The module docstring's element matrices with the element length l factored out of the slope
# DOFs: DOF order (w1, w1', w2, w2'), (tx1, tx2); a bending entry carries one l per slope index
_BEND_K = np.array([[12, 6, -12, 6], [6, 4, -6, 2], [-12, -6, 12, -6], [6, 2, -6, 4]], float)
_BEND_M = np.array([[156, 22, 54, -13], [22, 4, 13, -3], [54, 13, 156, -22],
                    [-13, -3, -22, 4]], float)
_L_POWER = np.add.outer([0, 1, 0, 1], [0, 1, 0, 1])
_SLOPE_FLIP = np.outer([1.0, -1.0, 1.0, -1.0], [1.0, -1.0, 1.0, -1.0])  # (w, w') -> (w, ty)
_TWIST_K = np.array([[1, -1], [-1, 1]], float)
_TWIST_M = np.array([[2, 1], [1, 2]], float)
_BEND, _TWIST = np.array([0, 2, 3, 5]), np.array([1, 4])  # their local DOFs in the element


def _scaled(factor, pattern, l=None) -> np.ndarray:
    """``factor`` (scalar or (e,)) times ``pattern``, whose entries times l per ``_L_POWER``
    when ``l`` is given, (c l) l as the textbook form rounds them: (..., n, n)."""
    if l is not None:
        l = l[..., None, None]
        once = pattern * l
        pattern = np.where(_L_POWER == 0, pattern, np.where(_L_POWER == 1, once, once * l))
    return np.asarray(factor)[..., None, None] * pattern


def strip_element_matrices(l, p: StripProperties) -> tuple[np.ndarray, np.ndarray]:
    """Local (K, M) of elements of length ``l`` [m], DOF order (w1, tx1, ty1, w2, tx2, ty2):
    6 x 6 each for a scalar ``l``, (e, 6, 6) for lengths (e,) and ``p`` fields scalar or (e,)."""
    l = np.asarray(l, dtype=float)
    k, m = np.zeros(l.shape + (6, 6)), np.zeros(l.shape + (6, 6))
    # l^3 by libm's pow, as a Python float's l**3: np.power's SIMD loop rounds 5 % of cubes
    # differently, and the unrefined out-of-plane frequencies pass that on at up to 2e-9
    l3 = np.float_power(l, 3)
    # w' = -ty: the slope rows and columns change sign
    k[..., _BEND[:, None], _BEND] = _scaled(p.EI / l3, _BEND_K, l) * _SLOPE_FLIP
    m[..., _BEND[:, None], _BEND] = _scaled(p.rhoA * l / 420, _BEND_M, l) * _SLOPE_FLIP
    k[..., _TWIST[:, None], _TWIST] = _scaled(p.GJ / l, _TWIST_K)
    m[..., _TWIST[:, None], _TWIST] = _scaled(p.rhoIp * l / 6, _TWIST_M)
    return k, m


def strip_chain_matrices(length: float, elements: int, p: StripProperties):
    """Local (K, M) of a uniform link of ``elements`` equal elements, size 3 (elements + 1)."""
    k, m = strip_element_matrices(length / elements, p)
    n = 3 * (elements + 1)
    K, M = np.zeros((n, n)), np.zeros((n, n))
    for e in range(elements):
        sl = slice(3 * e, 3 * e + 6)
        K[sl, sl] += k
        M[sl, sl] += m
    return K, M


def strip_node_rotation(angle) -> np.ndarray:
    """R with local (w, tx, ty) = R @ global (w, rx, ry) for a link at ``angle`` [rad]: 3 x 3,
    or (e, 3, 3) for angles (e,)."""
    angle = np.asarray(angle, dtype=float)
    c, s = np.cos(angle), np.sin(angle)
    zero, one = np.zeros_like(c), np.ones_like(c)
    R = np.array([[one, zero, zero], [zero, c, s], [zero, -s, c]])
    return np.moveaxis(R, (0, 1), (-2, -1))


def link_strips(model: FrameModel) -> tuple[StripProperties, ...]:
    """``StripProperties`` of each of ``model``'s links, in link order."""
    return tuple(StripProperties.of(link.section) for link in model.links)


def strip_entries(model: FrameModel, strips: tuple[StripProperties, ...]):
    """Every element's (K, M) in the global (w, rx, ry) DOFs as entries, all elements at once:
    (rows, cols (36 e,), values (2, 36 e) = K and M); repeated (row, col) pairs are to be summed.
    ``strips``: ``link_strips(model)``. Links own consecutive node ranges (``build_model``)."""
    links = model.links
    props = StripProperties(*(np.array([getattr(p, f.name) for p in strips])
                              for f in dataclasses.fields(StripProperties)))
    k, m = strip_element_matrices(np.array([link.length / link.elements for link in links]),
                                  props)
    T = np.zeros(k.shape)
    T[:, :3, :3] = T[:, 3:, 3:] = strip_node_rotation(np.array([link.angle for link in links]))
    Tt = np.swapaxes(T, 1, 2)
    # a link's elements are equal: one rotated element per link, repeated along its chain
    counts = np.array([link.elements for link in links])
    values = np.repeat(np.stack([Tt @ k @ T, Tt @ m @ T]), counts, axis=1)  # (2, e, 6, 6)
    first_element = np.cumsum(counts) - counts
    node = np.arange(counts.sum()) + np.repeat(
        np.array([link.first_node for link in links]) - first_element, counts)
    dofs = 3 * node[:, None] + np.arange(6)  # (e, 6): the element's two nodes
    rows = np.broadcast_to(dofs[:, :, None], values.shape[1:]).ravel()
    cols = np.broadcast_to(dofs[:, None, :], values.shape[1:]).ravel()
    return rows, cols, values.reshape(2, -1)


def out_of_plane_stiffness(joint, tilt) -> tuple[float, float, float]:
    """A joint's bearing stiffness on (w, rx, ry): Kt [N/m], then its Ktilt [N m/rad] from
    ``tilt`` (joint name -> Ktilt) twice. InputError for a Ktilt that is not >= 0 (NaN
    included), as the scene's reader refuses it."""
    k = tilt[joint.name]
    if not k >= 0:
        raise InputError(f"must be >= 0, got {k!r}", source=f"joint {joint.name}", field="Ktilt",
                         expected="N*m/rad, >= 0")
    return joint.Kt, k, k


def strip_mass_entries(model: FrameModel):
    """(rows, cols, values) of the lumped joint masses [kg], on w only."""
    return joint_mass_entries(model.point_masses, (0,))


def assemble_out_of_plane(model: FrameModel, springs: Springs):
    """(K, M) CSR of the out-of-plane problem on ``model``'s mesh, not reduced."""
    k_blocks, m_blocks = [], []
    for link in model.links:
        K, M = strip_chain_matrices(link.length, link.elements, StripProperties.of(link.section))
        T = np.kron(np.eye(link.elements + 1), strip_node_rotation(link.angle))
        k_blocks.append(T.T @ K @ T)
        m_blocks.append(T.T @ M @ T)
    K = sp.block_diag(k_blocks, format="csr")
    M = sp.block_diag(m_blocks, format="csr")
    rows, cols, vals = springs_stiffness_entries(springs)
    n = model.n_dofs
    K = K + sp.coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsr()
    if model.point_masses:
        rows, cols, vals = strip_mass_entries(model)
        M = M + sp.coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsr()
    return K, M


def assemble_out_of_plane_reduced_dense(model: FrameModel, springs: Springs, T,
                                        strips: tuple[StripProperties, ...]):
    """Dense (T^T K T, T^T M T) of ``assemble_out_of_plane``'s K and M, with T from
    ``assembly.rigid_elimination`` and ``strips`` = ``link_strips(model)``, scattered straight from the
    element entries (no sparse matrix built): for the small models the dense eigen solver
    takes, where scipy.sparse's bookkeeping costs more than the solve."""
    rows, cols, values = strip_entries(model, strips)
    s_rows, s_cols, s_vals = springs_stiffness_entries(springs)
    m_rows, m_cols, m_vals = strip_mass_entries(model)
    return reduced_dense_pair(
        T, model.n_dofs,
        (np.concatenate([rows, s_rows]), np.concatenate([cols, s_cols]),
         np.concatenate([values[0], s_vals])),
        (np.concatenate([rows, m_rows]), np.concatenate([cols, m_cols]),
         np.concatenate([values[1], m_vals])))


def out_of_plane_eigen_scale(model: FrameModel, strips=None) -> float:
    """Smallest weak-axis bending or torsion eigenvalue scale of the links [rad^2/s^2].
    ``strips``: ``link_strips(model)``, if the caller has them."""
    scales = []
    for link, p in zip(model.links, strips or link_strips(model)):
        scales += [p.EI / (p.rhoA * link.length**4), p.GJ / (p.rhoIp * link.length**2)]
    return min(scales)


def strip_stiffness_scale(model: FrameModel, strips=None) -> tuple[float, float]:
    """(translational [N/m], rotational [N m/rad]) stiffness of the stiffest out-of-plane
    element: 12 EI / h^3 on w; 4 EI / h (bending) or GJ / h (twist) on a rotation.
    ``strips``: ``link_strips(model)``, if the caller has them."""
    trans, rot = 0.0, 0.0
    for link, p in zip(model.links, strips or link_strips(model)):
        h = link.length / link.elements
        trans = max(trans, 12 * p.EI / h**3)
        rot = max(rot, 4 * p.EI / h, p.GJ / h)
    return trans, rot
