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
from flexlink.fe.assembly import (placed_link_entries, point_mass_entries, rotated_entries,
                                  springs_stiffness_entries)
from flexlink.fe.model import FrameModel
from flexlink.fe.pose import pose_model
from flexlink.fe.strip import link_strips, strip_entries, strip_mass_entries
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


def paired(parts: tuple[FamilyModes, ...], n_modes: int) -> list[tuple[float, int, int]]:
    """The lowest ``n_modes`` modes over all parts, ascending: (frequency [Hz], index into
    ``parts``, index into that part's modes); fewer if the parts have fewer."""
    found = sorted((f, p, k) for p, part in enumerate(parts) for k, f in enumerate(part.frequencies))
    return found[:n_modes]


def elastic_modes(scene: Scene, n_modes: int, elements: int | None = None,
                  method: str = "auto") -> tuple[np.ndarray, tuple[str, ...]]:
    """The lowest ``n_modes`` elastic frequencies [Hz] of the scene's family (NaN where fewer
    were found) and, per mode, whether it is an in-plane or out-of-plane mode."""
    parts = family_modes(scene, n_modes, elements, method)
    found = paired(parts, n_modes)
    freqs = np.full(n_modes, np.nan)
    freqs[:len(found)] = [f for f, _, _ in found]
    return freqs, tuple(parts[p].part for _, p, _ in found)


def part_model(scene: Scene, part: str, elements: int | None = None) -> FrameModel:
    """The model ``family_modes`` solves for ``part`` of ``scene``, built without solving."""
    topology, points = scene.topology(elements), scene.rigid_pose().joints
    if part == IN_PLANE:
        return pose_model(topology, points, warn=False)
    return out_of_plane_model(topology, points, tilt_stiffnesses(scene))[0]


def quadratic_forms(part: str, model: FrameModel, shapes: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
    """(s^T K s, s^T M s) for each column s of ``shapes`` (model.n_dofs, k) on ``part``'s K
    and M of ``model`` (finite springs only: rigid ones are constraints the shapes obey)."""
    if part == IN_PLANE:
        rows, cols, values = rotated_entries(*placed_link_entries(model))
        m_rows, m_cols, m_vals = point_mass_entries(model)
    else:
        rows, cols, values = strip_entries(model, link_strips(model))
        m_rows, m_cols, m_vals = strip_mass_entries(model)
    s_rows, s_cols, s_vals = springs_stiffness_entries(model.springs)

    def form(r, c, v):
        return (v[:, None] * shapes[r] * shapes[c]).sum(axis=0)

    return (form(rows, cols, values[0]) + form(s_rows, s_cols, s_vals),
            form(rows, cols, values[1]) + form(m_rows, m_cols, m_vals))
