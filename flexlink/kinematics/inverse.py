"""Inverse dynamics of a linkage whose crank motion is prescribed: the driving torque and the
joint forces that make every rigid body follow ``dynamics.RigidMotion``, given the bodies' mass
properties and the external loads at that instant.

Newton-Euler per moving body b (planar, moments about its centre of mass G):
    sum_j F_jb + sum F_ext = m a_G,
    sum_j (p_j - r_G) x F_jb + sum ((r_ext - r_G) x F_ext + M_ext) + [tau if b drives] = I_G alpha,
with F_jb the force on body b at joint j. A pin joining bodies only (no ground) carries no
mass of its own, so the forces it puts on its bodies sum to zero; at a ground pivot the
ground takes the balance. For a linkage of one degree of freedom this is a square linear
system in the pin forces and the driving torque tau (on the driver from the ground,
counter-clockwise positive, the sense of the crank angle q).
Mass properties: each body's beams as uniform straight bars between their joints
(I_G = m l^2 / 12 + rho I l, the second term the section's own rotary inertia about the
plane normal) plus the joint masses as point masses, lumped on the first body that carries
the joint (so a pin's force is reported between the body carrying its mass and the others).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence

import numpy as np

from flexlink.errors import InputError, KinematicsError
from flexlink.kinematics.dynamics import RigidMotion
from flexlink.kinematics.linkage import Linkage


@dataclasses.dataclass(frozen=True)
class BodyMass:
    """Mass [kg], centre of mass in the body frame (origin its first joint, x axis to its
    second) [m], and moment of inertia about the centre of mass [kg m^2]."""

    body: str
    mass: float
    centroid: tuple[float, float]
    inertia: float

    def __post_init__(self):
        if not (self.mass >= 0 and self.inertia >= 0 and np.all(np.isfinite(self.centroid))):
            raise InputError(f"body {self.body!r}: mass {self.mass!r} kg and inertia "
                             f"{self.inertia!r} kg m^2 must be finite and >= 0", field="bodies")


@dataclasses.dataclass(frozen=True)
class Bar:
    """A uniform straight bar from joint ``start`` to joint ``end``: mass per length [kg/m] and
    rotary inertia per length about the plane normal [kg m] (density x in-plane second moment)."""

    name: str
    start: str
    end: str
    mass_per_length: float
    rotary_per_length: float = 0.0


@dataclasses.dataclass(frozen=True)
class Wrench:
    """An external load on ``body`` at one instant: a force [N] (global x, y) at the global
    point ``point`` [m], and a torque [N m] (counter-clockwise positive)."""

    body: str
    force: tuple[float, float] = (0.0, 0.0)
    point: tuple[float, float] = (0.0, 0.0)
    torque: float = 0.0


@dataclasses.dataclass(frozen=True)
class InverseDynamics:
    """At one crank angle: the driving torque [N m] on the driver (counter-clockwise
    positive), the force [N] on each body at each of its joints (keyed (joint, body)), the
    kinetic energy [J] and the power of the external loads [W]."""

    q: float
    torque: float
    forces: dict[tuple[str, str], np.ndarray]
    kinetic_energy: float
    load_power: float


def _cross(r, f) -> float:
    return float(r[0] * f[1] - r[1] * f[0])


def body_masses(linkage: Linkage, bars: Sequence[Bar],
                point_masses: Mapping[str, float] = {}) -> tuple[BodyMass, ...]:
    """Each body's mass properties (``Linkage.bodies`` order) from the bars on it and the
    joint masses [kg]. A bar whose two joints are not on one body is refused (a compliant
    link has no rigid-body motion of its own)."""
    parts = {b.name: [] for b in linkage.bodies}  # (mass, local centre, own inertia)
    for bar in bars:
        body = next((b for b in linkage.bodies if bar.start in b.joints and bar.end in b.joints),
                    None)
        if body is None:
            raise InputError(f"link {bar.name!r} ({bar.start} to {bar.end}) is not on one rigid "
                             "body: a compliant link has no rigid-body motion, so the rigid-body "
                             "dynamics cannot carry its mass", field=f"links.{bar.name}")
        a, b = (np.array(body.shape[body.joints.index(j)]) for j in (bar.start, bar.end))
        length = float(np.linalg.norm(b - a))
        m = bar.mass_per_length * length
        parts[body.name].append((m, (a + b) / 2, m * length**2 / 12 + bar.rotary_per_length * length))
    for joint, m in point_masses.items():
        if m > 0 and joint not in linkage.ground:  # a ground pivot's mass never moves
            body = next((b for b in linkage.bodies if joint in b.joints), None)
            if body is None:
                raise InputError(f"joint {joint!r} is on no body", field=f"joints.{joint}.mass")
            parts[body.name].append((m, np.array(body.shape[body.joints.index(joint)]), 0.0))
    out = []
    for name, items in parts.items():
        mass = sum(m for m, _, _ in items)
        centre = (sum(m * c for m, c, _ in items) / mass) if mass > 0 else np.zeros(2)
        inertia = sum(i + m * float((c - centre) @ (c - centre)) for m, c, i in items)
        out.append(BodyMass(name, float(mass), (float(centre[0]), float(centre[1])),
                            float(inertia)))
    return tuple(out)


def centre_of_mass(linkage: Linkage, motion: RigidMotion, mass: BodyMass) -> np.ndarray:
    """Global position [m] of a body's centre of mass at the pose of ``motion``."""
    body = linkage.body(mass.body)
    p0, p1 = (motion.points[j] for j in body.joints[:2])
    e = (p1 - p0) / np.linalg.norm(p1 - p0)
    cx, cy = mass.centroid
    return p0 + cx * e + cy * np.array([-e[1], e[0]])


def _attachments(linkage: Linkage) -> list[tuple[str, list[str]]]:
    """(joint, the moving bodies carrying it) for every joint carried by a body."""
    out: dict[str, list[str]] = {}
    for b in linkage.bodies:
        for j in b.joints:
            out.setdefault(j, []).append(b.name)
    return list(out.items())


@dataclasses.dataclass(frozen=True)
class NewtonEuler:
    """The Newton-Euler equations of every moving body at one instant as a square linear
    system ``matrix @ x = rhs``: x holds the force [N] on each body at each of its joints (at
    ``columns[(joint, body)]``, x then y) and, last, the driving torque [N m]. ``moment_rows``
    names each body's moment equation (an external torque tau on body b adds +tau to the
    left side of row ``moment_rows[b]``). Kinetic energy [J] and the power of ``loads`` [W]
    at that instant come with it."""

    matrix: np.ndarray
    rhs: np.ndarray
    columns: dict[tuple[str, str], int]
    moment_rows: dict[str, int]
    kinetic_energy: float
    load_power: float


def newton_euler(linkage: Linkage, motion: RigidMotion, masses: Sequence[BodyMass],
                 loads: Sequence[Wrench] = ()) -> NewtonEuler:
    """The equations of the module doc at the instant of ``motion``."""
    names = [b.name for b in linkage.bodies]
    if [m.body for m in masses] != names:
        raise InputError("one BodyMass per body, in Linkage.bodies order", field="masses")
    for load in loads:
        if load.body not in names:
            raise InputError(f"a load on {load.body!r}, which is not a body", field="loads",
                             expected=f"one of {names}")
    attach = _attachments(linkage)
    unknowns = [(j, b) for j, bodies in attach for b in bodies]
    col = {key: 2 * i for i, key in enumerate(unknowns)}
    n = 2 * len(unknowns) + 1  # the last unknown: the driving torque
    rows, rhs, moment_rows = [], [], {}
    centres = {m.body: centre_of_mass(linkage, motion, m) for m in masses}
    kinetic, load_power = 0.0, 0.0
    for i, (b, m) in enumerate(zip(linkage.bodies, masses)):
        g = centres[b.name]
        a_g = motion.point_acceleration(b.name, g)
        v_g = motion.point_velocity(b.name, g)
        kinetic += 0.5 * m.mass * float(v_g @ v_g) + 0.5 * m.inertia * motion.omega[i] ** 2
        force, moment = m.mass * a_g, m.inertia * motion.alpha[i]
        for load in (w for w in loads if w.body == b.name):
            f, p = np.asarray(load.force, float), np.asarray(load.point, float)
            force = force - f
            moment -= _cross(p - g, f) + load.torque
            load_power += float(f @ motion.point_velocity(b.name, p)) + load.torque * motion.omega[i]
        fx, fy, mz = np.zeros(n), np.zeros(n), np.zeros(n)
        for j in b.joints:
            c = col[(j, b.name)]
            r = motion.points[j] - g
            fx[c], fy[c + 1] = 1.0, 1.0
            mz[c], mz[c + 1] = -r[1], r[0]
        if b.name == linkage.driver:
            mz[-1] = 1.0
        moment_rows[b.name] = len(rows) + 2
        rows += [fx, fy, mz]
        rhs += [force[0], force[1], moment]
    for j, bodies in attach:
        if j in linkage.ground:
            continue
        for axis in range(2):  # a massless pin: its forces on the bodies sum to zero
            r = np.zeros(n)
            for b in bodies:
                r[col[(j, b)] + axis] = 1.0
            rows.append(r)
            rhs.append(0.0)
    A = np.array(rows)
    if A.shape != (n, n):
        raise KinematicsError(f"{A.shape[0]} equations for {n} unknown pin forces and torque: "
                              "the linkage is not a one-degree-of-freedom chain of pins")
    return NewtonEuler(A, np.array(rhs), col, moment_rows, float(kinetic), float(load_power))


def inverse_dynamics(linkage: Linkage, motion: RigidMotion, masses: Sequence[BodyMass],
                     loads: Sequence[Wrench] = ()) -> InverseDynamics:
    """Driving torque and joint forces at the instant of ``motion`` (see the module doc)."""
    system = newton_euler(linkage, motion, masses, loads)
    try:
        x = np.linalg.solve(system.matrix, system.rhs)
    except np.linalg.LinAlgError:
        raise KinematicsError(f"the pin forces are not determined at q = {np.degrees(motion.q):.4f}"
                              " deg (a dead centre)") from None
    forces = {key: x[c:c + 2] for key, c in system.columns.items()}
    return InverseDynamics(q=motion.q, torque=float(x[-1]), forces=forces,
                           kinetic_energy=system.kinetic_energy, load_power=system.load_power)
