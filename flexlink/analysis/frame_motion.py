"""A scene's frame model moving with its rigid motion at one pose: each beam link's angular
velocity and acceleration, each node's rigid acceleration, the scene's [[loads]] as nodal
loads, and from them the pose's speed terms per unit crank speed and acceleration
(``fe.speed_terms``), the one way every study of the running linkage gets them."""

from __future__ import annotations

import numpy as np

from flexlink.errors import InputError
from flexlink.fe.geometric import GeometricForm
from flexlink.fe.model import FrameModel, Topology
from flexlink.fe.speed_terms import SpeedTerms, UnitMotion, speed_terms
from flexlink.kinematics.dynamics import RigidMotion, rigid_motion
from flexlink.scene import Scene
from flexlink.scene.contract import LoadKind
from flexlink.scene.loads import wrench


def link_bodies(scene: Scene, links) -> tuple[str, ...]:
    """The rigid body each beam link belongs to (the body holding both its joints)."""
    out = []
    for link in links:
        body = next((b.name for b in scene.linkage.bodies
                     if link.start in b.joints and link.end in b.joints), None)
        if body is None:
            raise InputError(f"link {link.name!r} joins {link.start} and {link.end}, which no "
                             "single body of the linkage holds: its rigid motion at speed is "
                             "not one body's (a compliant link)", source=scene.path,
                             field=f"links.{link.name}")
        out.append(body)
    return tuple(out)


def link_motion(scene: Scene, model: FrameModel, topology: Topology, motion: RigidMotion):
    """(omega, alpha) per link [rad/s, rad/s^2] and the rigid acceleration of every node
    (N, 2) [m/s^2] of ``motion``."""
    bodies = link_bodies(scene, topology.links)
    index = {b: i for i, b in enumerate(motion.bodies)}
    omega = np.array([motion.omega[index[b]] for b in bodies])
    alpha = np.array([motion.alpha[index[b]] for b in bodies])
    acc = np.empty((len(model.nodes), 2))
    for link, body in zip(model.links, bodies):
        acc[link.nodes] = motion.point_acceleration(body, model.nodes[link.nodes])
    return omega, alpha, acc


def unit_motion(scene: Scene, model: FrameModel, topology: Topology, state,
                accelerating: bool = False) -> UnitMotion:
    """The rigid motion of ``model``'s links and nodes at the pose ``state`` at 1 rad/s, and
    with ``accelerating`` also from rest at 1 rad/s^2 of crank acceleration."""
    omega, alpha, acc = link_motion(scene, model, topology,
                                    rigid_motion(scene.linkage, state, 1.0, 0.0))
    start = {}
    if accelerating:
        _, start_alpha, start_acc = link_motion(scene, model, topology,
                                                rigid_motion(scene.linkage, state, 0.0, 1.0))
        start = dict(start_alpha=start_alpha, start_acceleration=start_acc)
    return UnitMotion(omega=omega, alpha=alpha, acceleration=acc, **start)


def external_loads(scene: Scene, model: FrameModel, topology: Topology, state) -> np.ndarray:
    """The scene's [[loads]] at the pose ``state`` as nodal loads (n_dofs,) [N, N m], each put
    on the node of its body's beams nearest its point (a torque: nearest the body's first
    joint, its pivot or shaft), a force with the moment of its offset from that node: statically
    the same load on the body, spread over an element length on the flexible frame."""
    f = np.zeros(model.n_dofs)
    bodies = link_bodies(scene, topology.links)
    for load in scene.loads:
        own = [link for link, body in zip(model.links, bodies) if body == load.body]
        if not own:
            raise InputError(f"the load acts on body {load.body!r}, which has no beam link to "
                             "carry it", source=scene.path, field=load.field)
        nodes = np.concatenate([link.nodes for link in own])
        w = wrench(scene.linkage, state, load)
        pivot = state.points[scene.linkage.body(load.body).joints[0]]
        point = np.asarray(pivot if load.kind is LoadKind.TORQUE else w.point, dtype=float)
        node = nodes[np.argmin(np.linalg.norm(model.nodes[nodes] - point, axis=1))]
        r = point - model.nodes[node]
        f[3 * node:3 * node + 2] += w.force
        f[3 * node + 2] += w.torque + r[0] * w.force[1] - r[1] * w.force[0]
    return f


def pose_speed_terms(scene: Scene, topology: Topology, state, model: FrameModel, stiffness, T,
                     assemble, form: GeometricForm = GeometricForm.CONSISTENT,
                     accelerating: bool = False) -> SpeedTerms:
    """``fe.speed_terms.speed_terms`` of ``model`` (``topology`` at the pose ``state`` of
    ``scene``) with the scene's rigid motion and [[loads]]; ``stiffness``, ``T``, ``assemble``,
    ``form`` as there; ``accelerating``: with the terms per unit crank acceleration."""
    return speed_terms(model, stiffness, T, assemble,
                       unit_motion(scene, model, topology, state, accelerating),
                       external_loads(scene, model, topology, state), form)
