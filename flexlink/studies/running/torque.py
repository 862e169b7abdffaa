"""Driving torque and joint forces over one crank turn at a crank speed: the rigid-body
inverse dynamics (``kinematics.inverse``) of a scene at every pose of its cycle, with the
bodies' mass properties from the beams and joint masses the scene states and its
``[[loads]]``."""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.errors import InputError, KinematicsError
from flexlink.kinematics.dynamics import check_speed, rigid_motion
from flexlink.kinematics.inverse import (
    Bar,
    BodyMass,
    InverseDynamics,
    body_masses,
    inverse_dynamics,
)
from flexlink.kinematics.linkage import NEAR_SINGULAR, Linkage, State
from flexlink.scene import Scene
from flexlink.scene.contract import LoadSpec
from flexlink.scene.loads import wrench
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.cycle.modal_map import kinematic_cycle
from flexlink.units import degrees_in_turn

MODEL = (
    ("rigid-body motion prescribed by the crank: the crank speed (and angular acceleration, if "
     "given) applies at every crank angle"),
    "elastic deflections are small and are not fed back into the motion or the loads",
    ("each beam is a uniform straight bar between its joints (mass from its section and "
     "material; I = m l^2/12 + rho I_section l); joint masses are point masses on the first "
     "body carrying the joint"),
    "no friction; no gravity; external loads only as declared in [[loads]]",
)


@dataclasses.dataclass(frozen=True)
class TorqueCurve:
    """Over the crank angles ``q`` [rad]: driving torque [N m] on the crank (counter-clockwise
    positive), drive power tau Omega [W], kinetic energy [J], power of the external loads [W],
    and the force [N] (x, y) on each body at each of its joints, keyed "joint:body"."""

    scene: str
    speed: float  # [rad/s]
    crank_acceleration: float  # [rad/s^2]
    q: np.ndarray
    torque: np.ndarray
    power: np.ndarray
    kinetic_energy: np.ndarray
    load_power: np.ndarray
    forces: dict[str, np.ndarray]
    masses: tuple[BodyMass, ...]
    singular: np.ndarray  # (n,) bool: a pose whose motion is not determined; NaN rows there
    at_pose: InverseDynamics | None = None  # at the scene's own pose; None where singular
    loads: tuple[LoadSpec, ...] = ()
    model: tuple[str, ...] = MODEL
    turn_closes: bool = True  # False: after one turn the linkage is on another assembly

    def __post_init__(self):
        n = len(self.q)
        for name in ("torque", "power", "kinetic_energy", "load_power", "singular"):
            check_shape("TorqueCurve", name, getattr(self, name), (n,))
        for key, force in self.forces.items():
            check_shape("TorqueCurve", f"forces[{key!r}]", force, (n, 2))
        if np.asarray(self.singular).all():
            raise ValueError("every pose is singular: no torque to show")

    def summary(self) -> dict:
        """Peak (largest magnitude), largest, smallest and mean torque [N m] and power [W]
        over the poses whose motion is determined (means over the crank angle, which at
        constant speed are the means over time)."""
        deg = degrees_in_turn(self.q)
        ok = np.flatnonzero(~self.singular)
        torque, power = self.torque[ok], self.power[ok]
        i, hi, lo = (ok[np.argmax(np.abs(torque))], ok[np.argmax(torque)], ok[np.argmin(torque)])
        j = ok[np.argmax(np.abs(power))]
        return {"peak_torque_N_m": float(self.torque[i]), "peak_torque_at_deg": float(deg[i]),
                "max_torque_N_m": float(self.torque[hi]), "max_torque_at_deg": float(deg[hi]),
                "min_torque_N_m": float(self.torque[lo]), "min_torque_at_deg": float(deg[lo]),
                "mean_torque_N_m": float(torque.mean()),
                "rms_torque_N_m": float(np.sqrt(np.mean(torque**2))),
                "mean_power_W": float(power.mean()),
                "peak_power_W": float(self.power[j]), "peak_power_at_deg": float(deg[j])}


def scene_masses(scene: Scene) -> tuple[BodyMass, ...]:
    """Each body's mass properties from the scene's beams and joint masses."""
    bars = [Bar(link.name, link.start, link.end, link.section.mass_per_length,
                link.section.density * link.section.second_moment) for link in scene.links]
    try:
        return body_masses(scene.linkage, bars, {j.name: j.mass for j in scene.joints})
    except InputError as exc:
        raise InputError(str(exc), source=scene.path) from None


def torque_study(scene: Scene, speed: float, crank_acceleration: float = 0.0,
                 poses: int = 360, progress=None,
                 fields: tuple[str, str] = ("operation.crank_speed",
                                            "operation.crank_acceleration")) -> TorqueCurve:
    """The driving torque and joint forces of ``scene`` at ``poses`` crank angles over one
    turn, at crank speed ``speed`` [rad/s] and angular acceleration ``crank_acceleration``
    [rad/s^2], and at the scene's own pose. A pose whose motion is not determined (a dead
    centre or a change-point linkage's flat pose: ``linkage.NEAR_SINGULAR``) is marked
    singular and left out (NaN), never averaged in. Refuses a scene with neither masses nor
    loads, one with a compliant link (a beam not on one rigid body), and an operating point
    whose torque or forces overflow, naming the one of ``fields`` (where the speed and the
    acceleration were given) whose term is the larger."""
    check_speed(speed, crank_acceleration)
    masses = scene_masses(scene)
    if not scene.loads and not any(m.mass > 0 for m in masses):
        raise InputError("no masses and no loads: the scene has no [links] beams or joint "
                         "masses and no [[loads]], so nothing loads the drive",
                         source=scene.path, field="links")
    linkage = scene.linkage
    cycle = kinematic_cycle(scene, poses, progress)
    singular = np.array([linkage.conditioning(s) < NEAR_SINGULAR for s in cycle.states])
    if singular.all():
        raise KinematicsError("every sampled pose is singular: the motion is not determined "
                              "at any of them")
    closes = _turn_closes(linkage, cycle)
    pose_state = scene.rigid_state(None)
    states = [None if flat else s for s, flat in zip(cycle.states, singular)]
    if linkage.conditioning(pose_state) >= NEAR_SINGULAR:
        states.append(pose_state)  # the scene's own pose last
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused below
        try:
            rows = [None if s is None else _dynamics(scene, s, speed, crank_acceleration, masses)
                    for s in states]
        except InputError as exc:  # an overflowing motion, named where the user gave its cause
            field = fields[0] if exc.field == "speed" else fields[1]
            raise InputError(str(exc).split(": ", 1)[-1], source=scene.path, field=field) from None
        first = next(r for r in rows if r is not None)
        keys = [k for k in first.forces if _reported(linkage, *k)]

        def column(value):
            return np.array([np.full(np.shape(value(first)), np.nan) if r is None else value(r)
                             for r in rows])
        forces = {f"{j}:{b}": column(lambda r, key=(j, b): r.forces[key]) for j, b in keys}
        torque = _without_round_off(column(lambda r: r.torque), forces, linkage.size)
        n = len(cycle.q)
        at_pose = None if len(rows) == n else dataclasses.replace(rows[-1], torque=torque[-1])
        curve = TorqueCurve(scene=scene.name, speed=speed, crank_acceleration=crank_acceleration,
                            q=cycle.q, torque=torque[:n], power=torque[:n] * speed,
                            kinetic_energy=column(lambda r: r.kinetic_energy)[:n],
                            load_power=column(lambda r: r.load_power)[:n],
                            forces={k: f[:n] for k, f in forces.items()}, masses=masses,
                            singular=singular, at_pose=at_pose, loads=scene.loads,
                            turn_closes=closes)
        _check_finite(curve, scene, fields)
    return curve


ROUND_OFF = 1e-12  # a torque below this share of the pin forces' moment is round-off
SEAM = 1e-9  # a joint this share of the linkage's size from where the turn began: the same pose


def _turn_closes(linkage: Linkage, cycle) -> bool:
    """Whether the motion, continued one step past the last sampled pose to the first crank
    angle a turn on, is back at the first pose: not where it passed a change point's flat pose
    onto the other assembly (then the turn's curves do not join and its means are no cycle's)."""
    last = cycle.states[-1]
    after = linkage.solve(cycle.q[0] + 2.0 * np.pi, dict(last.points))
    first = cycle.states[0].points
    gap = max(float(np.hypot(*np.subtract(after.points[k], first[k]))) for k in first)
    return gap <= SEAM * linkage.size


def _without_round_off(torque: np.ndarray, forces: dict[str, np.ndarray],
                       size: float) -> np.ndarray:
    """``torque`` [N m] with the values below ROUND_OFF times the largest pin force [N] times
    the linkage's ``size`` [m] set to 0: the pin solve leaves about 1e-16 of that moment, so a
    balanced rotor's torque, exactly 0, would otherwise show as a jagged +-1e-13 N m."""
    moments = [np.nanmax(np.hypot(f[:, 0], f[:, 1])) * size for f in forces.values()]
    floor = ROUND_OFF * max(moments, default=0.0)
    return np.where(np.abs(torque) <= floor, 0.0, torque)  # +0.0, never -0.0


def torque_at(scene: Scene, speed: float, crank_acceleration: float,
              crank_angle: float) -> InverseDynamics:
    """The inverse dynamics of ``scene`` at ``crank_angle`` [rad] (on the scene's assembly),
    crank speed ``speed`` [rad/s] and acceleration ``crank_acceleration`` [rad/s^2]."""
    check_speed(speed, crank_acceleration)
    return _dynamics(scene, scene.rigid_state(crank_angle), speed, crank_acceleration,
                     scene_masses(scene))


def _dynamics(scene: Scene, state: State, speed: float, crank_acceleration: float,
              masses) -> InverseDynamics:
    linkage = scene.linkage
    motion = rigid_motion(linkage, state, speed, crank_acceleration)
    loads = [wrench(linkage, state, load) for load in scene.loads]
    return inverse_dynamics(linkage, motion, masses, loads)


def _check_finite(curve: TorqueCurve, scene: Scene, fields: tuple[str, str]) -> None:
    """InputError when a torque, force, energy or power of ``curve`` (or its summary: the rms
    squares the torque) is beyond the floating-point range."""
    ok = ~curve.singular
    values = [curve.torque[ok], curve.power[ok], curve.kinetic_energy[ok],
              curve.load_power[ok], *(f[ok] for f in curve.forces.values()),
              np.array(list(curve.summary().values()))]
    if curve.at_pose is not None:
        values.append(np.array([curve.at_pose.torque, curve.at_pose.kinetic_energy]))
    if all(np.isfinite(v).all() for v in values):
        return
    speed, acc = curve.speed, curve.crank_acceleration
    field = fields[1] if abs(acc) > speed * speed else fields[0]
    raise InputError(f"the driving torque at {speed:.6g} rad/s and {acc:.6g} rad/s^2 "
                     "overflows the floating-point range", source=scene.path, field=field,
                     expected="a crank speed and acceleration a machine can have")


def _reported(linkage: Linkage, joint: str, body: str) -> bool:
    """A joint force worth a column: at a ground pivot, or on a body that shares the joint with
    an earlier body (the first body's force at a pin is minus the sum of the others)."""
    if joint in linkage.ground:
        return True
    carriers = [b.name for b in linkage.bodies if joint in b.joints]
    return len(carriers) > 1 and body != carriers[0]
