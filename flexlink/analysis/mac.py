"""The modal assurance criterion (MAC) between two sets of mode shapes, and pairing by it.

    MAC(a, b) = (a^T W b)^2 / ((a^T W a) (b^T W b))

is 1 for shapes that are multiples of each other and 0 for W-orthogonal ones; it ignores sign
and scale. With W the mass matrix, a mass-orthonormal set compared with itself gives exactly
the identity.

Shapes of two models are compared in each link's own frame (axial u, transverse v along the
link), so the comparison does not depend on the pose:
  - same topology and mesh (neighbouring poses of a cycle): the nodal (u, v, rz) of every link
    and joint node (``link_frame``), weighted by the pose-independent local mass;
  - different meshes or scenes with the same link names: u and v sampled at the same fractions
    of each link's length (``stations``) with the element shape functions, weighted by the
    link's mass per station (a trapezoid rule of rhoA).

Only shapes of one model family can be compared. The in-plane family's DOFs are (ux, uy, rz)
per node and the out-of-plane family's (w, rx, ry) (``fe/strip.py``): different motions, not
two views of one, so a MAC between the families would mean nothing. ``compare_models`` takes
the family: "in-plane" samples (u, v) as above; "out-of-plane" samples, in each link's frame,
the deflection w (Hermite cubic of w and w' = -ty) weighted by the link's mass per station and
the twist tx (linear between nodes) weighted by its rotary inertia rho Ip per station, so the
weighted sum is the kinetic energy of the shape's velocities (``out_of_plane_stations``).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import scipy.sparse as sp

from flexlink.errors import InputError
from flexlink.fe.model import FrameModel
from flexlink.fe.modeshape import hermite_weights
from flexlink.fe.motions import Part

STATIONS = 20  # segments per link for comparing different meshes


def mac_matrix(A: np.ndarray, B: np.ndarray, W=None) -> np.ndarray:
    """(k_a, k_b) MAC of the columns of ``A`` against those of ``B`` (same rows), weighted by
    the symmetric positive semi-definite ``W`` (identity when None)."""
    A, B = np.asarray(A, dtype=float), np.asarray(B, dtype=float)
    WB = B if W is None else W @ B
    WA = A if W is None else W @ A
    cross = A.T @ WB
    return cross**2 / np.outer(np.einsum("ij,ij->j", A, WA), np.einsum("ij,ij->j", B, WB))


@dataclasses.dataclass(frozen=True)
class Pairing:
    """Column ``a[i]`` of the first set pairs with column ``b[i]`` of the second, MAC ``mac[i]``."""

    a: np.ndarray
    b: np.ndarray
    mac: np.ndarray


def pair_modes(mac: np.ndarray) -> Pairing:
    """The one-to-one pairing of rows and columns of ``mac`` with the largest total MAC
    (Hungarian algorithm), in row order."""
    from scipy.optimize import linear_sum_assignment

    rows, cols = linear_sum_assignment(-np.asarray(mac))
    return Pairing(rows, cols, np.asarray(mac)[rows, cols])


def link_frame(model: FrameModel, shapes: np.ndarray) -> np.ndarray:
    """``shapes`` (n_dofs, k) with every node's (ux, uy) turned into its link's (u, v)."""
    U = np.array(shapes, dtype=float).reshape(model.n_dofs, -1)
    for link in model.links:
        c, s = math.cos(link.angle), math.sin(link.angle)
        ux, uy = U[3 * link.nodes].copy(), U[3 * link.nodes + 1].copy()
        U[3 * link.nodes], U[3 * link.nodes + 1] = c * ux + s * uy, -s * ux + c * uy
    return U


def link_frame_mass(model: FrameModel) -> sp.csr_matrix:
    """The consistent mass in link frames: block diagonal of the links' local matrices plus the
    joint masses (isotropic, so unchanged). The same at every pose of one topology."""
    blocks = sp.block_diag([link.local_matrices()[1] for link in model.links], format="lil")
    for node, mass in model.point_masses:
        blocks[3 * node, 3 * node] += mass
        blocks[3 * node + 1, 3 * node + 1] += mass
    return blocks.tocsr()


def stations(model: FrameModel, shapes: np.ndarray, per_link: int = STATIONS):
    """(values (links * (per_link + 1) * 2, k), weights (same rows,), link names): u and v
    [shape units] in each link's frame at ``per_link + 1`` equally spaced fractions of its
    length, from the element shape functions, and the link mass [kg] each station stands for."""
    U = link_frame(model, shapes)
    values, weights = [], []
    for link in model.links:
        n, h = link.elements, link.length / link.elements
        where = np.linspace(0.0, n, per_link + 1)
        element = np.minimum(where.astype(int), n - 1)
        xi = where - element
        first, second = link.nodes[element], link.nodes[element + 1]
        u = (1 - xi)[:, None] * U[3 * first] + xi[:, None] * U[3 * second]
        W, _ = hermite_weights(xi, h)
        v = (W[:, 0:1] * U[3 * first + 1] + W[:, 1:2] * U[3 * first + 2]
             + W[:, 2:3] * U[3 * second + 1] + W[:, 3:4] * U[3 * second + 2])
        mass = np.full(per_link + 1, link.section.mass_per_length * link.length / per_link)
        mass[[0, -1]] /= 2
        values += [u, v]
        weights += [mass, mass]
    return np.vstack(values), np.concatenate(weights), tuple(l.name for l in model.links)


def _station_places(link, per_link: int):
    """(element, xi, station weight fraction) of ``per_link`` + 1 equally spaced stations."""
    n = link.elements
    where = np.linspace(0.0, n, per_link + 1)
    element = np.minimum(where.astype(int), n - 1)
    share = np.full(per_link + 1, 1.0 / per_link)  # trapezoid rule along the link
    share[[0, -1]] /= 2
    return element, where - element, share


def out_of_plane_stations(model: FrameModel, shapes: np.ndarray, per_link: int = STATIONS):
    """(values, weights, link names) as ``stations``, for out-of-plane shapes (n_dofs, k) with
    global (w, rx, ry) per node (``fe/strip.py``): per link the deflection w [shape units]
    at ``per_link`` + 1 stations weighted by the link mass [kg] each stands for, and the twist
    tx about the link axis [shape units] weighted by its rotary inertia [kg m^2]."""
    from flexlink.fe.strip import StripProperties

    U = np.asarray(shapes, dtype=float).reshape(model.n_dofs, -1)
    values, weights = [], []
    for link in model.links:
        c, s = math.cos(link.angle), math.sin(link.angle)
        tx = c * U[3 * link.nodes + 1] + s * U[3 * link.nodes + 2]
        ty = -s * U[3 * link.nodes + 1] + c * U[3 * link.nodes + 2]
        element, xi, share = _station_places(link, per_link)
        first, second = element, element + 1  # positions along the link's own node chain
        W, _ = hermite_weights(xi, link.length / link.elements)
        w_nodes = U[3 * link.nodes]
        w = (W[:, 0:1] * w_nodes[first] - W[:, 1:2] * ty[first]
             + W[:, 2:3] * w_nodes[second] - W[:, 3:4] * ty[second])  # w' = -ty
        twist = (1 - xi)[:, None] * tx[first] + xi[:, None] * tx[second]
        strip = StripProperties.of(link.section)
        values += [w, twist]
        weights += [strip.rhoA * link.length * share, strip.rhoIp * link.length * share]
    return np.vstack(values), np.concatenate(weights), tuple(l.name for l in model.links)


PART_STATIONS = {Part.IN_PLANE: stations, Part.OUT_OF_PLANE: out_of_plane_stations}


def compare_models(model_a: FrameModel, shapes_a: np.ndarray, model_b: FrameModel,
                   shapes_b: np.ndarray, per_link: int = STATIONS,
                   part: Part = Part.IN_PLANE) -> np.ndarray:
    """MAC of the modes of two models with the same link names (any meshes, poses, sections),
    compared at link stations weighted by the first model's link masses (and, out of plane,
    rotary inertias). ``part``: IN_PLANE (``stations``) or OUT_OF_PLANE
    (``out_of_plane_stations``); both shape sets must be of that part."""
    sample = PART_STATIONS[part]
    va, wa, names_a = sample(model_a, shapes_a, per_link)
    vb, _, names_b = sample(model_b, shapes_b, per_link)
    if names_a != names_b:
        raise InputError(f"the two models have different links ({', '.join(names_a)} vs "
                         f"{', '.join(names_b)}): MAC compares shapes link by link",
                         field="links", expected="the same link names in the same order")
    return mac_matrix(va, vb, sp.diags(wa))


def complex_mac(static_shapes: np.ndarray, shapes: np.ndarray, M) -> np.ndarray:
    """(k_static, k) MAC of real static shapes against complex ones, mass weighted:
    |phi^T M x|^2 / ((phi^T M phi)(x^H M x))."""
    MP, MX = M @ static_shapes, M @ shapes
    cross = np.abs(static_shapes.T @ MX) ** 2
    return cross / np.outer(np.einsum("ij,ij->j", static_shapes, MP),
                            np.einsum("ij,ij->j", shapes.conj(), MX).real)
