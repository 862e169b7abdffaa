"""Modes at an operating point: the small vibrations of the frame about its rigid motion at a
crank speed, against its frozen-pose (static) modes.

Model (kineto-elastodynamic, frozen configuration): the rigid motion is prescribed by the crank
(speed Omega, optional crank acceleration); elastic deflections are small and do not feed back
into it. At the pose, each link turns with its rigid angular velocity omega and acceleration
alpha (``kinematics.dynamics``), and the linearised equations are
    M x'' + G x' + (K + K_g(N) - omega^2 Mt + alpha S) x = 0   (per link),
with K_g the geometric stiffness of the axial forces N of the preload (``fe.preload``,
``fe.geometric``: the d'Alembert inertia loads and the scene's [[loads]], the crank held by its
drive), and the centrifugal -omega^2 Mt, gyroscopic G = 2 omega S and circulatory
alpha S terms of each link's turning frame (``fe.rotating``). The quadratic eigenproblem is
solved by ``analysis.quadratic``; each mode is paired by MAC with a static mode of the same
model (``analysis.modal.pose_modes``).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import scipy.sparse as sp

from flexlink.analysis.instability import Cause, RootKind, instability_causes, root_kinds
from flexlink.analysis.mesh import choose_mesh
from flexlink.analysis.modal import pose_system
from flexlink.analysis.quadratic import QuadraticModes, quadratic_modes
from flexlink.analysis.eigensolver import AUTO_DENSE_MAX
from flexlink.analysis.solve import MECHANISM, ModalResult
from flexlink.errors import InputError, NumericalError
from flexlink.fe.assembly import (assemble_reduced_dense, dense_slots, dense_sum,
                                  placed_link_entries, point_mass_entries, reduced_columns,
                                  rotated_entries, spring_entries)
from flexlink.fe.energy import twice_strain_energy
from flexlink.fe.geometric import GeometricForm, geometric_entries
from flexlink.fe.model import FrameModel
from flexlink.fe.preload import axial_forces, inertia_loads, static_displacement
from flexlink.fe.rotating import rotating_entries
from flexlink.kinematics.dynamics import RigidMotion, check_speed, rigid_motion
from flexlink.scene import Scene, load_scene
from flexlink.scene.contract import LoadKind, RigidPose, pose_transmission_angles
from flexlink.scene.plausibility import check_speeds, model_warnings, pose_warnings
from flexlink.studies.running.torque import operating_point, wrench

ASSUMPTIONS = (
    ("rigid-body motion prescribed by the crank (constant speed, or the given crank "
     "acceleration); elastic deflections are small and do not feed back into it"),
    ("frozen configuration: each link's turning rate and the preload are those of this "
     "instant, and the pins tie the links' turning frames at this instant"),
)


PAIRING_MAC = 0.8  # a mode at speed whose MAC with every static mode is lower: unpaired


@dataclasses.dataclass(frozen=True)
class Terms:
    """Which operating-point terms enter (all by default); ``geometric`` the K_g form."""

    preload: bool = True
    centrifugal: bool = True
    coriolis: bool = True
    acceleration: bool = True  # the circulatory alpha S term
    geometric: GeometricForm = GeometricForm.CONSISTENT


@dataclasses.dataclass(frozen=True)
class OperatingRequest:
    """The operating point asked for, None where the scene's own is taken: crank ``speed``
    [rad/s] (its [operation] crank_speed), ``crank_angle`` [rad] (its pose),
    ``crank_acceleration`` [rad/s^2] (its [operation] value with its speed, else 0), and which
    ``terms`` enter."""

    speed: float | None = None
    crank_angle: float | None = None
    crank_acceleration: float | None = None
    terms: Terms = Terms()


@dataclasses.dataclass(frozen=True)
class AxialForce:
    """The largest |N| of the preload: signed value [N], link, element index, position along
    the link [m] (element middle)."""

    value: float
    link: str
    element: int
    position: float


@dataclasses.dataclass(frozen=True)
class OperatingPoint:
    """Modes at speed beside the static modes of the same model (SI; frequencies [Hz])."""

    scene: Scene
    motion: RigidMotion
    terms: Terms
    model: FrameModel
    static: ModalResult
    modes: QuadraticModes
    static_index: np.ndarray  # per mode: the static elastic mode it pairs with (0-based)
    mac: np.ndarray  # per mode: MAC with that static mode
    link_omega: np.ndarray  # [rad/s] per link
    link_alpha: np.ndarray  # [rad/s^2] per link
    axial_forces: dict[str, np.ndarray]  # link -> per element N [N]
    largest_axial: AxialForce
    elements_per_link: int
    loads: np.ndarray  # the preload's nodal loads, d'Alembert and external (n_dofs,) [N, N m]
    warnings: tuple[str, ...] = ()  # model outside its range (``scene.plausibility``)
    causes: tuple[Cause, ...] = ()  # why the point is unstable (``analysis.instability``)

    def __post_init__(self):
        k = len(self.modes.eigenvalues)
        if self.static_index.shape != (k,) or self.mac.shape != (k,):
            raise ValueError(f"static_index and mac need one value per mode ({k})")

    @property
    def kinds(self) -> tuple[RootKind, ...]:
        """Per mode: a vibration, or a real root (diverging or decaying: no frequency)."""
        return root_kinds(self.modes.eigenvalues)

    @property
    def paired(self) -> np.ndarray:
        """Per mode: a vibration whose shape is its static partner's, MAC >= PAIRING_MAC;
        only a paired mode has a change from the static frequency."""
        vibrating = np.array([k is RootKind.VIBRATING for k in self.kinds])
        return vibrating & (self.mac >= PAIRING_MAC)

    @property
    def frequencies(self) -> np.ndarray:
        return self.modes.frequencies

    @property
    def static_frequencies(self) -> np.ndarray:
        """The paired static frequency of each mode [Hz]."""
        return self.static.elastic_frequencies[self.static_index]


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


def complex_mac(static_shapes: np.ndarray, shapes: np.ndarray, M) -> np.ndarray:
    """(k_static, k) MAC of real static shapes against complex ones, mass weighted:
    |phi^T M x|^2 / ((phi^T M phi)(x^H M x))."""
    MP, MX = M @ static_shapes, M @ shapes
    cross = np.abs(static_shapes.T @ MX) ** 2
    return cross / np.outer(np.einsum("ij,ij->j", static_shapes, MP),
                            np.einsum("ij,ij->j", shapes.conj(), MX).real)


def reducer(column: np.ndarray, n: int, dense: bool):
    """entries (rows, cols, values) of a full-size matrix -> its n x n T^T A T, dense or
    sparse; ``column`` from ``assembly.reduced_columns`` (T only renumbers and drops DOFs)."""
    if dense:
        return lambda rows, cols, vals: dense_sum(dense_slots(column, n, rows, cols), vals, n)

    def sparse(rows, cols, vals):
        r, c = column[rows], column[cols]
        keep = (r >= 0) & (c >= 0)
        return sp.csr_matrix((vals[keep], (r[keep], c[keep])), shape=(n, n))
    return sparse


def operating_modes(scene: Scene, speed: float, n_modes: int = 4,
                    elements_per_link: int | None = None, crank_angle: float | None = None,
                    crank_acceleration: float = 0.0, terms: Terms = Terms()) -> OperatingPoint:
    """The lowest ``n_modes`` modes of ``scene`` about its rigid motion at crank ``speed``
    [rad/s] and ``crank_acceleration`` [rad/s^2], at ``crank_angle`` [rad] (default: the
    scene's pose), on ``elements_per_link`` (default: the scene's mesh)."""
    check_speed(speed, crank_acceleration)
    state = scene.rigid_state(crank_angle)
    motion = rigid_motion(scene.linkage, state, speed, crank_acceleration)
    topology = scene.topology(elements_per_link)
    # as `modes` solves them; with its spare modes, a mode that swaps order finds its pair
    system = pose_system(topology, state.points, n_modes)
    model, static = system.model, system.modes
    if MECHANISM in static.kinds:
        raise NumericalError(
            f"{scene.path}: the frame has {static.kinds.count(MECHANISM)} rigid-body/mechanism "
            "mode(s) at this pose: modes at speed need the crank held by its drive and every "
            "link by its bearings (the preload has nothing to react against)")
    pose = RigidPose(crank_angle=state.q, joints=state.points, branch=scene.branch,
                     transmission=pose_transmission_angles(scene.linkage, scene.transmission,
                                                           state.points))
    warnings = tuple(pose_warnings(scene.four_bar, pose) + model_warnings(model))
    omega, alpha, acc = link_motion(scene, model, topology, motion)
    T = system.T
    column, n = reduced_columns(T, model.n_dofs)
    reduce = reducer(column, n, dense=n <= AUTO_DENSE_MAX)
    Kr, Mr = reused_pair(system)
    loads = inertia_loads(model, acc, alpha) + external_loads(scene, model, topology, state)
    forces = axial_forces(model, static_displacement(Kr, T, loads))
    rows, cols, rot = rotating_entries(model, omega, alpha)
    on = np.array([terms.centrifugal, terms.coriolis, terms.acceleration], dtype=float)
    extra = [(rows, cols, rot[0] * on[0] + rot[2] * on[2])]
    if terms.preload:
        extra.append(geometric_entries(model, forces, terms.geometric))
    K_extra = reduce(*(np.concatenate(part) for part in zip(*extra)))
    static_shapes = np.zeros((n, len(static.elastic)))
    static_shapes[column[column >= 0]] = static.shapes[np.ix_(column >= 0, static.elastic)]
    guess = (static_shapes[:, :n_modes], 2 * np.pi * static.elastic_frequencies[:n_modes])

    def stiffness(X):  # x^H K_eff x with K's part from the element deformations, as `modes`
        full = X if T is None else T @ X
        parts = twice_strain_energy(model, np.hstack([full.real, full.imag]))
        return (parts[:X.shape[1]] + parts[X.shape[1]:]
                + np.einsum("ij,ij->j", X.conj(), K_extra @ X))
    modes = quadratic_modes(Mr, reduce(rows, cols, rot[1] * on[1]), Kr + K_extra, n_modes,
                            guess, stiffness)
    mac = complex_mac(static_shapes, modes.shapes, Mr)
    pair = mac.argmax(axis=0)
    parts = {Cause.PRELOAD: reduce(*geometric_entries(model, forces, terms.geometric))
             if terms.preload else None,
             Cause.CENTRIFUGAL: reduce(rows, cols, rot[0]) if terms.centrifugal else None}
    causes = instability_causes(Kr, parts, reduce(rows, cols, rot[2]) if terms.acceleration
                                else None, modes.negative_stiffness, modes.growing,
                                root_kinds(modes.eigenvalues))
    return OperatingPoint(
        scene=scene, motion=motion, terms=terms, model=model, static=static, modes=modes,
        static_index=pair, mac=mac[pair, np.arange(len(pair))], link_omega=omega,
        link_alpha=alpha, axial_forces={l.name: f for l, f in zip(model.links, forces)},
        largest_axial=_largest(model, forces), elements_per_link=topology.links[0].elements,
        loads=loads, warnings=warnings, causes=causes)


def scene_operating_modes(path, n_modes: int = 4, elements: int | None = None,
                          tol: float | None = None,
                          at: OperatingRequest = OperatingRequest()) -> OperatingPoint:
    """``operating_modes`` of the scene file at ``path`` at the operating point ``at``, on the
    mesh of its static modes (``elements`` per link, else the scene's pinned mesh, else the
    mesh rule at relative tolerance ``tol``)."""
    scene = load_scene(path)
    if at.speed is not None:
        check_speeds(scene, [at.speed], "--speed")
    speed, acceleration = operating_point(scene, at.speed, at.crank_acceleration)
    mesh = choose_mesh(scene, n_modes, elements, tol)
    return operating_modes(scene, speed, n_modes, mesh.elements, at.crank_angle, acceleration,
                           at.terms)


def link_motion(scene: Scene, model: FrameModel, topology, motion: RigidMotion):
    """(omega, alpha) per link [rad/s, rad/s^2] and the rigid acceleration of every node
    (N, 2) [m/s^2]."""
    bodies = link_bodies(scene, topology.links)
    index = {b: i for i, b in enumerate(motion.bodies)}
    omega = np.array([motion.omega[index[b]] for b in bodies])
    alpha = np.array([motion.alpha[index[b]] for b in bodies])
    acc = np.empty((len(model.nodes), 2))
    for link, body in zip(model.links, bodies):
        acc[link.nodes] = motion.point_acceleration(body, model.nodes[link.nodes])
    return omega, alpha, acc


def external_loads(scene: Scene, model: FrameModel, topology, state) -> np.ndarray:
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


def reused_pair(system) -> tuple:
    """The (K, M) with the rigid constraints eliminated, from the static solve's own
    (``modal.PoseSystem``): as they are when it eliminated them (dense), else T^T K T and
    T^T M T of its full sparse ones."""
    if system.eliminated:
        return system.K, system.M
    if system.T is None:
        return sp.csr_matrix(system.K), sp.csr_matrix(system.M)
    T = sp.csr_matrix(system.T)
    return (T.T @ system.K @ T).tocsr(), (T.T @ system.M @ T).tocsr()


def reduced_pair(model: FrameModel, T, n: int, reduce):
    """Reduced (K, M) of size ``n``, dense through ``assembly.assemble_reduced_dense`` for
    small models."""
    if n <= AUTO_DENSE_MAX:
        return assemble_reduced_dense(model, T)
    rows, cols, values = rotated_entries(*placed_link_entries(model))
    springs, masses = spring_entries(model), point_mass_entries(model)
    return (reduce(*(np.concatenate(p) for p in zip((rows, cols, values[0]), springs))),
            reduce(*(np.concatenate(p) for p in zip((rows, cols, values[1]), masses))))


def _largest(model: FrameModel, forces) -> AxialForce:
    best = max(((abs(float(f[e])), i, e) for i, f in enumerate(forces) for e in range(len(f))),
               default=(0.0, 0, 0))
    _, i, e = best
    link = model.links[i]
    h = link.length / link.elements
    return AxialForce(value=float(forces[i][e]), link=link.name, element=e,
                      position=(e + 0.5) * h)


def crank_speed(scene: Scene, speed: float | None) -> float:
    """The speed to use [rad/s]: ``speed`` if given, else the scene's [operation] crank_speed;
    InputError when neither is."""
    if speed is not None:
        return speed
    if scene.options.crank_speed is None:
        raise InputError("no crank speed: give --speed or [operation] crank_speed",
                         source=scene.path, field="operation.crank_speed",
                         expected="an angular speed, e.g. '2000 rev/min'")
    return scene.options.crank_speed

