"""The one scene contract: what every command gets from a scene file, whatever its kind.

A four-bar scene and a general scene both load into ``Scene``: the linkage as data (a
``kinematics.Linkage``, plus the closed-form ``FourBar`` where there is one), the analysed pose,
the beam links, joints and drive, the mesh if pinned, the reference table, the assumptions, and
each stage's declared options. All values SI.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexlink.errors import InputError
from flexlink.fe.model import DriveSpec, JointSpec, LinkSpec, Section, Topology
from flexlink.kinematics import FourBar, Linkage
from flexlink.scene.source import Assumption


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
    shear_modulus: str = "printed"  # constituent G: "printed" (Table I) or "isotropic"


@dataclasses.dataclass(frozen=True)
class PrbOptions:
    strip: str
    pivot: str
    link: str
    clamp: str
    gamma: float
    K_theta: float


@dataclasses.dataclass(frozen=True)
class Options:
    """The stages' declared options (``schema.py`` documents each)."""

    family: str = "planar"  # model family
    crank_speed: float | None = None  # [rad/s]
    plausibility: str = "error"
    prb: PrbOptions | None = None
    variants: tuple[Variant, ...] = ()
    tilt: dict[str, float] = dataclasses.field(default_factory=dict)  # joint -> Ktilt [N m/rad]


@dataclasses.dataclass(frozen=True)
class RigidPose:
    """A rigid pose: input (crank) angle [rad], joint positions [m], and the transmission angles
    [rad] of the scene's body pairs (``mu`` is the first, None if the scene names none)."""

    crank_angle: float
    joints: dict[str, tuple[float, float]]
    transmission: dict[str, float]
    branch: str

    @property
    def theta2(self) -> float:
        return self.crank_angle

    @property
    def mu(self) -> float | None:
        return next(iter(self.transmission.values()), None)


@dataclasses.dataclass(frozen=True)
class Scene:
    """A validated scene of either kind; ``kind`` is "four-bar" or "general"."""

    name: str
    path: str
    kind: str
    linkage: Linkage
    four_bar: FourBar | None
    start: float  # input angle of the analysed pose [rad]
    branch: str
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
    origin: dict[str, str] = dataclasses.field(default_factory=dict, repr=False, compare=False)

    @property
    def sections(self) -> dict[str, Section]:
        return {link.name: link.section for link in self.links}

    def file_of(self, field: str) -> str:
        """The file a dotted key came from (a base file, the scene, or "overrides")."""
        if field in self.origin:
            return self.origin[field]
        below = [f for f in self.origin if f.startswith(field + ".")]
        return self.origin[below[0]] if below else self.path

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

    def cycle_origin(self) -> tuple[float, dict[str, tuple[float, float]]]:
        """Where a whole-cycle sweep starts: (input angle [rad], moving joints near that pose).
        A four-bar scene's cycle runs over crank angles 0 to 360 deg whatever pose it analyses;
        a general scene's starts at its own start pose, whose guess picks the assembly."""
        if self.kind == "four-bar":
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
