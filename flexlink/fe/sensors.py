"""Sensors on a frame model: where a measured point sits on the links, and the model's
displacement there along a measuring direction, as one linear operator on the mode shapes.

A point (x, y) [m] in the mechanism plane is placed on the link whose axis passes nearest to
it: the foot of the perpendicular on the segment from the link's start to its end (clamped to
the ends), the element holding the foot and the foot's place xi = x / h in that element, and
the in-plane offset r = point - foot of the point from the axis. A point farther than
``max_distance`` from every link is refused, naming it.

The displacement at the point is the element's own interpolation of its nodal DOFs (the
interpolation the solver's element matrices are built on), carried to the point as a rigid
cross-section:

  in plane (DOFs ux, uy, rz per node, ``model.py``): axial u linear between the nodes;
    transverse v and the section rotation by the link's beam theory: Hermite cubics with the
    slope dv/dx as rotation (Euler-Bernoulli, ``modeshape.hermite_weights``), or the
    interdependent cubic v and quadratic psi (Timoshenko, ``timoshenko.shape_functions``);
    then  d_point = d_axis + rz e_z x r;
  out of plane (DOFs w, rx, ry per node, ``strip.py``): deflection w by Hermite cubics of
    (w, w' = -ty), twist tx linear; then  w_point = w_axis + (t x r)_z = w + tx r_y - ty r_x
    in the link frame.

A channel is one point and one unit direction (dx, dy, dz) in the scene frame; its reading is
dx ux + dy uy (in plane) or dz w (out of plane). ``channel_operator`` returns the matrix S
(channels, n_dofs) with readings = S @ shapes, so any set of mode shapes is sampled by one
product, and the two parts of a "3d" family by their own operators.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexlink.errors import InputError
from flexlink.fe.beams import BeamTheory
from flexlink.fe.model import FrameModel
from flexlink.fe.modeshape import hermite_weights
from flexlink.fe.motions import Part
from flexlink.fe.timoshenko import shape_functions


@dataclasses.dataclass(frozen=True)
class Placement:
    """Points placed on a model's links, one row each: ``link`` (index into model.links),
    ``element`` (0-based within that link), ``xi`` in [0, 1] in that element, ``foot`` (P, 2)
    [m] on the link's axis, ``offset`` (P, 2) [m] from the foot to the point, ``distance``
    (P,) [m] = |offset|, ``fraction`` (P,) of the link's length from its start."""

    link: np.ndarray
    element: np.ndarray
    xi: np.ndarray
    foot: np.ndarray
    offset: np.ndarray
    distance: np.ndarray
    fraction: np.ndarray

    def __post_init__(self):
        n = len(self.link)
        for name in ("element", "xi", "distance", "fraction"):
            if np.shape(getattr(self, name)) != (n,):
                raise ValueError(f"Placement.{name} has shape {np.shape(getattr(self, name))}, "
                                 f"expected ({n},)")
        for name in ("foot", "offset"):
            if np.shape(getattr(self, name)) != (n, 2):
                raise ValueError(f"Placement.{name} has shape {np.shape(getattr(self, name))}, "
                                 f"expected ({n}, 2)")


def nearest_on_links(model: FrameModel, points: np.ndarray):
    """(link index, fraction in [0, 1], foot (P, 2) [m], distance (P,) [m]) of each point's
    nearest place on the links' axes."""
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    starts = np.array([model.nodes[l.first_node] for l in model.links])
    ends = np.array([model.nodes[l.first_node + l.elements] for l in model.links])
    axis = ends - starts  # (L, 2)
    length2 = np.einsum("lk,lk->l", axis, axis)
    rel = points[:, None, :] - starts[None, :, :]  # (P, L, 2)
    t = np.clip(np.einsum("plk,lk->pl", rel, axis) / length2, 0.0, 1.0)
    feet = starts[None] + t[..., None] * axis[None]
    dist = np.linalg.norm(points[:, None, :] - feet, axis=2)
    best = np.argmin(dist, axis=1)  # a joint's coincident link ends: the first link listed
    rows = np.arange(len(points))
    return best, t[rows, best], feet[rows, best], dist[rows, best]


def place_points(model: FrameModel, points: np.ndarray, names, max_distance: float,
                 source: str | None = None) -> Placement:
    """``points`` (P, 2) [m] placed on the nearest link; a point farther than
    ``max_distance`` [m] from every link's axis raises InputError naming it (``names``: one
    label per point, ``source``: the file the points came from)."""
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    link, t, foot, dist = nearest_on_links(model, points)
    far = np.flatnonzero(dist > max_distance)
    if far.size:
        i = int(far[0])
        name = model.links[int(link[i])].name
        others = f" (and {far.size - 1} more)" if far.size > 1 else ""
        raise InputError(f"at ({points[i, 0] * 1e3:.4g}, "
                         f"{points[i, 1] * 1e3:.4g}) mm is {dist[i] * 1e3:.4g} mm from the "
                         f"nearest link ({name}): off every link{others}", source=source,
                         field=f"sensor {names[i]}",
                         expected=f"within test.max_distance = {max_distance * 1e3:.4g} mm of "
                                  "a link's axis, in the scene's frame after [test] offset and "
                                  "rotation")
    elements = np.array([model.links[k].elements for k in link])
    where = t * elements
    element = np.minimum(np.floor(where).astype(int), elements - 1)
    return Placement(link=link, element=element, xi=where - element, foot=foot,
                     offset=points - foot, distance=dist, fraction=t)


def _bending_weights(link, xi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(v weights, rotation weights), each (n, 4) on the local (v1, rz1, v2, rz2), by the
    link's beam theory."""
    h = link.length / link.elements
    section = link.section
    if section.beam is BeamTheory.TIMOSHENKO:
        phi = 12.0 * section.EI / (section.kGA * h * h)
        Nv, _, Npsi, _ = shape_functions(xi, h, phi)
        return Nv.T, Npsi.T
    return hermite_weights(xi, h)


def _in_plane_rows(model: FrameModel, placement: Placement, point: np.ndarray,
                   direction: np.ndarray) -> np.ndarray:
    S = np.zeros((len(point), model.n_dofs))
    for c, (p, d) in enumerate(zip(point, direction)):
        link = model.links[int(placement.link[p])]
        cos, sin = math.cos(link.angle), math.sin(link.angle)
        xi = np.array([placement.xi[p]])
        W, R = (w[0] for w in _bending_weights(link, xi))
        along = d[0] * cos + d[1] * sin  # direction along the link axis (local u)
        across = -d[0] * sin + d[1] * cos  # along local v
        ox, oy = placement.offset[p]
        turn = d[1] * ox - d[0] * oy  # reading per unit section rotation: (e_z x r) . d
        first = link.first_node + int(placement.element[p])
        for k, node in enumerate((first, first + 1)):
            axial = (1.0 - xi[0]) if k == 0 else xi[0]
            lateral = across * W[2 * k] + turn * R[2 * k]  # per unit local v of the node
            S[c, 3 * node] += along * axial * cos - lateral * sin
            S[c, 3 * node + 1] += along * axial * sin + lateral * cos
            S[c, 3 * node + 2] += across * W[2 * k + 1] + turn * R[2 * k + 1]
    return S


def _out_of_plane_rows(model: FrameModel, placement: Placement, point: np.ndarray,
                       direction: np.ndarray) -> np.ndarray:
    S = np.zeros((len(point), model.n_dofs))
    for c, (p, d) in enumerate(zip(point, direction)):
        if d[2] == 0:
            continue
        link = model.links[int(placement.link[p])]
        cos, sin = math.cos(link.angle), math.sin(link.angle)
        xi = placement.xi[p]
        W, dW = (w[0] for w in hermite_weights(np.array([xi]), link.length / link.elements))
        ox, oy = placement.offset[p]
        lx, ly = cos * ox + sin * oy, -sin * ox + cos * oy  # offset in the link frame
        first = link.first_node + int(placement.element[p])
        for k, node in enumerate((first, first + 1)):
            # w_point = w - ty lx with w' = -ty: lx is 0 inside a link (the foot of the
            # perpendicular) and, past an end, the nodal w's own share of w' vanishes there
            on_w = W[2 * k]
            on_ty = -(W[2 * k + 1] + lx * dW[2 * k + 1])
            on_tx = ly * ((1.0 - xi) if k == 0 else xi)
            S[c, 3 * node] += d[2] * on_w
            S[c, 3 * node + 1] += d[2] * (on_tx * cos - on_ty * sin)
            S[c, 3 * node + 2] += d[2] * (on_tx * sin + on_ty * cos)
    return S


PART_ROWS = {Part.IN_PLANE: _in_plane_rows, Part.OUT_OF_PLANE: _out_of_plane_rows}


def channel_operator(part: Part, model: FrameModel, placement: Placement, point, direction
                     ) -> np.ndarray:
    """S (channels, model.n_dofs): the reading of channel c, at placed point ``point[c]``
    along the unit ``direction[c]`` (dx, dy, dz) in the scene frame, is S[c] @ shape for a
    shape of ``part`` on ``model``. Readings in the shapes' units."""
    point = np.asarray(point, dtype=int)
    direction = np.asarray(direction, dtype=float).reshape(-1, 3)
    if len(point) != len(direction):
        raise ValueError(f"{len(point)} channel points for {len(direction)} directions")
    return PART_ROWS[part](model, placement, point, direction)
