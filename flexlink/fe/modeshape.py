"""Mode shapes between the nodes: each frame element sampled with its own shape functions.

An element of length h carries, per node, the axial displacement u, the transverse
displacement v and the rotation rz = dv/dx (local frame, see ``link.py``). Inside the element,
at xi = x / h in [0, 1], the finite-element solution is exactly
    u(xi) = (1 - xi) u1 + xi u2                                  (linear, P1)
    v(xi) = H1 v1 + h H2 rz1 + H3 v2 + h H4 rz2                  (Hermite cubic)
    H1 = 1 - 3 xi^2 + 2 xi^3,  H2 = xi - 2 xi^2 + xi^3,  H3 = 3 xi^2 - 2 xi^3,  H4 = xi^3 - xi^2
and the rotation between the nodes is the slope dv/dx = (dv/dxi) / h. Sampling these at a few
points per element draws the bent shape the solver actually computed, instead of straight
chords between nodes.

Points are numbered link by link, ``subdivisions`` segments per element; neighbouring elements of
a link share their common point, and the links' end points stay separate (as the model's nodes
do: joints are springs between coincident nodes).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.fe.assembly import node_rotation
from flexlink.fe.model import FrameModel


@dataclasses.dataclass(frozen=True)
class SampledShapes:
    """Mode shapes sampled along every element.

    points (P, 2) [m]: undeformed positions; cells (E, subdivisions + 1): point indices of each
    element from its first node to its second; cell_link (E,): index into ``link_names``;
    cell_element (E,): global element number (link by link, from each link's start);
    point_node (P,): model node at that point, -1 between nodes;
    displacement (P, 2, k) and rotation (P, k): the k shapes in global axes, in the units of the
    shape vectors given (mass-normalised shapes: m / sqrt(kg) and rad / sqrt(kg)).
    """

    points: np.ndarray
    cells: np.ndarray
    cell_link: np.ndarray
    cell_element: np.ndarray
    point_node: np.ndarray
    displacement: np.ndarray
    rotation: np.ndarray
    link_names: tuple[str, ...]

    @property
    def subdivisions(self) -> int:
        return self.cells.shape[1] - 1


def hermite_weights(xi: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
    """(W, dW) of shape (len(xi), 4): v(xi) = W @ (v1, rz1, v2, rz2), dv/dx = dW @ (same).

    ``h`` [m] is the element length (it scales the rotation terms)."""
    xi = np.asarray(xi, dtype=float)
    W = np.stack([1 - 3 * xi**2 + 2 * xi**3, h * (xi - 2 * xi**2 + xi**3),
                  3 * xi**2 - 2 * xi**3, h * (xi**3 - xi**2)], axis=1)
    dW = np.stack([-6 * xi + 6 * xi**2, h * (1 - 4 * xi + 3 * xi**2),
                   6 * xi - 6 * xi**2, h * (3 * xi**2 - 2 * xi)], axis=1) / h
    return W, dW


def sample_shapes(model: FrameModel, shapes: np.ndarray, subdivisions: int = 4) -> SampledShapes:
    """Sample ``shapes`` (3N, k), global DOFs (ux, uy, rz) per node, ``subdivisions`` segments
    per element (>= 1; 1 gives the nodes only)."""
    if subdivisions < 1:
        raise ValueError(f"subdivisions must be >= 1, got {subdivisions}")
    shapes = np.asarray(shapes, dtype=float)
    if shapes.ndim == 1:
        shapes = shapes[:, None]
    if shapes.shape[0] != model.n_dofs:
        raise ValueError(f"shapes have {shapes.shape[0]} rows, the model has {model.n_dofs} DOFs")
    k = shapes.shape[1]
    s = subdivisions
    xi = np.arange(s) / s  # each element contributes its first s points; the link adds its end
    points, disp, rot, node_of, cells, cell_link, cell_element = [], [], [], [], [], [], []
    n_points = n_elements = 0
    for link_index, link in enumerate(model.links):
        n_el = link.elements
        h = link.length / n_el
        R = node_rotation(link.angle)[:2, :2]  # global (ux, uy) -> local (u, v)
        nodal = shapes.reshape(-1, 3, k)[link.nodes]  # (n_el + 1, 3, k)
        local = np.einsum("ij,njk->nik", R, nodal[:, :2])  # (n_el + 1, 2, k): u, v
        u, v, rz = local[:, 0], local[:, 1], nodal[:, 2]
        W, dW = hermite_weights(xi, h)
        # element e, sample j: values from nodes e and e + 1
        bend = np.stack([v[:-1], rz[:-1], v[1:], rz[1:]], axis=1)  # (n_el, 4, k)
        v_s = np.einsum("jq,eqk->ejk", W, bend).reshape(-1, k)
        slope = np.einsum("jq,eqk->ejk", dW, bend).reshape(-1, k)
        u_s = ((1 - xi)[None, :, None] * u[:-1, None] + xi[None, :, None] * u[1:, None]).reshape(-1, k)
        # the link's end point: the last node itself
        v_s = np.vstack([v_s, v[-1:]])
        u_s = np.vstack([u_s, u[-1:]])
        slope = np.vstack([slope, rz[-1:]])
        local_s = np.stack([u_s, v_s], axis=1)  # (P_link, 2, k)
        disp.append(np.einsum("ji,pjk->pik", R, local_s))  # back to global: R^T
        rot.append(slope)
        xy = model.nodes[link.nodes]  # samples on nodes are the nodes themselves
        inner = xy[:-1, None, :] + xi[None, :, None] * (xy[1:] - xy[:-1])[:, None, :]
        points.append(np.vstack([inner.reshape(-1, 2), xy[-1:]]))
        node = np.full(n_el * s + 1, -1)
        node[::s] = link.nodes
        node_of.append(node)
        cells.append(n_points + np.arange(n_el)[:, None] * s + np.arange(s + 1)[None, :])
        cell_link.append(np.full(n_el, link_index))
        cell_element.append(n_elements + np.arange(n_el))
        n_points += n_el * s + 1
        n_elements += n_el
    return SampledShapes(points=np.vstack(points), cells=np.vstack(cells),
                         cell_link=np.concatenate(cell_link),
                         cell_element=np.concatenate(cell_element),
                         point_node=np.concatenate(node_of), displacement=np.vstack(disp),
                         rotation=np.vstack(rot), link_names=tuple(link.name for link in model.links))
