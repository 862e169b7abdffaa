"""The rigid-motion study of a scene over one crank revolution: every body's angle, velocity
coefficient K and its derivative L, limit positions, swing and time ratio of rockers, torque
ratio, transmission angles; and the same for every member of the scene's [[family]] tables."""

from __future__ import annotations

import dataclasses
import math

from flexlink.kinematics.linkage import Cycle
from flexlink.kinematics.motion import (BodySummary, Extremes, LimitPosition, body_summary,
                                        extremes, limit_positions)
from flexlink.scene import Scene
from flexlink.scene import load_scene
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.cycle.modal_map import kinematic_cycle, transmission_angles


@dataclasses.dataclass(frozen=True)
class BodyMotion:
    """One body over the cycle: its ``summary`` (extremes of angle, K, L, omega, alpha and the
    torque ratio); for a body turning back and forth about a ground pivot its ``limits``
    (limit positions), the ``swing`` [deg] between them and, with exactly two, the
    ``time_ratio`` [-] (None where there is none)."""

    summary: BodySummary
    limits: tuple[LimitPosition, ...] = ()
    swing: float | None = None
    time_ratio: float | None = None

    def __post_init__(self):
        if (self.swing is None) != (not self.limits):
            raise ValueError(f"BodyMotion.swing is {self.swing} with {len(self.limits)} limit "
                             "positions, expected a swing exactly when there are limit positions")
        if (self.time_ratio is None) != (len(self.limits) != 2):
            raise ValueError(f"BodyMotion.time_ratio is {self.time_ratio} with "
                             f"{len(self.limits)} limit positions, expected one exactly when "
                             "there are two")
        if self.time_ratio is not None and not self.time_ratio >= 1.0:
            raise ValueError(f"BodyMotion.time_ratio is {self.time_ratio}, expected >= 1")


@dataclasses.dataclass(frozen=True)
class MotionStudy:
    """The rigid motion of ``scene`` over one revolution: the ``cycle`` (angles, K and L at
    every sampled crank angle), the crank speed [rad/s] omega and alpha are given at (None:
    none), each body's motion by name in the cycle's body order, and the extremes of each
    transmission angle [deg] by body pair."""

    scene: Scene
    cycle: Cycle
    crank_speed: float | None
    bodies: dict[str, BodyMotion]
    transmission: dict[str, Extremes]

    def __post_init__(self):
        poses, names = len(self.cycle.q), self.cycle.body_names
        check_shape("MotionStudy", "cycle.q", self.cycle.q, (poses,))
        for name in ("angles", "K", "L"):
            check_shape("MotionStudy", f"cycle.{name}", getattr(self.cycle, name),
                        (poses, len(names)))
        if tuple(self.bodies) != tuple(names):
            raise ValueError(f"MotionStudy.bodies has {list(self.bodies)}, expected the "
                             f"cycle's bodies {list(names)}")
        for name, body in self.bodies.items():
            if (body.summary.omega is None) == bool(self.crank_speed):
                raise ValueError(f"MotionStudy.bodies[{name!r}] has omega "
                                 f"{'missing' if body.summary.omega is None else 'given'} at "
                                 f"crank speed {self.crank_speed}, expected it exactly at a "
                                 "crank speed")

    @property
    def poses(self) -> int:
        """Sampled crank angles over the revolution."""
        return len(self.cycle.q)


@dataclasses.dataclass(frozen=True)
class VariantMotion:
    """The motion study of one member of a [[family]] table: the table's ``name``, the scene
    key (``field``) it sets and the ``value`` it sets it to, and the ``study``."""

    name: str
    field: str
    value: float | int | str
    study: MotionStudy


def time_ratio(limits: tuple[LimitPosition, ...]) -> float:
    """Crank turn [deg] from the first limit position to the second over the turn back (>= 1)."""
    a, b = limits[0].crank_deg, limits[1].crank_deg
    forward = (b - a) % 360.0
    return max(forward, 360.0 - forward) / min(forward, 360.0 - forward)


def _body_motion(scene: Scene, cycle: Cycle, name: str, crank_speed: float | None) -> BodyMotion:
    """The motion of body ``name``; limit positions only for a body turning about a ground
    pivot other than the crank."""
    linkage = scene.linkage
    output = name != linkage.driver and linkage.body(name).joints[0] in linkage.ground
    summary = body_summary(cycle, name, crank_speed, output)
    limits = limit_positions(linkage, cycle, name) if output else ()
    if not limits:
        return BodyMotion(summary)
    angles = [lim.angle_deg for lim in limits]
    return BodyMotion(summary, limits, max(angles) - min(angles),
                      time_ratio(limits) if len(limits) == 2 else None)


def motion_study(scene: Scene, poses: int, crank_speed: float | None,
                 progress=None) -> MotionStudy:
    """The cycle at ``poses`` crank angles and what it amounts to: per body the extremes
    (``motion.body_summary``; omega [rad/s] and alpha [rad/s^2] given ``crank_speed``
    [rad/s]), and for a body turning about a ground pivot its limit positions [deg], swing
    [deg] and time ratio; the transmission angles' extremes [deg]."""
    cycle = kinematic_cycle(scene, poses, progress)
    bodies = {b.name: _body_motion(scene, cycle, b.name, crank_speed)
              for b in scene.linkage.bodies}
    mu = {k: extremes(cycle.q, v * 180 / math.pi)
          for k, v in transmission_angles(scene, cycle).items()}
    return MotionStudy(scene, cycle, crank_speed, bodies, mu)


def variant_studies(scene_path, scene: Scene, poses: int,
                    crank_speed: float | None) -> tuple[VariantMotion, ...]:
    """``motion_study`` of every variant the scene's [[family]] tables declare (the scene file
    reloaded with ``field = value``), with the variant's name, field and value."""
    return tuple(VariantMotion(variant.name, variant.field, value, motion_study(
                     load_scene(scene_path, overrides={variant.field: value}), poses,
                     crank_speed))
                 for variant in scene.options.variants for value in variant.values)
