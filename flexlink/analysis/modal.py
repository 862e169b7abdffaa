"""One scene, end to end: rigid pose -> model -> K, M -> modes. Pure function of its inputs."""

from __future__ import annotations

import dataclasses
import enum
import functools
import logging
import time
from collections.abc import Mapping

import numpy as np
import scipy.sparse as sp

from flexlink.analysis.precision import refuse_too_fine
from flexlink.choices import parse_choice
from flexlink.analysis.eigensolver import DEFAULT_SOLVER, EigenSolver
from flexlink.analysis.solve import (LOST_LIMIT, ModalResult, lowest_elastic, require_elastic,
                                     solve_eliminated_modes, solve_modes)
from flexlink.fe.assembly import assemble, assemble_reduced_dense, rigid_elimination
from flexlink.fe.energy import lumped_mass, twice_strain_energy
from flexlink.fe.model import FrameModel, Topology
from flexlink.fe.model_at_pose import in_plane_eigen_scale, pose_model
from flexlink.scene import RigidPose, Scene
from flexlink.scene.plausibility import model_warnings, pose_warnings

log = logging.getLogger(__name__)



class Mass(enum.StrEnum):
    """The mass matrix: the element's own (consistent) or the HRZ diagonal (lumped,
    ``energy.lumped_mass``)."""

    CONSISTENT = "consistent"
    LUMPED = "lumped"


@dataclasses.dataclass(frozen=True)
class CaseResult:
    scene: Scene
    pose: RigidPose
    model: FrameModel
    modes: ModalResult
    elements_per_link: int
    seconds: dict[str, float]
    warnings: tuple[str, ...] = ()  # model outside its range (plausibility.py), also logged

    def elastic_frequencies(self, n: int) -> np.ndarray:
        return self.modes.elastic_frequencies[:n]


@dataclasses.dataclass(frozen=True)
class PoseSystem:
    """A pose's model, its assembled K and M and its modes (``pose_system``): K, M are
    T^T K T and T^T M T when ``eliminated`` (dense), else full size; T from
    ``assembly.rigid_elimination`` (None: nothing rigid)."""

    model: FrameModel
    modes: ModalResult
    K: object
    M: object
    T: object
    eliminated: bool
    seconds: dict[str, float]

    def eliminated_pair(self) -> tuple:
        """(T^T K T, T^T M T), the rigid constraints eliminated: as the solve had them when it
        eliminated them (dense), else from its full sparse K and M."""
        if self.eliminated:
            return self.K, self.M
        if self.T is None:
            return sp.csr_matrix(self.K), sp.csr_matrix(self.M)
        T = sp.csr_matrix(self.T)
        return (T.T @ self.K @ T).tocsr(), (T.T @ self.M @ T).tocsr()


def pose_modes(topology: Topology, points: Mapping[str, tuple[float, float]], n_modes: int,
               solver: EigenSolver = DEFAULT_SOLVER, mass: Mass = Mass.CONSISTENT,
               refine: bool = True) -> tuple[FrameModel, ModalResult, dict[str, float]]:
    """(model, modes, seconds) of ``pose_system``."""
    system = pose_system(topology, points, n_modes, solver, mass, refine)
    return system.model, system.modes, system.seconds


def pose_system(topology: Topology, points: Mapping[str, tuple[float, float]], n_modes: int,
                solver: EigenSolver = DEFAULT_SOLVER, mass: Mass = Mass.CONSISTENT,
                refine: bool = True) -> PoseSystem:
    """``topology`` with its joints at ``points`` [m], assembled, and its lowest ``n_modes``
    elastic modes and every rigid-body/mechanism mode below them, labelled.

    Refuses, before assembling, a mesh too fine for double precision
    (``precision.refuse_too_fine``), and asking for more elastic modes than the model has
    (``solve.require_elastic``). ``mass`` and ``refine`` as in ``analyze``."""
    t0 = time.perf_counter()
    refuse_too_fine(topology, points, LOST_LIMIT)
    model = pose_model(topology, points)
    T = rigid_elimination(model)
    n = model.n_dofs if T is None else T.shape[1]
    # Small models, which the dense solver takes anyway, are assembled straight into dense
    # K and M with the constraints eliminated: scipy.sparse's bookkeeping (COO -> CSR, T^T K T)
    # costs several times their eigen solve. Same matrices, same checks.
    eliminated = mass is Mass.CONSISTENT and solver.assembles_dense(n)
    if eliminated:
        solve_model = solve_eliminated_modes
        K, M = assemble_reduced_dense(model, T)
    else:
        solve_model = solve_modes
        K, M = assemble(model)
        if mass is Mass.LUMPED:
            M = lumped_mass(model)
    t1 = time.perf_counter()
    energy = (lambda shapes: twice_strain_energy(model, shapes)) if refine else None
    solve = functools.partial(solve_model, K, M, T=T, lambda_ref=in_plane_eigen_scale(model),
                              solver=solver, energy=energy)
    modes = require_elastic(lowest_elastic(solve, n_modes), n_modes)
    t2 = time.perf_counter()
    return PoseSystem(model, modes, K, M, T, eliminated, {"assembly": t1 - t0, "solve": t2 - t1})


def analyze(scene: Scene, n_modes: int = 4, elements_per_link: int | None = None,
            solver: EigenSolver = DEFAULT_SOLVER, mass: Mass = Mass.CONSISTENT,
            refine: bool = True) -> CaseResult:
    """Natural frequencies of ``scene`` at its pose: the lowest ``n_modes`` elastic modes
    (plus any rigid-body/mechanism modes below them, labelled as such).

    ``solver``: the eigen solver (``eigensolver.EigenSolver``, or its method's text: "auto",
    "dense" or "sparse"). ``mass``: a ``Mass`` (its text accepted: "consistent" or "lumped").
    ``refine``: eigenvalues as Rayleigh quotients of the strain energy computed from element
    deformations (``energy.py``), so fine meshes are not limited by the round-off of K."""
    mass = parse_choice(Mass, mass, "mass")
    solver = solver if isinstance(solver, EigenSolver) else EigenSolver(solver)
    pose = scene.rigid_pose()
    topology = scene.topology(elements_per_link)
    model, modes, seconds = pose_modes(topology, pose.joints, n_modes, solver, mass, refine)
    warnings = tuple(pose_warnings(scene.four_bar, pose) + model_warnings(model))
    for w in warnings:  # once per kind and run: the CLI's logbook filter counts the repeats
        log.warning("%s: %s", scene.path, w)
    return CaseResult(scene=scene, pose=pose, model=model, modes=modes,
                      elements_per_link=topology.links[0].elements, seconds=seconds,
                      warnings=warnings)
