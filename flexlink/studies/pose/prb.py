"""Pseudo-rigid-body (PRB) model of a partially compliant linkage: its first natural frequency,
to set beside the finite-element value.

A compliant strip of length l, clamped to one body (here the coupler) and pinned to the ground,
is replaced by a rigid link of length gamma l from the ground pin to a characteristic pivot,
with a torsional spring there (Howell's fixed-pinned segment):
    K = gamma K_Theta E I / l          [N m/rad]
The spring turns by the angle between the PRB link and the clamping body, so with velocity
coefficients the linkage (one degree of freedom q, here the free crank) has
    generalized stiffness  k_q = K (K_link - K_clamp)^2,
    generalized mass       m_q = sum over uniform bars of m (vP^2 + vP.vQ + vQ^2) / 3
                                 + sum over joint masses of m v^2,
vP, vQ the bar ends' velocities per unit qdot (a rigid uniform bar's kinetic energy is exactly
m (vP^2 + vP.vQ + vQ^2) / 6 qdot^2). The strip's mass is split at the characteristic pivot:
gamma of it moves with the PRB link, 1 - gamma with the clamping body. Then
f = sqrt(k_q / m_q) / (2 pi), valid about a pose where the spring is unstressed.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexlink.errors import InputError
from flexlink.kinematics.linkage import State
from flexlink.studies.array_shapes import check_shape
from flexlink.units import percent_error


@dataclasses.dataclass(frozen=True)
class PRBResult:
    spring: float  # K [N m/rad]
    stiffness: float  # k_q [N m/rad]
    mass: float  # m_q [kg m^2]
    frequency: float  # [Hz]


def _bar(mass, vp, vq):
    return mass * (vp @ vp + vp @ vq + vq @ vq) / 3.0


def prb_frequency(scene, state: State, strip: str, pivot: str, link_body: str, clamp_body: str,
                  gamma: float, K_theta: float) -> PRBResult:
    """First natural frequency of the PRB model of ``scene`` at ``state`` (see module doc).
    ``strip``: the compliant beam link (its ends: the clamp joint and the ground pin);
    ``pivot``: the joint at the characteristic pivot; ``link_body``/``clamp_body``: the PRB
    link and the body the strip is clamped to."""
    v = {j: np.asarray(d, float) for j, d in state.dpoints.items()}
    links = {s.name: s for s in scene.links}
    strip_spec = links[strip]
    p = {j: np.asarray(xy) for j, xy in state.points.items()}
    length = float(np.linalg.norm(p[strip_spec.end] - p[strip_spec.start]))
    section = strip_spec.section
    spring = gamma * K_theta * section.EI / length
    names = [b.name for b in scene.linkage.bodies]
    k_rel = state.K[names.index(link_body)] - state.K[names.index(clamp_body)]
    mass = 0.0
    for spec in scene.links:
        m = spec.section.mass_per_length * float(np.linalg.norm(p[spec.end] - p[spec.start]))
        if spec.name == strip:
            ground_end = spec.start if spec.start in scene.linkage.ground else spec.end
            clamp_end = spec.end if ground_end == spec.start else spec.start
            mass += _bar(gamma * m, v[ground_end], v[pivot])
            mass += _bar((1 - gamma) * m, v[pivot], v[clamp_end])
        else:
            mass += _bar(m, v[spec.start], v[spec.end])
    for joint in scene.joints:
        mass += joint.mass * float(v[joint.name] @ v[joint.name])
    stiffness = spring * k_rel**2
    return PRBResult(spring=spring, stiffness=stiffness, mass=mass,
                     frequency=math.sqrt(stiffness / mass) / (2 * math.pi))


@dataclasses.dataclass(frozen=True)
class PrbComparison:
    """The scene's FE modes [Hz] at its start pose (strip unstressed) beside the PRB model's
    first frequency; ``points`` [m] are the joints of that pose."""

    crank_angle: float  # [rad]
    points: dict[str, tuple[float, float]]
    fe: tuple[float, ...]
    prb: PRBResult

    def __post_init__(self):
        if np.ndim(self.fe) != 1 or not len(self.fe):  # the comparison is with fe[0]
            raise ValueError(f"PrbComparison.fe has shape {np.shape(self.fe)}, expected "
                             "(at least 1,)")
        for name, xy in self.points.items():
            check_shape("PrbComparison", f"points[{name!r}]", xy, (2,))

    @property
    def prb_vs_fe_pct(self) -> float:
        return percent_error(self.prb.frequency, self.fe[0])


def compare_prb(scene, n_modes: int, elements: int | None = None) -> PrbComparison:
    """FE and PRB first frequencies of a scene with a [prb] table (InputError without one)."""
    from flexlink.analysis.modal import pose_modes  # studies sit above analysis

    p = scene.options.prb
    if p is None:
        raise InputError("no [prb] table: nothing to compare", source=scene.path, field="prb")
    state = scene.linkage.solve(scene.start, scene.guess)
    prb = prb_frequency(scene, state, p.strip, p.pivot, p.link, p.clamp, p.gamma, p.K_theta)
    modes = pose_modes(scene.topology(elements), state.points, n_modes)[1]
    fe = tuple(float(f) for f in modes.elastic_frequencies[:n_modes])
    return PrbComparison(scene.start, dict(state.points), fe, prb)
