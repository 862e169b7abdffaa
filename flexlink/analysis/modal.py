"""One scene, end to end: rigid pose -> model -> K, M -> modes. Pure function of its inputs."""

from __future__ import annotations

import dataclasses
import logging
import time

import numpy as np

from flexlink.fe.assembly import assemble, reduction
from flexlink.fe.energy import lumped_mass, twice_strain_energy
from flexlink.kinematics.fourbar import Pose
from flexlink.fe.model import FrameModel, build_model
from flexlink.scene.plausibility import model_warnings, pose_warnings
from flexlink.fe.rigid import rigidified
from flexlink.scene import Scene
from flexlink.analysis.solve import ModalResult, solve_modes

log = logging.getLogger(__name__)

_WARNED: set[tuple[str, str]] = set()
EXTRA_MODES = 4  # solved beyond the requested count, so mechanism modes cannot crowd them out


def lambda_scale(model: FrameModel) -> float:
    """The model's own eigenvalue scale [rad^2/s^2]: the smallest EI / (rhoA L^4) of its links.

    A link's lowest bending eigenvalue is this times a constant of order 10 to 500, so modes
    many orders of magnitude below it are rigid-body or mechanism modes."""
    return min(l.section.EI / (l.section.mass_per_length * l.length**4) for l in model.links)


@dataclasses.dataclass(frozen=True)
class CaseResult:
    scene: Scene
    pose: Pose
    model: FrameModel
    modes: ModalResult
    elements_per_link: int
    seconds: dict[str, float]
    warnings: tuple[str, ...] = ()  # model outside its range (plausibility.py), also logged

    def elastic_frequencies(self, n: int) -> np.ndarray:
        return self.modes.elastic_frequencies[:n]


MASSES = ("consistent", "lumped")


def analyze(scene: Scene, n_modes: int = 4, elements_per_link: int | None = None,
            method: str = "auto", mass: str = "consistent", refine: bool = True) -> CaseResult:
    """Natural frequencies of ``scene`` at its pose: the lowest ``n_modes`` elastic modes
    (plus any rigid-body/mechanism modes below them, labelled as such).

    ``mass``: "consistent" (the element's own) or "lumped" (HRZ diagonal, ``energy.py``).
    ``refine``: eigenvalues as Rayleigh quotients of the strain energy computed from element
    deformations (``energy.py``), so fine meshes are not limited by the round-off of K."""
    if mass not in MASSES:
        raise ValueError(f"unknown mass {mass!r}: one of {MASSES}")
    t0 = time.perf_counter()
    pose = scene.rigid_pose()
    topology = scene.topology(elements_per_link)
    model = rigidified(build_model(topology, pose.joints))
    warnings = tuple(pose_warnings(scene.four_bar, pose) + model_warnings(model))
    for w in warnings:
        if (scene.path, w) not in _WARNED:  # once per process: sweeps call this many times
            _WARNED.add((scene.path, w))
            log.warning("%s: %s", scene.path, w)
    K, M = assemble(model)
    if mass == "lumped":
        M = lumped_mass(model)
    T = reduction(model)
    t1 = time.perf_counter()
    energy = (lambda shapes: twice_strain_energy(model, shapes)) if refine else None
    modes = solve_modes(K, M, n_modes + EXTRA_MODES, T=T, lambda_ref=lambda_scale(model),
                        method=method, energy=energy)
    t2 = time.perf_counter()
    return CaseResult(scene=scene, pose=pose, model=model, modes=modes,
                      elements_per_link=topology.links[0].elements,
                      seconds={"assembly": t1 - t0, "solve": t2 - t1}, warnings=warnings)
