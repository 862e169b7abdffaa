"""Model families a scene can choose (``[model] family = ...``), behind one function.

- "planar": the paper's model, in-plane frame elements (``analysis.analyze``); the default.
- "out-of-plane": weak-axis bending and St Venant torsion of the strips (``outofplane``).
- "3d": both; for a linkage lying in one plane with doubly symmetric sections the two sets of
  motions decouple to first order, so the 3D spectrum is the union of the two, sorted.
Each part is one ``fe.formulation.Formulation``; its solver here is the one thing that differs
per part at this stage. Measured frequencies are paired with the lowest elastic modes of the
chosen family by mode order only.

``part_modes`` keeps each part's model and mode shapes, for callers that differentiate the
frequencies (``studies.calibration.jacobian``): ``quadratic_forms`` gives s^T K s and s^T M s of shapes on a
part's model, from the same element, spring and mass entries the assembly sums.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.analysis.eigensolver import DEFAULT_SOLVER, EigenSolver
from flexlink.analysis.modal import analyze
from flexlink.analysis.outofplane import out_of_plane_solution, tilt_stiffnesses
from flexlink.fe.formulation import FORMULATIONS, IN_PLANE_FORMULATION, OUT_OF_PLANE_FORMULATION
from flexlink.fe.model import FrameModel
from flexlink.fe.motions import ModelFamily, Part
from flexlink.scene import Scene

IN_PLANE, OUT_OF_PLANE = IN_PLANE_FORMULATION.part, OUT_OF_PLANE_FORMULATION.part


def scene_family(scene: Scene) -> ModelFamily:
    return scene.options.family


def in_plane_only_note(scene: Scene, what: str) -> str | None:
    """Why ``what`` (a result built on the in-plane model only: crank-cycle maps, exported
    shapes, the report's shapes) holds other modes than the scene's family's; None when the
    family is planar."""
    family = scene_family(scene)
    if family is ModelFamily.PLANAR:
        return None
    return (f"model.family = '{family}': {what} holds the in-plane modes only (built for the "
            "in-plane model; `flexlink modes` gives the family's modes at the scene's pose)")


@dataclasses.dataclass(frozen=True)
class PartModes:
    """One part (IN_PLANE or OUT_OF_PLANE) of a scene's family at its pose: the model solved
    (for OUT_OF_PLANE with its bearing springs), its elastic frequencies [Hz], ascending, and
    their shapes (model.n_dofs, k) in the model's DOFs."""

    part: Part
    model: FrameModel
    frequencies: np.ndarray
    shapes: np.ndarray


def _in_plane_solution(scene: Scene, n_modes: int, elements: int | None, solver: EigenSolver):
    case = analyze(scene, n_modes, elements, solver)  # with the scene's plausibility warnings
    return case.model, case.modes


def _out_of_plane_solution(scene: Scene, n_modes: int, elements: int | None, solver: EigenSolver):
    return out_of_plane_solution(scene.topology(elements), scene.rigid_pose().joints,
                                 tilt_stiffnesses(scene), n_modes, solver)


SOLUTIONS = {IN_PLANE: _in_plane_solution, OUT_OF_PLANE: _out_of_plane_solution}


def part_modes(scene: Scene, n_modes: int, elements: int | None = None,
                 solver: EigenSolver = DEFAULT_SOLVER) -> tuple[PartModes, ...]:
    """The lowest ``n_modes`` elastic modes of each part of the scene's family."""
    out = []
    for part in scene_family(scene).parts:
        model, modes = SOLUTIONS[part](scene, n_modes, elements, solver)
        elastic = modes.elastic[:n_modes]
        out.append(PartModes(part, model, modes.frequencies[elastic], modes.shapes[:, elastic]))
    return tuple(out)


def paired(parts: tuple[PartModes, ...], n_modes: int
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
                  solver: EigenSolver = DEFAULT_SOLVER) -> tuple[np.ndarray, tuple[Part, ...]]:
    """The lowest ``n_modes`` elastic frequencies [Hz] of the scene's family (NaN where fewer
    were found) and, per mode, whether it is an in-plane or out-of-plane mode."""
    parts = part_modes(scene, n_modes, elements, solver)
    freqs, pairs = paired(parts, n_modes)
    return freqs, tuple(parts[p].part for p, _ in pairs)


def part_model(scene: Scene, part: Part, elements: int | None = None) -> FrameModel:
    """The model ``part_modes`` solves for ``part`` of ``scene``, built without solving."""
    return FORMULATIONS[part].model(scene.topology(elements), scene.rigid_pose().joints,
                                    tilt_stiffnesses(scene))


def quadratic_forms(part: Part, model: FrameModel, shapes: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
    """(s^T K s, s^T M s) for each column s of ``shapes`` (model.n_dofs, k) on ``part``'s K
    and M of ``model`` (finite springs only: rigid ones are constraints the shapes obey)."""
    return FORMULATIONS[part].quadratic_forms(model, shapes)
