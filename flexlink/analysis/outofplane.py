"""The out-of-plane model family at a scene's pose: weak-axis bending and St Venant torsion of
flat strip links (element matrices and assembly in ``fe.strip``, whose docstring gives the DOFs,
the closed forms and the joint springs).

Scene keys: ``joints.Ktilt`` (or ``joints.<J>.Ktilt``) [N m/rad], default "rigid" (an ideal
revolute joint transmits both out-of-plane bending moments).
"""

from __future__ import annotations

import functools

from flexlink.analysis.eigensolver import DEFAULT_SOLVER, EigenSolver
from flexlink.analysis.solve import (ModalResult, lowest_elastic, require_elastic,
                                     solve_eliminated_modes, solve_modes)
from flexlink.fe.assembly import rigid_elimination
from flexlink.fe.formulation import OUT_OF_PLANE_FORMULATION
from flexlink.fe.model import FrameModel
from flexlink.fe.strip import (StripProperties, assemble_out_of_plane,
                               assemble_out_of_plane_reduced_dense, link_strips,
                               out_of_plane_eigen_scale)
from flexlink.scene import Scene


def tilt_stiffnesses(scene: Scene) -> dict[str, float]:
    """Ktilt [N m/rad] per joint from ``joints.<J>.Ktilt`` or ``joints.Ktilt`` (default rigid)."""
    return dict(scene.options.tilt)


def out_of_plane_model(topology, points, tilt: dict[str, float]
                       ) -> tuple[FrameModel, tuple[StripProperties, ...]]:
    """(model, its ``link_strips``): ``topology``'s mesh at joint ``points`` [m] with the
    out-of-plane joint springs (``tilt``: Ktilt [N m/rad] per joint)."""
    model = OUT_OF_PLANE_FORMULATION.model(topology, points, tilt)
    return model, link_strips(model)


def out_of_plane_modes(topology, points, tilt: dict[str, float], n_modes: int,
                       solver: EigenSolver = DEFAULT_SOLVER) -> ModalResult:
    """The lowest ``n_modes`` elastic out-of-plane modes of ``topology`` at joint ``points``
    [m], and every rigid-body/mechanism mode below them."""
    return out_of_plane_solution(topology, points, tilt, n_modes, solver)[1]


def out_of_plane_solution(topology, points, tilt: dict[str, float], n_modes: int,
                          solver: EigenSolver = DEFAULT_SOLVER) -> tuple[FrameModel, ModalResult]:
    """(the out-of-plane model, ``out_of_plane_modes``): for callers that need the model too."""
    model, strips = out_of_plane_model(topology, points, tilt)
    T = rigid_elimination(model)
    n = model.n_dofs if T is None else T.shape[1]
    # Small models, which the dense solver takes anyway, are assembled straight into dense
    # K and M with the constraints eliminated, as in modal.pose_modes: scipy.sparse's
    # bookkeeping costs several times their eigen solve. Same matrices, same checks.
    if solver.assembles_dense(n):
        solve_model = solve_eliminated_modes
        K, M = assemble_out_of_plane_reduced_dense(model, model.springs, T, strips)
    else:
        solve_model = solve_modes
        K, M = assemble_out_of_plane(model, model.springs)
    solve = functools.partial(solve_model, K, M, T=T,
                              lambda_ref=out_of_plane_eigen_scale(model, strips), solver=solver)
    return model, require_elastic(lowest_elastic(solve, n_modes), n_modes)


def analyze_out_of_plane(scene: Scene, n_modes: int = 4, elements_per_link: int | None = None,
                         solver: EigenSolver = DEFAULT_SOLVER) -> ModalResult:
    """Out-of-plane modes of ``scene`` at its pose."""
    return out_of_plane_modes(scene.topology(elements_per_link), scene.rigid_pose().joints,
                              tilt_stiffnesses(scene), n_modes, solver)
