"""Rigid-body motion at a crank speed: angular velocities and accelerations of every body and
velocities and accelerations of any point, from the velocity and acceleration coefficients of
``linkage.State``.

The crank angle q(t) is prescribed (speed Omega = qdot, acceleration qddot). With the
coefficients K = dtheta/dq, L = dK/dq per body and p' = dp/dq, p'' = d2p/dq2 per joint:
    omega = K Omega,          alpha = K qddot + L Omega^2,
    v_joint = p' Omega,       a_joint = p'' Omega^2 + p' qddot.
A point r of a body whose first joint is j0 (a rigid body in the plane):
    v = v_j0 + omega k x (r - p_j0),    a = a_j0 + alpha k x (r - p_j0) - omega^2 (r - p_j0).
Elastic deflections are not part of this motion (they are small and do not feed back).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexlink.errors import InputError
from flexlink.kinematics.linkage import Linkage, State


def _perp(r: np.ndarray) -> np.ndarray:
    """k x r for planar vectors r (..., 2): (x, y) -> (-y, x)."""
    return np.stack([-r[..., 1], r[..., 0]], axis=-1)


@dataclasses.dataclass(frozen=True)
class RigidMotion:
    """Rigid-body motion of every body at one crank angle (SI units)."""

    q: float  # crank angle [rad]
    speed: float  # crank angular speed Omega [rad/s]
    crank_acceleration: float  # crank angular acceleration [rad/s^2]
    bodies: tuple[str, ...]  # body names, Linkage.bodies order
    omega: np.ndarray  # angular velocity per body [rad/s]
    alpha: np.ndarray  # angular acceleration per body [rad/s^2]
    points: dict[str, np.ndarray]  # joint positions [m]
    velocities: dict[str, np.ndarray]  # joint velocities [m/s]
    accelerations: dict[str, np.ndarray]  # joint accelerations [m/s^2]
    anchors: dict[str, str] = dataclasses.field(repr=False, default_factory=dict)
    # body -> the joint its motion is referred to (its first joint)

    def __post_init__(self):
        n = len(self.bodies)
        if np.shape(self.omega) != (n,) or np.shape(self.alpha) != (n,):
            raise ValueError(f"omega and alpha need one value per body ({n})")

    def _index(self, body: str) -> int:
        if body not in self.bodies:
            raise InputError(f"no body {body!r}", field="body", expected=f"one of {list(self.bodies)}")
        return self.bodies.index(body)

    def _arm(self, body: str, xy) -> tuple[int, np.ndarray, str]:
        i = self._index(body)
        anchor = self.anchors[body]
        return i, np.asarray(xy, float) - self.points[anchor], anchor

    def point_velocity(self, body: str, xy) -> np.ndarray:
        """Velocity [m/s] of the point(s) ``xy`` (..., 2) [m, global] fixed on ``body``."""
        i, r, anchor = self._arm(body, xy)
        return self.velocities[anchor] + self.omega[i] * _perp(r)

    def point_acceleration(self, body: str, xy) -> np.ndarray:
        """Acceleration [m/s^2] of the point(s) ``xy`` (..., 2) [m, global] fixed on ``body``."""
        i, r, anchor = self._arm(body, xy)
        return (self.accelerations[anchor] + self.alpha[i] * _perp(r)
                - self.omega[i] ** 2 * r)


def check_speed(speed: float, crank_acceleration: float = 0.0) -> None:
    """Refuse a crank speed or acceleration that is not a finite number."""
    for name, value, unit in (("speed", speed, "rad/s"),
                              ("crank_acceleration", crank_acceleration, "rad/s^2")):
        if not (isinstance(value, (int, float)) and math.isfinite(value)):
            raise InputError(f"got {value!r}", field=name, expected=f"a finite value in {unit}")


def rigid_motion(linkage: Linkage, state: State, speed: float,
                 crank_acceleration: float = 0.0) -> RigidMotion:
    """The rigid motion at ``state`` (a pose of ``linkage``, with its coefficients) for crank
    speed ``speed`` [rad/s] and crank angular acceleration ``crank_acceleration`` [rad/s^2]."""
    check_speed(speed, crank_acceleration)
    w, a = float(speed), float(crank_acceleration)
    points = {j: np.asarray(p, float) for j, p in state.points.items()}
    velocities = {j: np.asarray(state.dpoints[j], float) * w for j in points}
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused below
        accelerations = {j: np.asarray(state.ddpoints[j], float) * w * w
                         + np.asarray(state.dpoints[j], float) * a for j in points}
    squared = w * w
    if not (math.isfinite(squared) and all(np.isfinite(v).all() for v in accelerations.values())):
        raise InputError(f"a crank speed of {w:g} rad/s with an acceleration of {a:g} rad/s^2 "
                         f"overflows the rigid-body accelerations (Omega^2 = {squared:g})",
                         field="speed" if squared > abs(a) else "crank_acceleration",
                         expected="a crank speed and acceleration a machine can have")
    return RigidMotion(
        q=float(state.q), speed=w, crank_acceleration=a,
        bodies=tuple(b.name for b in linkage.bodies),
        omega=np.asarray(state.K, float) * w,
        alpha=np.asarray(state.K, float) * a + np.asarray(state.L, float) * w * w,
        points=points, velocities=velocities, accelerations=accelerations,
        anchors={b.name: b.joints[0] for b in linkage.bodies})
