"""Driving torque and joint forces over one crank turn at a crank speed: the rigid-body
inverse dynamics (``kinematics.inverse``) of a scene at every pose of its cycle, with the
bodies' mass properties from the beams and joint masses the scene states and its
``[[loads]]``."""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.errors import InputError
from flexlink.kinematics.dynamics import check_speed, rigid_motion
from flexlink.kinematics.inverse import Bar, BodyMass, body_masses, inverse_dynamics
from flexlink.kinematics.linkage import Linkage
from flexlink.scene import Scene
from flexlink.scene.loads import wrench
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.cycle.modal_map import kinematic_cycle

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
    model: tuple[str, ...] = MODEL

    def __post_init__(self):
        n = len(self.q)
        for name in ("torque", "power", "kinetic_energy", "load_power"):
            check_shape("TorqueCurve", name, getattr(self, name), (n,))
        for key, force in self.forces.items():
            check_shape("TorqueCurve", f"forces[{key!r}]", force, (n, 2))

    def summary(self) -> dict:
        """Peak (largest magnitude), largest, smallest and mean torque [N m] and power [W]
        (means over the crank angle, which at constant speed are the means over time)."""
        deg = np.degrees(self.q) % 360.0
        i, hi, lo = (int(np.argmax(np.abs(self.torque))), int(np.argmax(self.torque)),
                     int(np.argmin(self.torque)))
        j = int(np.argmax(np.abs(self.power)))
        return {"peak_torque_N_m": float(self.torque[i]), "peak_torque_at_deg": float(deg[i]),
                "max_torque_N_m": float(self.torque[hi]), "max_torque_at_deg": float(deg[hi]),
                "min_torque_N_m": float(self.torque[lo]), "min_torque_at_deg": float(deg[lo]),
                "mean_torque_N_m": float(self.torque.mean()),
                "rms_torque_N_m": float(np.sqrt(np.mean(self.torque**2))),
                "mean_power_W": float(self.power.mean()),
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
                 poses: int = 360, progress=None) -> TorqueCurve:
    """The driving torque and joint forces of ``scene`` at ``poses`` crank angles over one
    turn, at crank speed ``speed`` [rad/s] and angular acceleration ``crank_acceleration``
    [rad/s^2]. Refuses a scene with neither masses nor loads, and one with a compliant link
    (a beam not on one rigid body)."""
    check_speed(speed, crank_acceleration)
    masses = scene_masses(scene)
    if not scene.loads and not any(m.mass > 0 for m in masses):
        raise InputError("no masses and no loads: the scene has no [links] beams or joint "
                         "masses and no [[loads]], so nothing loads the drive",
                         source=scene.path, field="links")
    linkage = scene.linkage
    cycle = kinematic_cycle(scene, poses, progress)
    rows = []
    for state in cycle.states:
        motion = rigid_motion(linkage, state, speed, crank_acceleration)
        loads = [wrench(linkage, state, load) for load in scene.loads]
        rows.append(inverse_dynamics(linkage, motion, masses, loads))
    torque = np.array([r.torque for r in rows])
    keys = [k for k in rows[0].forces if _reported(linkage, *k)]
    forces = {f"{j}:{b}": np.array([r.forces[(j, b)] for r in rows]) for j, b in keys}
    return TorqueCurve(scene=scene.name, speed=speed, crank_acceleration=crank_acceleration,
                       q=cycle.q, torque=torque, power=torque * speed,
                       kinetic_energy=np.array([r.kinetic_energy for r in rows]),
                       load_power=np.array([r.load_power for r in rows]), forces=forces,
                       masses=masses)


def _reported(linkage: Linkage, joint: str, body: str) -> bool:
    """A joint force worth a column: at a ground pivot, or on a body that shares the joint with
    an earlier body (the first body's force at a pin is minus the sum of the others)."""
    if joint in linkage.ground:
        return True
    carriers = [b.name for b in linkage.bodies if joint in b.joints]
    return len(carriers) > 1 and body != carriers[0]
