"""The one scene contract: what every command gets from a scene file, whatever its kind.

A four-bar scene and a general scene both load into ``Scene``: the linkage as data (a
``kinematics.Linkage``, plus the closed-form ``FourBar`` where there is one), the analysed pose,
the beam links, joints and drive, the mesh if pinned, the reference table, the assumptions, and
each stage's declared options. All values SI.
"""

from __future__ import annotations

import dataclasses
import enum
import math

import numpy as np

from flexlink.errors import InputError, KinematicsError
from flexlink.fe.model import DriveSpec, JointSpec, LinkSpec, Section, Topology
from flexlink.fe.motions import ModelFamily
from flexlink.kinematics import Branch, FourBar, Linkage, State
from flexlink.kinematics.kinetostatics import Losses, Transmission
from flexlink.materials.mixtures import ShearSource
from flexlink.scene.source import Assumption, file_of

CONTINUATION_STEP = math.radians(5.0)  # [rad] between poses continued along a general scene's input


@dataclasses.dataclass(frozen=True)
class Reference:
    """Published or measured frequencies [Hz] to compare with, by mode order."""

    source: str
    columns: dict[str, tuple[float, ...]]  # e.g. {"Ex": (...), "FE": (...)}


@dataclasses.dataclass(frozen=True)
class Variant:
    """Copies of the scene with dotted key ``field`` set to each of ``values`` (as in a file)."""

    name: str
    field: str
    values: tuple


@dataclasses.dataclass(frozen=True)
class Composite:
    """The shared [material] composite as written: constituent names (or paths) and Vf [-]."""

    fiber: str
    matrix: str
    fiber_volume_fraction: float
    shear_modulus: ShearSource = ShearSource.PRINTED  # constituent G: Table I's or from E, nu


@dataclasses.dataclass(frozen=True)
class LinkMaterial:
    """Where a link's material comes from, for the data a section does not hold (strengths):
    ``field`` the scene key ("material" or "links.<link>.material") in ``source`` (its file);
    ``isotropic`` the named material file, or ``composite`` the constituents, or neither (E and
    density written in the scene: no material file, so no strength data); ``plies`` the
    section's ply count, where given."""

    field: str
    source: str
    isotropic: str | None = None
    composite: Composite | None = None
    plies: int | None = None


@dataclasses.dataclass(frozen=True)
class PrbOptions:
    strip: str
    pivot: str
    link: str
    clamp: str
    gamma: float
    K_theta: float


@dataclasses.dataclass(frozen=True)
class ModalTestFrame:
    """The scene's [test] table: a test point (x, y) in ``unit`` (None: the file's own) lands
    at ``offset`` [m] + R(``rotation`` [rad]) (x, y) in the scene's frame; a sensor farther
    than ``max_distance`` [m] from every link's axis is refused."""

    unit: str | None = None
    offset: tuple[float, float] = (0.0, 0.0)
    rotation: float = 0.0
    max_distance: float = 0.01

    def to_scene(self, points, metres_per_unit: float):
        """(P, 2) scene coordinates [m] of test points (P, >= 2) in the file's unit."""
        c, s = math.cos(self.rotation), math.sin(self.rotation)
        p = np.asarray(points, dtype=float)[:, :2] * metres_per_unit
        return np.column_stack([c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1]]) + self.offset

    def to_test(self, points, metres_per_unit: float):
        """(P, 2) test-frame coordinates in the file's unit of scene points (P, 2) [m]: the
        inverse of ``to_scene``."""
        c, s = math.cos(self.rotation), math.sin(self.rotation)
        p = np.asarray(points, dtype=float) - self.offset
        return np.column_stack([c * p[:, 0] + s * p[:, 1], -s * p[:, 0] + c * p[:, 1]]) / metres_per_unit

    def direction_to_test(self, directions):
        """Unit directions (C, 3) of the scene's frame turned into the test frame."""
        c, s = math.cos(self.rotation), math.sin(self.rotation)
        d = np.asarray(directions, dtype=float).reshape(-1, 3)
        return np.column_stack([c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1], d[:, 2]])

    def direction_to_scene(self, directions):
        """Unit directions (C, 3) of the test frame turned into the scene's frame."""
        c, s = math.cos(self.rotation), math.sin(self.rotation)
        d = np.asarray(directions, dtype=float).reshape(-1, 3)
        return np.column_stack([c * d[:, 0] - s * d[:, 1], s * d[:, 0] + c * d[:, 1], d[:, 2]])


class Plausibility(enum.StrEnum):
    """What a model outside its range of validity does: refuse (ERROR) or warn."""

    ERROR = "error"
    WARN = "warn"


@dataclasses.dataclass(frozen=True)
class Options:
    """The stages' declared options (``schema.py`` documents each)."""

    family: ModelFamily = ModelFamily.PLANAR
    crank_speed: float | None = None  # [rad/s]
    crank_acceleration: float | None = None  # [rad/s^2], only with crank_speed
    plausibility: Plausibility = Plausibility.ERROR
    prb: PrbOptions | None = None
    variants: tuple[Variant, ...] = ()
    tilt: dict[str, float] = dataclasses.field(default_factory=dict)  # joint -> Ktilt [N m/rad]
    damping: ModalDamping | None = None  # declared modal damping; None: the loss factors
    test: ModalTestFrame = ModalTestFrame()  # where a modal test's geometry sits (``[test]``)


@dataclasses.dataclass(frozen=True)
class ModalDamping:
    """Damping declared by the scene's [damping] table, one of: ``ratios`` (one per elastic
    mode, lowest first, the last repeated past the end; a single ratio is a one-entry tuple)
    or Rayleigh ``alpha`` [1/s] and ``beta`` [s] of C = alpha M + beta K."""

    ratios: tuple[float, ...] = ()
    alpha: float = 0.0
    beta: float = 0.0

    @property
    def is_rayleigh(self) -> bool:
        return not self.ratios


class LoadKind(enum.StrEnum):
    TORQUE = "torque"
    FORCE = "force"


class LoadFrame(enum.StrEnum):
    """Axes a force's components are given along: the global ones or the body's own."""

    GLOBAL = "global"
    BODY = "body"


@dataclasses.dataclass(frozen=True)
class LoadSpec:
    """An external load on body ``body`` (see schema ``LoadTable``): ``kind`` "torque" [N m,
    counter-clockwise positive] or "force" [N] acting at ``at`` [m] in the body's frame with
    components along ``frame`` ("global" or "body"). ``angles`` [rad] (increasing, one turn,
    evenly spaced) and ``values`` (one row per angle: (T,) or (Fx, Fy)) sample it over the
    crank angle; a constant load has a single row and no angles. ``field`` names where it was
    declared, e.g. "loads[0]"."""

    kind: LoadKind
    body: str
    values: np.ndarray
    angles: np.ndarray | None = None
    at: tuple[float, float] = (0.0, 0.0)
    frame: LoadFrame = LoadFrame.GLOBAL
    field: str = "loads"

    def value_at(self, q: float) -> np.ndarray:
        """The load's components at crank angle ``q`` [rad], linear between samples and
        periodic over the turn."""
        if self.angles is None:
            return self.values[0]
        period = 2 * math.pi
        x = self.angles[0] + np.remainder(q - self.angles[0], period)
        xs = np.append(self.angles, self.angles[0] + period)
        ys = np.vstack([self.values, self.values[:1]])
        return np.array([np.interp(x, xs, ys[:, k]) for k in range(ys.shape[1])])


@dataclasses.dataclass(frozen=True)
class KinetostaticsSpec:
    """The scene's [kinetostatics]: the input torque on the driver (a torque ``LoadSpec`` on
    it, constant or over the crank angle), the outputs and how they share it, and the losses."""

    input_torque: LoadSpec
    transmission: Transmission
    losses: Losses


@dataclasses.dataclass(frozen=True)
class RigidPose:
    """A rigid pose: input (crank) angle [rad], joint positions [m], and the transmission angles
    [rad] of the scene's body pairs (``mu`` is the first, None if the scene names none)."""

    crank_angle: float
    joints: dict[str, tuple[float, float]]
    transmission: dict[str, float]
    branch: Branch

    @property
    def mu(self) -> float | None:
        return next(iter(self.transmission.values()), None)


class SceneKind(enum.StrEnum):
    """``[linkage] type``: a four-bar given by its lengths, or any linkage as data."""

    FOUR_BAR = "four-bar"
    GENERAL = "general"


@dataclasses.dataclass(frozen=True)
class Scene:
    """A validated scene of either kind."""

    name: str
    path: str
    kind: SceneKind
    linkage: Linkage
    four_bar: FourBar | None
    start: float  # input angle of the analysed pose [rad]
    branch: Branch
    guess: dict[str, tuple[float, float]]  # moving joints near the start pose [m]
    transmission: tuple[tuple[str, str], ...]
    links: tuple[LinkSpec, ...]
    joints: tuple[JointSpec, ...]
    drive: DriveSpec | None
    elements_per_link: int | None  # pinned by the scene; None: the commands' mesh rule
    reference: Reference | None
    assumptions: tuple[Assumption, ...]
    options: Options
    synthesis: dict | None = None  # method, inputs and the synthesised lengths [m]
    composite: Composite | None = None  # the shared material, where it is a composite
    loads: tuple[LoadSpec, ...] = ()  # external loads for the driving torque
    kinetostatics: KinetostaticsSpec | None = None  # a declared input torque and its outputs
    loss_factors: dict[str, float] = dataclasses.field(default_factory=dict)  # link -> eta [-]
    materials: dict[str, LinkMaterial] = dataclasses.field(default_factory=dict)  # per link
    origin: dict[str, str] = dataclasses.field(default_factory=dict, repr=False, compare=False)

    @property
    def sections(self) -> dict[str, Section]:
        return {link.name: link.section for link in self.links}

    def file_of(self, field: str) -> str:
        """The file a dotted key came from (a base file, the scene, or "overrides")."""
        return file_of(self.origin, field, self.path)

    def has_field(self, field: str) -> bool:
        return field in self.origin or any(f.startswith(field + ".") for f in self.origin)

    def topology(self, elements_per_link: int | None = None) -> Topology:
        """Links, joints and drive with ``elements_per_link`` (else the scene's pinned mesh, else
        each link's own count, else meshes.DEFAULT_ELEMENTS)."""
        if not self.links:
            raise InputError("the scene has no [links] beams: kinematics only", source=self.path,
                             field="links")
        n = elements_per_link or self.elements_per_link
        links = tuple(dataclasses.replace(s, elements=n) if n else s for s in self.links)
        return Topology(links=links, joints=self.joints, drive=self.drive)

    def require_full_turn(self) -> None:
        """KinematicsError where the scene is a four-bar whose crank cannot make a whole turn
        (a non-Grashof linkage, or a Grashof one driven by a link that only rocks): the studies
        over the crank turn need one."""
        if self.four_bar is not None and not self.four_bar.crank_turns_fully():
            raise KinematicsError(f"the crank cannot turn fully: the linkage is "
                                  f"{self.four_bar.grashof_class()} (lengths "
                                  f"{', '.join(f'{1e3 * v:g}' for v in self.four_bar.lengths)} "
                                  "mm: ground, crank, coupler, rocker); a whole turn needs a "
                                  "crank that is the shortest link, or the ground, of a Grashof "
                                  "linkage")

    def cycle_origin(self) -> tuple[float, dict[str, tuple[float, float]]]:
        """Where a whole-cycle sweep starts: (input angle [rad], moving joints near that pose).
        A four-bar scene's cycle runs over crank angles 0 to 360 deg whatever pose it analyses;
        a general scene's starts at its own start pose, whose guess picks the assembly."""
        if self.kind is SceneKind.FOUR_BAR:
            joints = self.four_bar.pose(0.0, self.branch).joints
            return 0.0, {k: v for k, v in joints.items() if k in self.guess}
        return self.start, dict(self.guess)

    def rigid_pose(self, crank_angle: float | None = None) -> RigidPose:
        """The rigid pose at ``crank_angle`` [rad] (default: the scene's analysed pose)."""
        q = self.start if crank_angle is None else crank_angle
        if self.four_bar is not None and set(self.guess) <= {"A", "B"}:
            pose = self.four_bar.pose(q, self.branch)  # closed form, with its dead-centre checks
            points = dict(pose.joints)
        else:
            points = dict(self.linkage.solve(q, self.guess).points)
        return RigidPose(crank_angle=q, joints=points, branch=self.branch,
                         transmission=pose_transmission_angles(self.linkage, self.transmission, points))


    def rigid_state(self, crank_angle: float | None = None) -> State:
        """The rigid pose at ``crank_angle`` [rad] (default: the analysed pose) with its
        velocity and acceleration coefficients, on the scene's assembly: a four-bar's from its
        closed form, a general scene's continued from its start pose in steps of at most
        ``CONTINUATION_STEP``."""
        q = self.start if crank_angle is None else float(crank_angle)
        if self.four_bar is not None and set(self.guess) <= {"A", "B"}:
            joints = self.four_bar.pose(q, self.branch).joints
            return self.linkage.solve(q, {k: joints[k] for k in self.guess})
        steps = math.ceil(abs(q - self.start) / CONTINUATION_STEP)
        if steps == 0:  # the start pose itself
            return self.linkage.solve(q, self.guess)
        return self.linkage.cycle(np.linspace(self.start, q, steps + 1), self.guess).states[-1]


def pose_transmission_angles(linkage: Linkage, pairs, points) -> dict[str, float]:
    """mu [rad] for each body pair: the angle between the two bodies' lines at the joint they
    share (0 or 180 deg at a dead centre)."""
    out = {}
    for a, b in pairs:
        body_a, body_b = linkage.body(a), linkage.body(b)
        shared = next(j for j in body_a.joints if j in body_b.joints)
        far_a = next(j for j in body_a.joints if j != shared)
        far_b = next(j for j in body_b.joints if j != shared)
        u = np.subtract(points[far_a], points[shared])
        v = np.subtract(points[far_b], points[shared])
        out[f"{a}/{b}"] = math.atan2(abs(u[0] * v[1] - u[1] * v[0]), float(u @ v))
    return out
