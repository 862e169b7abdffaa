"""The driving torque of every member of a scene's [[family]] tables (``studies.running.torque``
per member, the scene file reloaded with the member's value): the peak, largest, smallest and
rms torque over the turn and where they are, with the member's link lengths and the rocker's
moment of inertia about its pivot, the inputs a family changes."""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.scene import Scene, load_scene
from flexlink.studies.cycle.rigid_motion import family_member
from flexlink.studies.running.torque import torque_study


@dataclasses.dataclass(frozen=True)
class MemberTorque:
    """One member: its table's name, key and value; ``summary`` as ``TorqueCurve.summary``
    ([N m], [W], [deg]); the body lengths [m] and each output's moment of inertia about its
    ground pivot [kg m^2]."""

    family: str
    field: str
    value: object
    summary: dict
    lengths: dict[str, float]
    pivot_inertia: dict[str, float]


@dataclasses.dataclass(frozen=True)
class FamilyTorques:
    scene: str
    speed: float  # [rad/s]
    members: tuple[MemberTorque, ...]


def _pivot_inertia(scene: Scene, masses) -> dict[str, float]:
    """I about the ground pivot [kg m^2] of each body turning about one (parallel axes)."""
    out = {}
    for body, m in zip(scene.linkage.bodies, masses):
        if body.joints[0] in scene.linkage.ground and body.name != scene.linkage.driver:
            out[body.name] = m.inertia + m.mass * float(np.hypot(*m.centroid) ** 2)
    return out


def family_torques(scene_path, scene: Scene, speed: float, poses: int = 360,
                   progress=None) -> FamilyTorques:
    """The driving torque at crank speed ``speed`` [rad/s] of every [[family]] member of the
    scene at ``path``; a member that cannot be built or closed is refused naming its entry."""
    plan = [(i, j) for i, v in enumerate(scene.options.variants) for j in range(len(v.values))]
    members = []
    for i, j in (progress(plan) if progress else plan):
        variant = scene.options.variants[i]
        with family_member(scene, i, j):
            member = load_scene(scene_path, overrides={variant.field: variant.values[j]})
            curve = torque_study(member, speed, 0.0, poses)
        members.append(MemberTorque(
            variant.name, variant.field, variant.values[j], curve.summary(),
            {b.name: b.length for b in member.linkage.bodies},
            _pivot_inertia(member, curve.masses)))
    return FamilyTorques(scene.name, float(speed), tuple(members))
