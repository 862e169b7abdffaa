"""Test planning: where to put N sensors on a scene's links so that its M lowest modes can be
measured and told apart, by Effective Independence (``analysis.effective_independence``).

Candidates are stations along every link's axis (``stations`` segments per link, its ends
left out: a joint is two links' ends, and a ground pivot barely moves), each with the
directions the scene's family moves: in plane along the link (axial) and across it
(transverse), out of plane (z). Their readings of the target modes (mass-normalised, by the
element interpolation, ``fe.sensors``) are Phi; Effective Independence keeps ``count`` of
them.

The comparison is a uniform layout of the same count: points evenly spaced over the links'
total length, from the first link's start to the last link's end (so the joints, ground
pivots included, get sensors, as a layout drawn by hand does), each measuring across its link
(in plane) or out of the plane (out-of-plane family; alternately for "3d"). Both are judged by
the autoMAC of the target modes (largest off-diagonal value: how alike two modes look to the
sensors) and the determinant of the Fisher information det(Phi^T Phi) for unit sensor noise
(how well the modal coordinates are determined).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexlink.analysis.correlation import correlate
from flexlink.analysis.effective_independence import effective_independence, fisher_determinant
from flexlink.fe.motions import Part
from flexlink.fe.sensors import Placement
from flexlink.scene import Scene
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.correlation.correlation import ModelModes, model_modes


UNSEEN = 1e-4  # a mode reading below this share of the layout's largest reading goes unseen:
# about a test channel's resolution of its full scale, and far above the mesh's interpolation
# error at a nodal point (2e-7 of the peak for a 40-element beam's third mode)


class Direction:
    """Names of a candidate's measuring direction."""

    AXIAL = "axial"
    TRANSVERSE = "transverse"
    OUT_OF_PLANE = "z"


@dataclasses.dataclass(frozen=True)
class Layout:
    """Sensor channels on the links: ``points`` (N, 2) [m] in the scene's frame, ``link``
    (N,) index into the model's links, ``fraction`` (N,) of that link's length,
    ``directions`` (N, 3) unit vectors in the scene's frame, ``kinds`` (N,) their names,
    ``readings`` (N, M) of the target modes; ``auto_mac`` (M, M) their autoMAC (NaN rows
    for unseen modes), ``max_auto_mac`` its largest off-diagonal value among the modes seen,
    ``unseen`` the target modes reading (about) zero at every channel, which no layout
    measures, ``fisher`` det(Phi^T Phi) [(m^2/kg)^M] (about 0 with a mode unseen)."""

    points: np.ndarray
    link: np.ndarray
    fraction: np.ndarray
    directions: np.ndarray
    kinds: tuple[str, ...]
    readings: np.ndarray
    auto_mac: np.ndarray
    max_auto_mac: float
    unseen: tuple[int, ...]
    fisher: float
    placement: Placement

    def __post_init__(self):
        n = len(self.kinds)
        check_shape("Layout", "points", self.points, (n, 2))
        check_shape("Layout", "directions", self.directions, (n, 3))
        check_shape("Layout", "readings", self.readings, (n, None))


@dataclasses.dataclass(frozen=True)
class SensorPlan:
    """The Effective Independence layout (``chosen``) and the uniform one of the same count,
    for the ``target`` modes (frequencies [Hz] and labels of ``modes``)."""

    scene: Scene | None
    modes: ModelModes
    count: int
    candidates: int
    chosen: Layout
    uniform: Layout


def _stations(model, per_link: int, ends: bool):
    """(points, link index, fraction, Placement) of stations along every link's axis."""
    points, link, fraction, element, xi = [], [], [], [], []
    t = np.linspace(0.0, 1.0, per_link + 1)
    t = t if ends else t[1:-1]
    for k, l in enumerate(model.links):
        start, end = model.nodes[l.first_node], model.nodes[l.first_node + l.elements]
        where = t * l.elements
        e = np.minimum(np.floor(where).astype(int), l.elements - 1)
        points += list(start + t[:, None] * (end - start))
        link += [k] * len(t)
        fraction += list(t)
        element += list(e)
        xi += list(where - e)
    points = np.array(points)
    placement = Placement(np.array(link), np.array(element), np.array(xi), points,
                          np.zeros_like(points), np.zeros(len(points)), np.array(fraction))
    return points, np.array(link), np.array(fraction), placement


def _directions(model, link: int, kind: str) -> np.ndarray:
    angle = model.links[link].angle
    if kind == Direction.AXIAL:
        return np.array([math.cos(angle), math.sin(angle), 0.0])
    if kind == Direction.TRANSVERSE:
        return np.array([-math.sin(angle), math.cos(angle), 0.0])
    return np.array([0.0, 0.0, 1.0])


def _read(modes: ModelModes, placement: Placement, point, directions) -> np.ndarray:
    """(channels, M) the target modes read at ``point`` (indices into ``placement``) along
    ``directions`` (channels, 3)."""
    from flexlink.fe.sensors import channel_operator

    out = np.zeros((len(point), len(modes.frequencies)))
    operators = {}
    for mode in range(len(modes.frequencies)):
        part, shape = modes.shape(mode)
        if part.part not in operators:
            operators[part.part] = channel_operator(part.part, part.model, placement, point,
                                                    directions)
        out[:, mode] = operators[part.part] @ shape
    return out


def _layout(modes, placement, points, link, fraction, point, kinds, model) -> Layout:
    directions = np.array([_directions(model, int(link[p]), kind) for p, kind in zip(point, kinds)])
    readings = _read(modes, placement, point, directions)
    seen = np.any(np.abs(readings) > UNSEEN * max(np.abs(readings).max(), 1e-300), axis=0)
    unseen = tuple(int(k) for k in np.flatnonzero(~seen))
    auto = np.full((readings.shape[1],) * 2, np.nan)
    if seen.any():
        auto[np.ix_(seen, seen)] = correlate(readings[:, seen], readings[:, seen]).auto_mac
    off = auto[np.ix_(seen, seen)][~np.eye(int(seen.sum()), dtype=bool)]
    largest = float(np.max(off, initial=0.0))
    placed = Placement(*(np.asarray(getattr(placement, f.name))[point]
                         for f in dataclasses.fields(Placement)))
    return Layout(points[point], link[point], fraction[point], directions, tuple(kinds),
                  readings, auto, largest, unseen, fisher_determinant(readings), placed)


def displacements(modes: ModelModes, layout: Layout) -> np.ndarray:
    """(N, 3, M) the target modes' displacement (x, y, z in the scene's frame) at each of the
    layout's points: what a triaxial sensor there would read."""
    n = len(layout.kinds)
    directions = np.tile(np.eye(3), (n, 1))
    return _read(modes, layout.placement, np.repeat(np.arange(n), 3), directions).reshape(n, 3, -1)


def _kinds(parts: tuple[Part, ...]) -> tuple[str, ...]:
    kinds = []
    if Part.IN_PLANE in parts:
        kinds += [Direction.TRANSVERSE, Direction.AXIAL]
    if Part.OUT_OF_PLANE in parts:
        kinds.append(Direction.OUT_OF_PLANE)
    return tuple(kinds)


def plan_sensors(scene: Scene, count: int, n_modes: int, elements: int | None = None,
                 stations: int = 20) -> SensorPlan:
    """``count`` sensor channels for the lowest ``n_modes`` elastic modes of ``scene``'s
    family at its pose, by Effective Independence over ``stations`` - 1 inner stations per
    link and the family's directions, against the uniform layout of the same count."""
    return dataclasses.replace(plan_for_modes(model_modes(scene, n_modes, elements), count,
                                              stations), scene=scene)


def plan_for_modes(modes: ModelModes, count: int, stations: int = 20) -> SensorPlan:
    """``plan_sensors`` for given target ``modes`` (no scene attached)."""
    model = modes.solved[0].model
    kinds = _kinds(tuple(p.part for p in modes.solved))
    points, link, fraction, placement = _stations(model, stations, ends=False)
    point = np.repeat(np.arange(len(points)), len(kinds))
    candidate_kinds = kinds * len(points)
    directions = np.array([_directions(model, int(link[p]), k)
                           for p, k in zip(point, candidate_kinds)])
    Phi = _read(modes, placement, point, directions)
    kept = effective_independence(Phi, count)
    chosen = _layout(modes, placement, points, link, fraction, point[kept],
                     [candidate_kinds[i] for i in kept], model)
    uniform = _uniform(modes, model, count, kinds)
    return SensorPlan(None, modes, count, len(Phi), chosen, uniform)


def _uniform(modes: ModelModes, model, count: int, kinds) -> Layout:
    """``count`` points evenly spaced over the links' total length, ends included, each
    across its link (in plane) or out of the plane, alternating for both."""
    lengths = np.array([l.length for l in model.links])
    s = np.linspace(0.0, lengths.sum(), count)
    edges = np.concatenate([[0.0], np.cumsum(lengths)])
    link = np.minimum(np.searchsorted(edges, s, side="right") - 1, len(lengths) - 1)
    fraction = np.clip((s - edges[link]) / lengths[link], 0.0, 1.0)
    points, element, xi = [], [], []
    for k, t in zip(link, fraction):
        l = model.links[k]
        start, end = model.nodes[l.first_node], model.nodes[l.first_node + l.elements]
        points.append(start + t * (end - start))
        e = min(int(math.floor(t * l.elements)), l.elements - 1)
        element.append(e)
        xi.append(t * l.elements - e)
    points = np.array(points)
    placement = Placement(link, np.array(element), np.array(xi), points, np.zeros_like(points),
                          np.zeros(count), fraction)
    across = [k for k in kinds if k != Direction.AXIAL]
    chosen_kinds = [across[i % len(across)] for i in range(count)]
    return _layout(modes, placement, points, link, fraction, np.arange(count), chosen_kinds,
                   model)
