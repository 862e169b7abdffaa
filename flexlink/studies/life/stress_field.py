"""The normal stress at both extreme fibres of every element end of every link over one crank
turn at a crank speed: the quasi-static part and the steady dynamic part.

What is included. The steady elastic motion x(theta) about the rigid motion at crank speed
Omega solves the periodic equations of ``running.steady_response`` (its reduced basis B,
co-rotating coordinates, modal damping), forced by the d'Alembert loads of the rigid motion
(Omega^2 f2(theta)) and the scene's [[loads]] (f_ext(theta)); its harmonic balance solution q
holds the quasi-static and the dynamic answer together, with centrifugal softening, the
geometric stiffness of the inertia preload and Coriolis coupling. The basis holds the low
bending modes; the axial stretch of the links under their own inertia (the preload's axial
stress) and the local bending between nodes lie mostly outside it. So the stress is recovered
by the mode-acceleration method:

    x(theta) = B q(theta) + [x_s(theta) - B q_s(theta)],
    x_s = K^-1 f (the full model's static answer), q_s = (B^T K B)^-1 B^T f,

the bracket (the static answer the basis misses) taken for the d'Alembert loads per Omega^2 and
for the [[loads]] at every sampled pose; the directions outside the basis are assumed to answer
quasi-statically (their frequencies lie far above the forcing harmonics), through K at rest. The
stress of each part is ``fe.stress.link_stresses``, with the elements' own d'Alembert loads in
the static answer (exact element-end forces of the preload). All rows are taken at the forced
model's poses and interpolated in the crank angle by their Fourier series, as the model's
matrices are. The quasi-static part reported is K^-1 f's stress (Omega^2 sigma_2 + sigma_ext);
the dynamic part is the rest.

Not included: stress concentrations (holes, pins, clamps, fillets), shear stress (zero at the
extreme fibres), out-of-plane bending and torsion, the start-up transient, and the joints'
own stresses. Frozen-configuration small elastic motion about the rigid motion, linear
elastic material.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexlink.analysis.eigensolver import AUTO_DENSE_MAX
from flexlink.analysis.frame_motion import pose_speed_terms, unit_motion
from flexlink.analysis.periodic import PeriodicModel, periodic_model, speed_multipliers
from flexlink.errors import InputError
from flexlink.fe.assembly import (eliminated_pair, eliminating_assembler, reduced_columns,
                                  rigid_elimination)
from flexlink.fe.preload import element_inertia_loads
from flexlink.fe.stress import FIBRES, end_positions, link_stresses
from flexlink.scene import Scene
from flexlink.studies.running.steady_response import (SAMPLES, ForcedModel, UnstableError,
                                                      forced_model, periodic_solution)
from flexlink.units import RPM

INCLUDED = ("normal stress sigma = N/A -+ M c/I at both extreme fibres of every element end; "
            "quasi-static part: the d'Alembert loads of the rigid motion (the inertia preload's "
            "axial stress included) and the scene's [[loads]]; dynamic part: the steady "
            "periodic elastic response at the crank speed (harmonic balance, modal damping, "
            "centrifugal, Coriolis and preload stiffness), the basis completed by the "
            "static answer of the directions outside it (mode acceleration)")
# static modes per pose behind the basis: the peak stress converges more slowly in the basis
# than the frequencies do (a resonant response leans on modes the frequency check does not
# ask for); 14 holds the Table II peaks within 2 % where 6 did not (docs/life.md)
MODES = 14
# whether a steady state exists: the stability map's verdict in its own default basis, so the
# life command refuses exactly the speeds ``stability-map`` and ``response`` call unstable
VERDICT_MODES = 6
ASSUMPTIONS = ("small elastic motion about the rigid motion (frozen configuration at each crank "
               "angle), linear elastic material, sections symmetric about their axis; not "
               "included: stress concentrations at holes, pins and clamps, shear stress, "
               "out-of-plane bending and torsion, start-up transients")


@dataclasses.dataclass(frozen=True)
class StressPoints:
    """The stress points: per point the link index, element, end (0 start, 1 end), fibre
    (0: y = +c, 1: y = -c) and distance from the link's start joint [m] (points,)."""

    links: tuple[str, ...]
    link: np.ndarray
    element: np.ndarray
    end: np.ndarray
    fibre: np.ndarray
    position: np.ndarray

    def __post_init__(self):
        n = len(self.link)
        for name in ("element", "end", "fibre", "position"):
            if getattr(self, name).shape != (n,):
                raise ValueError(f"{name} must be ({n},)")

    def of(self, link: str) -> np.ndarray:
        """The indices of ``link``'s points."""
        return np.flatnonzero(self.link == self.links.index(link))


@dataclasses.dataclass(frozen=True)
class StressModel:
    """The forced model with stress rows at every ``points`` entry, at the forced model's
    poses: modal (poses, points, n) [Pa per modal coordinate]; residual and quasi_static
    (poses, points, 2) [Pa]: the static answer the basis misses, and the whole static answer,
    for the d'Alembert loads per (rad/s)^2 (column 0) and for the [[loads]] (column 1);
    elements, the mesh per link; sections, per link; verdict: the periodic model whose
    Floquet multipliers say whether a steady state exists (``VERDICT_MODES``)."""

    forced: ForcedModel
    points: StressPoints
    modal: np.ndarray
    residual: np.ndarray
    quasi_static: np.ndarray
    elements: tuple[int, ...]
    sections: tuple
    verdict: PeriodicModel

    def __post_init__(self):
        poses = len(self.forced.periodic.angles)
        count, n = len(self.points.link), len(self.forced.periodic.frequencies)
        if self.modal.shape != (poses, count, n):
            raise ValueError(f"modal must be ({poses}, {count}, {n})")
        for name in ("residual", "quasi_static"):
            if getattr(self, name).shape != (poses, count, 2):
                raise ValueError(f"{name} must be ({poses}, {count}, 2)")


def stress_model(scene: Scene, n_modes: int = MODES, poses: int = 37,
                 damping_ratio: float | None = None, elements_per_link: int | None = None,
                 basis_size: int | None = None, verdict: bool = True) -> StressModel:
    """``running.steady_response.forced_model`` with the stress rows of every element end
    and fibre (module docstring), and the stability map's model for the verdict (``verdict``
    False: the model's own, for a field whose speed is known to be stable)."""
    forced = forced_model(scene, n_modes, poses, damping_ratio,
                          elements_per_link=elements_per_link, basis_size=basis_size)
    own = not verdict or (n_modes == VERDICT_MODES and basis_size is None)
    verdict = forced.periodic.stability if own else periodic_model(scene, VERDICT_MODES, poses,
                                                         damping_ratio, elements_per_link)
    topology = scene.topology(elements_per_link)
    periodic = forced.periodic
    model0 = periodic.pose_models[0]
    T = rigid_elimination(model0)
    column, n = reduced_columns(T, model0.n_dofs)
    assemble = eliminating_assembler(column, n, dense=True)
    points = _points(model0)
    count, size = len(points.link), periodic.pose_shapes.shape[2]
    modal = np.empty((poses, count, size))
    residual, quasi = np.empty((poses, count, 2)), np.empty((poses, count, 2))
    for p, (angle, model, full) in enumerate(zip(periodic.angles, periodic.pose_models,
                                                 periodic.pose_shapes)):
        state = scene.rigid_state(angle)
        modal[p] = _flat(link_stresses(model, full))
        Kr = eliminated_pair(model, T, assemble, direct=n <= AUTO_DENSE_MAX)[0]
        Kr = Kr.toarray() if hasattr(Kr, "toarray") else np.asarray(Kr)
        terms = pose_speed_terms(scene, topology, state, model, Kr, T, assemble)
        u = np.stack([terms.inertia_displacement, terms.external_displacement], axis=1)
        motion = unit_motion(scene, model, topology, state)
        own = tuple(np.stack([e, np.zeros_like(e)], axis=-1)
                    for e in element_inertia_loads(model, motion.acceleration, motion.alpha))
        quasi[p] = _flat(link_stresses(model, u, own))
        # the basis' static answer to the same loads: its projected stiffness and forcing
        qs = np.linalg.solve(periodic.elastic_stiffness[p], np.stack(
            [periodic.inertia_forcing[p], periodic.external_forcing[p]], axis=1))
        residual[p] = quasi[p] - modal[p] @ qs
    return StressModel(forced=forced, points=points, modal=modal, residual=residual,
                       quasi_static=quasi, elements=tuple(l.elements for l in model0.links),
                       sections=tuple(l.section for l in model0.links), verdict=verdict)


def _points(model) -> StressPoints:
    """The point table of ``model``'s links, in ``_flat``'s order."""
    parts = []
    for i, link in enumerate(model.links):
        e = link.elements
        grid = np.meshgrid(np.arange(e), np.arange(2), np.arange(len(FIBRES)), indexing="ij")
        where = end_positions(link)[grid[0], grid[1]]
        parts.append((np.full(grid[0].size, i), grid[0].ravel(), grid[1].ravel(),
                      grid[2].ravel(), where.ravel()))
    link, element, end, fibre, position = (np.concatenate(c) for c in zip(*parts))
    return StressPoints(tuple(l.name for l in model.links), link, element, end, fibre, position)


def _flat(per_link) -> np.ndarray:
    """Per-link stresses (e, 2 ends, ..., 2 fibres) -> (points, ...), ``_points``' order."""
    out = []
    for s in per_link:
        s = np.moveaxis(s, -1, 2)  # (e, 2, fibres, ...)
        out.append(s.reshape((-1,) + s.shape[3:]))
    return np.concatenate(out)


@dataclasses.dataclass(frozen=True)
class StressField:
    """The stress over one turn at crank ``speed`` [rad/s]: crank angles (samples,) [rad];
    total and quasi_static stress (samples, points) [Pa]; the harmonic balance's estimated
    error [-] and harmonics; the largest multiplier modulus [-] (below 1: a steady state)."""

    speed: float
    angles: np.ndarray
    points: StressPoints
    total: np.ndarray
    quasi_static: np.ndarray
    harmonic_error: float
    harmonics: int
    largest_modulus: float

    def __post_init__(self):
        shape = (len(self.angles), len(self.points.link))
        for name in ("total", "quasi_static"):
            if getattr(self, name).shape != shape:
                raise ValueError(f"{name} must be {shape}")

    @property
    def dynamic(self) -> np.ndarray:
        """The dynamic part, total less quasi-static (samples, points) [Pa]."""
        return self.total - self.quasi_static


def stress_field(model: StressModel, speed: float, samples: int = SAMPLES,
                 check_stability: bool = True) -> StressField:
    """The stress over one turn at crank ``speed`` [rad/s] at ``samples`` crank angles.
    UnstableError, naming the unstable range of speeds around it, where no steady state
    exists (``check_stability``: False where the caller has the verdict already)."""
    if not (math.isfinite(speed) and speed > 0.0):
        raise InputError(f"crank speed {speed / RPM:.6g} rev/min", field="--speed",
                         expected="a positive finite speed")
    modulus = math.nan
    if check_stability:
        modulus = speed_multipliers(model.verdict, speed).largest_modulus
        if modulus >= 1.0:
            low, high = unstable_range(model.verdict, speed)
            raise UnstableError(
                f"no steady state at {speed / RPM:.6g} rev/min: it lies in the unstable range "
                f"{low / RPM:.6g} to {high / RPM:.6g} rev/min (largest Floquet multiplier "
                f"|mu| = {modulus:.4g} >= 1: the free motion grows)")
    solution = periodic_solution(model.forced, speed)
    turn = 2.0 * np.pi * np.arange(samples) / samples
    angles = model.forced.periodic.angles[0] + turn
    q = solution.at(turn)
    at = model.forced.at
    scale = np.array([speed**2, 1.0])
    total = np.einsum("spn,sn->sp", at(model.modal, angles), q) \
        + at(model.residual, angles) @ scale
    quasi = at(model.quasi_static, angles) @ scale
    return StressField(speed=float(speed), angles=angles, points=model.points, total=total,
                       quasi_static=quasi, harmonic_error=solution.error,
                       harmonics=solution.harmonics, largest_modulus=modulus)


def unstable_range(model: PeriodicModel, speed: float, resolution: float = 0.005,
                   widest: float = 4.0) -> tuple[float, float]:
    """The run of unstable speeds [rad/s] around the unstable ``speed``: stepped outwards by
    doubling steps until stable (at most a factor ``widest``), then bisected to
    ``resolution`` (relative)."""
    def unstable(w):
        return speed_multipliers(model, w).largest_modulus >= 1.0

    ends = []
    for direction in (-1.0, 1.0):
        inside, step = speed, resolution * speed
        outside = None
        while abs(step) < widest * speed:
            trial = inside + direction * step
            if trial <= 0.0:
                outside = 0.0
                break
            if not unstable(trial):
                outside = trial
                break
            inside, step = trial, 2.0 * step
        if outside is None:
            ends.append(inside)
            continue
        while abs(outside - inside) > resolution * speed and outside > 0.0:
            middle = 0.5 * (inside + outside)
            if unstable(middle):
                inside = middle
            else:
                outside = middle
        ends.append(inside)
    return ends[0], ends[1]


__all__ = ["ASSUMPTIONS", "INCLUDED", "StressField", "StressModel", "StressPoints",
           "UnstableError", "stress_field", "stress_model", "unstable_range"]
