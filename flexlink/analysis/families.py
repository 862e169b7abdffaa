"""Model families a scene can choose (``[model] family = ...``), behind one function.

- "planar": the paper's model, in-plane frame elements (``analysis.analyze``); the default.
- "out-of-plane": weak-axis bending and St Venant torsion of the strips (``outofplane``).
- "3d": both; for a linkage lying in one plane with doubly symmetric sections the two sets of
  motions decouple to first order, so the 3D spectrum is the union of the two, sorted.
Measured frequencies are paired with the lowest elastic modes of the chosen family by mode
order only.

``family_modes`` keeps each family's model and mode shapes, for callers that differentiate the
frequencies (``studies.jacobian``): ``quadratic_forms`` gives s^T K s and s^T M s of shapes on a
family's model, from the same element, spring and mass entries the assembly sums.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.analysis.modal import analyze
from flexlink.analysis.outofplane import out_of_plane_model, out_of_plane_solution, tilt_stiffnesses
from flexlink.fe.assembly import node_rotation, point_mass_entries, springs_stiffness_entries
from flexlink.fe.beams import link_entries
from flexlink.fe.model import FrameModel
from flexlink.fe.pose import pose_model
from flexlink.fe.strip import (StripProperties, link_strips, strip_element_matrices,
                               strip_mass_entries, strip_node_rotation)
from flexlink.scene import Scene

FAMILIES = ("planar", "out-of-plane", "3d")
IN_PLANE, OUT_OF_PLANE = "in-plane", "out-of-plane"
PARTS = {"planar": (IN_PLANE,), "out-of-plane": (OUT_OF_PLANE,), "3d": (IN_PLANE, OUT_OF_PLANE)}


def scene_family(scene: Scene) -> str:
    return scene.options.family  # one of FAMILIES, checked by the scene schema


@dataclasses.dataclass(frozen=True)
class FamilyModes:
    """One part (IN_PLANE or OUT_OF_PLANE) of a scene's family at its pose: the model solved
    (for OUT_OF_PLANE with its bearing springs), its elastic frequencies [Hz], ascending, and
    their shapes (model.n_dofs, k) in the model's DOFs."""

    part: str
    model: FrameModel
    frequencies: np.ndarray
    shapes: np.ndarray


def family_modes(scene: Scene, n_modes: int, elements: int | None = None,
                 method: str = "auto") -> tuple[FamilyModes, ...]:
    """The lowest ``n_modes`` elastic modes of each part of the scene's family."""
    out = []
    for part in PARTS[scene_family(scene)]:
        if part == IN_PLANE:
            case = analyze(scene, n_modes, elements, method)
            model, modes = case.model, case.modes
        else:
            model, modes = out_of_plane_solution(scene.topology(elements), scene.rigid_pose().joints,
                                                 tilt_stiffnesses(scene), n_modes, method)
        elastic = modes.elastic[:n_modes]
        out.append(FamilyModes(part, model, modes.frequencies[elastic], modes.shapes[:, elastic]))
    return tuple(out)


def paired(parts: tuple[FamilyModes, ...], n_modes: int
           ) -> tuple[np.ndarray, tuple[tuple[int, int], ...]]:
    """The lowest ``n_modes`` modes over all parts, ascending: their frequencies [Hz] (NaN
    where the parts have fewer) and, per mode found, (index into ``parts``, index into that
    part's modes)."""
    found = sorted((f, p, k) for p, part in enumerate(parts) for k, f in enumerate(part.frequencies))
    found = found[:n_modes]
    freqs = np.full(n_modes, np.nan)
    freqs[:len(found)] = [f for f, _, _ in found]
    return freqs, tuple((p, k) for _, p, k in found)


def elastic_modes(scene: Scene, n_modes: int, elements: int | None = None,
                  method: str = "auto") -> tuple[np.ndarray, tuple[str, ...]]:
    """The lowest ``n_modes`` elastic frequencies [Hz] of the scene's family (NaN where fewer
    were found) and, per mode, whether it is an in-plane or out-of-plane mode."""
    parts = family_modes(scene, n_modes, elements, method)
    freqs, pairs = paired(parts, n_modes)
    return freqs, tuple(parts[p].part for p, _ in pairs)


def part_model(scene: Scene, part: str, elements: int | None = None) -> FrameModel:
    """The model ``family_modes`` solves for ``part`` of ``scene``, built without solving."""
    topology, points = scene.topology(elements), scene.rigid_pose().joints
    if part == IN_PLANE:
        return pose_model(topology, points, warn=False)
    return out_of_plane_model(topology, points, tilt_stiffnesses(scene))[0]


def quadratic_forms(part: str, model: FrameModel, shapes: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
    """(s^T K s, s^T M s) for each column s of ``shapes`` (model.n_dofs, k) on ``part``'s K
    and M of ``model`` (finite springs only: rigid ones are constraints the shapes obey).

    Each link's element entries act on its nodes' displacements in the link frame (every node
    belongs to one link), so the shapes are rotated per node and the local entries used as
    they are: a ninth of the rotated entries the assembly sums."""
    local = np.empty_like(shapes)
    q_K, q_M = np.zeros(shapes.shape[1]), np.zeros(shapes.shape[1])
    if part != IN_PLANE:  # equal elements: one 6 x 6 pair per link
        strips = link_strips(model)
        props = StripProperties(*(np.array([getattr(p, f.name) for p in strips])
                                  for f in dataclasses.fields(StripProperties)))
        k_links, m_links = strip_element_matrices(
            np.array([link.length / link.elements for link in model.links]), props)
    for index, link in enumerate(model.links):
        nodes = link.nodes
        R = (node_rotation(link.angle) if part == IN_PLANE
             else strip_node_rotation(link.angle))
        block = shapes[3 * nodes[0]:3 * nodes[-1] + 3].reshape(len(nodes), 3, -1)
        chain = np.einsum("ij,njk->nik", R, block)
        local[3 * nodes[0]:3 * nodes[-1] + 3] = chain.reshape(-1, shapes.shape[1])
        if part == IN_PLANE:
            rows, cols, k, m = link_entries(link.length, link.elements, link.section)
            flat = chain.reshape(-1, shapes.shape[1])
            q_K += (k[:, None] * flat[rows] * flat[cols]).sum(axis=0)
            q_M += (m[:, None] * flat[rows] * flat[cols]).sum(axis=0)
        else:  # on each element's two nodes
            pairs = np.concatenate([chain[:-1], chain[1:]], axis=1).transpose(2, 0, 1)
            q_K += ((pairs @ k_links[index]) * pairs).sum(axis=(1, 2))
            q_M += ((pairs @ m_links[index]) * pairs).sum(axis=(1, 2))
    q_K += _spring_form(model, shapes)
    m_rows, m_cols, m_vals = (point_mass_entries(model) if part == IN_PLANE
                              else strip_mass_entries(model))
    q_M += (m_vals[:, None] * shapes[m_rows] * shapes[m_cols]).sum(axis=0)
    return q_K, q_M


def _spring_form(model: FrameModel, shapes: np.ndarray) -> np.ndarray:
    """sum over the finite springs of k (s_a - s_b)^2, per shape (s_b = 0 for ground)."""
    rows, cols, vals = springs_stiffness_entries(model.springs)
    return (vals[:, None] * shapes[rows] * shapes[cols]).sum(axis=0)
