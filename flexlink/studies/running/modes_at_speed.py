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

from flexlink.analysis.eigensolver import AUTO_DENSE_MAX
from flexlink.analysis.frame_motion import link_motion, pose_speed_terms
from flexlink.analysis.mac import complex_mac
from flexlink.analysis.instability import Cause, RootKind, instability_causes, root_kinds
from flexlink.analysis.mesh import choose_mesh
from flexlink.analysis.modal import pose_system
from flexlink.analysis.quadratic import QuadraticModes, quadratic_modes
from flexlink.analysis.solve import MECHANISM, ModalResult
from flexlink.errors import NumericalError
from flexlink.fe.assembly import eliminating_assembler, reduced_columns
from flexlink.fe.energy import twice_strain_energy
from flexlink.fe.model import FrameModel
from flexlink.fe.speed_terms import ALL_TERMS, Terms, speed_quadratic
from flexlink.kinematics.dynamics import RigidMotion, check_speed, rigid_motion
from flexlink.scene import Scene, load_scene
from flexlink.scene.contract import RigidPose, pose_transmission_angles
from flexlink.scene.plausibility import model_warnings, pose_warnings
from flexlink.studies.array_shapes import check_shape

__all__ = ["ASSUMPTIONS", "AxialForce", "OperatingPoint", "OperatingRequest", "Terms",
           "operating_modes", "scene_operating_modes"]

ASSUMPTIONS = (
    ("rigid-body motion prescribed by the crank (constant speed, or the given crank "
     "acceleration); elastic deflections are small and do not feed back into it"),
    ("frozen configuration: each link's turning rate and the preload are those of this "
     "instant, and the pins tie the links' turning frames at this instant"),
)


PAIRING_MAC = 0.8  # a mode at speed whose MAC with every static mode is lower: unpaired


@dataclasses.dataclass(frozen=True)
class OperatingRequest:
    """The operating point asked for: crank ``speed`` [rad/s] (resolved against the scene's
    [operation] by the command line, ``commands._speeds.operating_speed``), ``crank_angle``
    [rad] (None: the scene's pose), ``crank_acceleration`` [rad/s^2] (None: 0), and which
    ``terms`` enter."""

    speed: float | None = None
    crank_angle: float | None = None
    crank_acceleration: float | None = None
    terms: Terms = ALL_TERMS


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
        k, links = len(self.modes.eigenvalues), len(self.model.links)
        for name, shape in (("static_index", (k,)), ("mac", (k,)), ("link_omega", (links,)),
                            ("link_alpha", (links,)), ("loads", (self.model.n_dofs,))):
            check_shape("OperatingPoint", name, getattr(self, name), shape)

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


def operating_modes(scene: Scene, speed: float, n_modes: int = 4,
                    elements_per_link: int | None = None, crank_angle: float | None = None,
                    crank_acceleration: float = 0.0, terms: Terms = ALL_TERMS) -> OperatingPoint:
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
    omega, alpha, _ = link_motion(scene, model, topology, motion)
    T = system.T
    column, n = reduced_columns(T, model.n_dofs)
    Kr, Mr = system.eliminated_pair()
    unit = pose_speed_terms(scene, topology, state, model, Kr, T,
                            eliminating_assembler(column, n, dense=n <= AUTO_DENSE_MAX),
                            terms.geometric, accelerating=crank_acceleration != 0.0)
    G, K_extra = unit.at(speed, crank_acceleration, terms)
    loads = unit.loads_at(speed, crank_acceleration)
    forces = unit.forces_at(speed, crank_acceleration)
    static_shapes = np.zeros((n, len(static.elastic)))
    static_shapes[column[column >= 0]] = static.shapes[np.ix_(column >= 0, static.elastic)]
    guess = (static_shapes[:, :n_modes], 2 * np.pi * static.elastic_frequencies[:n_modes])

    def stiffness(X):  # x^H K_eff x with K's part from the element deformations, as `modes`
        full = X if T is None else T @ X
        parts = twice_strain_energy(model, np.hstack([full.real, full.imag]))
        return (parts[:X.shape[1]] + parts[X.shape[1]:]
                + np.einsum("ij,ij->j", X.conj(), K_extra @ X))
    modes = quadratic_modes(Mr, G, Kr + K_extra, n_modes, guess, stiffness)
    mac = complex_mac(static_shapes, modes.shapes, Mr)
    pair = mac.argmax(axis=0)
    accelerating = crank_acceleration != 0.0
    parts = {Cause.PRELOAD: speed_quadratic(
                 speed, unit.external_preload, unit.preload, crank_acceleration,
                 unit.start_preload if accelerating else None) if terms.preload else None,
             Cause.CENTRIFUGAL: speed_quadratic(speed, 0.0, unit.centrifugal)
             if terms.centrifugal else None}
    circulatory = speed_quadratic(speed, 0.0, unit.circulatory, crank_acceleration,
                                  unit.start_circulatory if accelerating else None)
    causes = instability_causes(Kr, parts, circulatory if terms.acceleration else None,
                                modes.negative_stiffness, modes.growing,
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
    """``operating_modes`` of the scene file at ``path`` at the operating point ``at`` (its
    speed given: the command line resolves it against the scene's), on the mesh of its static
    modes (``elements`` per link, else the scene's pinned mesh, else the mesh rule at relative
    tolerance ``tol``)."""
    if at.speed is None:
        raise ValueError("scene_operating_modes needs the crank speed resolved")
    scene = load_scene(path) if not isinstance(path, Scene) else path
    mesh = choose_mesh(scene, n_modes, elements, tol)
    return operating_modes(scene, at.speed, n_modes, mesh.elements, at.crank_angle,
                           at.crank_acceleration or 0.0, at.terms)


def _largest(model: FrameModel, forces) -> AxialForce:
    best = max(((abs(float(f[e])), i, e) for i, f in enumerate(forces) for e in range(len(f))),
               default=(0.0, 0, 0))
    _, i, e = best
    link = model.links[i]
    h = link.length / link.elements
    return AxialForce(value=float(forces[i][e]), link=link.name, element=e,
                      position=(e + 0.5) * h)
