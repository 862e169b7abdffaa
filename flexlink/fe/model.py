"""The finite-element model of a linkage at one pose: nodes, beam links, springs, masses.

Plain data only; no matrices here beyond each link's local ones (see ``link.py``).

Global DOFs: node i owns 3i (ux [m]), 3i+1 (uy [m]), 3i+2 (rz [rad]). Every link has its own
chain of nodes, so two links meeting at a joint have two coincident nodes; the joint joins
them through explicit spring elements (``joints.py``, shared with the out-of-plane model): a
translational spring Kt [N/m] in x and in y and a torsional spring Kr [N m/rad] per pin or
bearing, a rigid weld between the links of a ``welded`` ground joint (one bearing on its
first link's node), and the drive: a torsional spring between the driven link's node and the
ground, in parallel with its bearing's Kr.
A stiffness of ``inf`` ("rigid" in a scene file) is an exact constraint, not a penalty: the
two DOFs are merged (or the DOF is fixed, for ground) by ``assembly.rigid_elimination``.
"""

from __future__ import annotations

import dataclasses
import functools
import enum
import math

import numpy as np

from flexlink.choices import parse_choice, spelled
from flexlink.errors import InputError
from flexlink.fe.beams import THEORIES, BeamTheory, beam_matrices
from flexlink.fe.joints import GROUND as GROUND  # the models' name for the ground DOF
from flexlink.fe.joints import JointDofs, Springs, springs_of_joints



class Bending(enum.StrEnum):
    """How a flat bar lies (``Section.rectangle``)."""

    EDGEWISE = "edgewise"
    FLATWISE = "flatwise"


BENDINGS = tuple(Bending)
DOF_NAMES = ("ux", "uy", "rz")
# in-plane joints: Kt on ux and uy, Kr on rz; the drive holds rz
IN_PLANE_JOINTS = JointDofs(bearing_labels=("Kt x", "Kt y", "Kr"), weld_labels=("x", "y", "r"),
                            drive_dof=2)


@dataclasses.dataclass(frozen=True)
class Section:
    """Cross-section and material of a link, SI units.

    E [Pa], G [Pa], density [kg/m^3], area [m^2], second_moment [m^4] for in-plane bending,
    depth [m] = in-plane depth of the section (for slenderness checks).
    beam: the beam theory of the link's elements, a name in ``beams.THEORIES``;
    shear_factor [-]: Timoshenko shear correction k (5/6 for a rectangle), unused otherwise.
    """

    E: float
    G: float
    density: float
    area: float
    second_moment: float
    depth: float
    name: str = ""
    beam: BeamTheory = BeamTheory.EULER_BERNOULLI
    shear_factor: float = 5.0 / 6.0
    bending: Bending = Bending.EDGEWISE  # a flat bar's orientation (``rectangle``); edgewise otherwise

    def __post_init__(self):
        for field in ("E", "G", "density", "area", "second_moment", "depth", "shear_factor"):
            value = getattr(self, field)
            if not (math.isfinite(value) and value > 0):
                raise InputError(f"must be positive and finite, got {value!r}",
                                 source=self.name or None, field=field)
        if self.beam not in THEORIES:
            raise InputError(f"unknown beam theory {self.beam!r}", source=self.name or None,
                             field="model.beam", expected=spelled(BeamTheory))
        # the Python edge: text choices become members
        object.__setattr__(self, "beam", BeamTheory(self.beam))
        object.__setattr__(self, "bending", parse_choice(Bending, self.bending, "section.bending"))

    @classmethod
    def rectangle(cls, E, G, density, width, thickness, name="", bending="edgewise",
                  beam="euler-bernoulli"):
        """Flat bar of ``width`` [m] and ``thickness`` [m]. ``bending`` says how it lies:
        "edgewise": the width is in the mechanism plane, so in-plane bending uses the width as
        depth, I = thickness width^3 / 12 (the stiff way); "flatwise": the thickness is in the
        plane and the width out of it (the broad faces stand normal to the mechanism plane), so
        in-plane bending uses I = width thickness^3 / 12 (the flexible way)."""
        if bending not in BENDINGS:
            raise InputError(f"unknown bending {bending!r}", source=name or None,
                             field="section.bending", expected=spelled(Bending))
        depth, across = (width, thickness) if bending == Bending.EDGEWISE else (thickness, width)
        return cls(E=E, G=G, density=density, area=width * thickness,
                   second_moment=across * depth**3 / 12.0, depth=depth, name=name, beam=beam,
                   bending=bending)

    @classmethod
    def tube(cls, E, G, density, outer_radius, inner_radius, name=""):
        """Round tube [m]: A = pi (ro^2 - ri^2), I = pi (ro^4 - ri^4) / 4, depth 2 ro."""
        if not 0 <= inner_radius < outer_radius:
            raise InputError(f"need 0 <= inner radius < outer radius, got {inner_radius!r}, "
                             f"{outer_radius!r}", source=name or None, field="tube")
        ro2, ri2 = outer_radius**2, inner_radius**2
        return cls(E=E, G=G, density=density, area=math.pi * (ro2 - ri2),
                   second_moment=math.pi * (ro2**2 - ri2**2) / 4.0, depth=2 * outer_radius,
                   name=name)

    @property
    def EA(self) -> float:
        return self.E * self.area

    @property
    def EI(self) -> float:
        return self.E * self.second_moment

    @property
    def mass_per_length(self) -> float:
        return self.density * self.area

    @property
    def strip(self) -> tuple[float, float]:
        """(width, thickness) [m] of a flat bar, whichever way it lies."""
        across = self.area / self.depth
        return (self.depth, across) if self.bending is Bending.EDGEWISE else (across, self.depth)

    @property
    def kGA(self) -> float:
        """Shear stiffness k G A [N] (Timoshenko)."""
        return self.shear_factor * self.G * self.area

    @property
    def rotary_inertia(self) -> float:
        """Rotary inertia per unit length rho I [kg m] (Timoshenko)."""
        return self.density * self.second_moment


@dataclasses.dataclass(frozen=True)
class LinkSpec:
    """A link of the linkage: a straight beam from joint ``start`` to joint ``end``."""

    name: str
    start: str
    end: str
    section: Section
    elements: int


@dataclasses.dataclass(frozen=True)
class JointSpec:
    """A joint: ``ground`` joints are bearings to the frame. Kt [N/m], Kr [N m/rad]; inf = rigid."""

    name: str
    ground: bool
    Kt: float
    Kr: float
    mass: float = 0.0  # lumped joint mass [kg] (pin, bearing), on the first attached link end's node
    welded: bool = False  # ground joint only: its links are welded together (see module docstring)

    def __post_init__(self):
        # as the scene's reader: stiffnesses >= 0 or inf (rigid), a mass >= 0 and finite;
        # `not value >= 0` refuses NaN too
        for field, unit in (("Kt", "N/m"), ("Kr", "N*m/rad"), ("mass", "kg")):
            value = getattr(self, field)
            if not value >= 0 or (field == "mass" and math.isinf(value)):
                raise InputError(f"must be >= 0{' and finite' if field == 'mass' else ''}, "
                                 f"got {value!r}", source=f"joint {self.name}", field=field,
                                 expected=f"{unit}, >= 0" + (", finite" if field == "mass"
                                                            else " or inf (rigid)"))
        if self.welded and not self.ground:
            raise InputError("only a ground joint can be welded (a moving weld is Kt = Kr = rigid)",
                             source=f"joint {self.name}", field="welded")


@dataclasses.dataclass(frozen=True)
class DriveSpec:
    """The drive holds ``link``'s rotation at ground joint ``joint`` with ``stiffness`` [N m/rad]."""

    link: str
    joint: str
    stiffness: float

    def __post_init__(self):
        if not self.stiffness >= 0:  # NaN too
            raise InputError(f"must be >= 0, got {self.stiffness!r}", source="drive",
                             field="stiffness", expected="N*m/rad, >= 0")


@dataclasses.dataclass(frozen=True)
class Topology:
    """Which links meet at which joints, with their properties; independent of the pose."""

    links: tuple[LinkSpec, ...]
    joints: tuple[JointSpec, ...]
    drive: DriveSpec | None = None


@dataclasses.dataclass(frozen=True)
class LinkMesh:
    """A meshed link at a pose: nodes first_node ... first_node + elements, start to end."""

    name: str
    first_node: int
    elements: int
    length: float
    angle: float  # [rad], direction start -> end from the global x axis
    section: Section

    @property
    def nodes(self) -> np.ndarray:
        return np.arange(self.first_node, self.first_node + self.elements + 1)

    def local_matrices(self):
        """(K, M) in the link frame; cached in ``link.py``, so cheap across poses."""
        return beam_matrices(self.length, self.elements, self.section)


@dataclasses.dataclass(frozen=True)
class FrameModel:
    """Everything assembly needs at one pose."""

    nodes: np.ndarray  # (N, 2) [m]
    links: tuple[LinkMesh, ...]
    springs: Springs
    point_masses: tuple[tuple[int, float], ...]  # (node, mass [kg]) translational
    joint_nodes: dict[str, tuple[int, ...]]

    @property
    def n_dofs(self) -> int:
        return 3 * len(self.nodes)


@dataclasses.dataclass(frozen=True)
class _Layout:
    """The pose-independent part of a model: node numbering, joint nodes, springs, masses."""

    first_nodes: tuple[int, ...]
    n_nodes: int
    springs: Springs
    point_masses: tuple[tuple[int, float], ...]
    joint_nodes: dict[str, tuple[int, ...]]


def in_plane_stiffness(joint: JointSpec) -> tuple[float, float, float]:
    """A joint's bearing stiffness on (ux, uy, rz): Kt, Kt [N/m], Kr [N m/rad]."""
    return joint.Kt, joint.Kt, joint.Kr


def _layout(topology: Topology) -> _Layout:
    joint_nodes = {j.name: [] for j in topology.joints}
    first_nodes, next_node = [], 0
    for spec in topology.links:
        for joint in (spec.start, spec.end):
            if joint not in joint_nodes:
                raise InputError(f"link {spec.name!r} names joint {joint!r}, which is not defined",
                                 field=f"links.{spec.name}", expected=f"one of {list(joint_nodes)}")
        first_nodes.append(next_node)
        joint_nodes[spec.start].append(next_node)
        joint_nodes[spec.end].append(next_node + spec.elements)
        next_node += spec.elements + 1

    point_masses = []
    for joint in topology.joints:
        attached = joint_nodes[joint.name]
        if not attached:
            raise InputError(f"joint {joint.name!r} has no link attached", field=f"joints.{joint.name}")
        if joint.mass > 0:
            point_masses.append((attached[0], joint.mass))
    springs = springs_of_joints(topology, joint_nodes, first_nodes, IN_PLANE_JOINTS,
                                in_plane_stiffness)
    return _Layout(first_nodes=tuple(first_nodes), n_nodes=next_node,
                   springs=springs, point_masses=tuple(point_masses),
                   joint_nodes={name: tuple(v) for name, v in joint_nodes.items()})


_cached_layout = functools.lru_cache(maxsize=32)(_layout)


@functools.lru_cache(maxsize=64)
def _fractions(elements: int) -> np.ndarray:
    t = np.linspace(0.0, 1.0, elements + 1)[:, None]
    t.flags.writeable = False
    return t


def layout(topology: Topology) -> _Layout:
    """The pose-independent part of ``topology``'s models, cached per topology."""
    try:
        return _cached_layout(topology)
    except TypeError:  # a topology built from lists is not hashable: nothing to cache
        return _layout(topology)


def build_model(topology: Topology, points: dict[str, tuple[float, float]],
                known_layout: _Layout | None = None) -> FrameModel:
    """Mesh every link between its joints' positions ``points`` [m] and join them with springs.

    Node numbering, springs and masses depend on the topology alone and are worked out once per
    topology (cached; a caller looping over poses may pass ``layout(topology)`` as ``known_layout``
    to skip even the cache look-up, which hashes the whole topology)."""
    lay = known_layout or layout(topology)
    nodes, links = [], []
    for spec, first in zip(topology.links, lay.first_nodes):
        for joint in (spec.start, spec.end):
            if joint not in points:
                raise InputError(f"no position for joint {joint!r}", field="pose")
        (x0, y0), (x1, y1) = points[spec.start], points[spec.end]
        dx, dy = float(x1) - float(x0), float(y1) - float(y0)
        length = math.hypot(dx, dy)
        if length <= 0:
            raise InputError(f"link {spec.name!r} has zero length at this pose",
                             field=f"links.{spec.name}")
        nodes.append(np.array([x0, y0], dtype=float) + _fractions(spec.elements) * (dx, dy))
        links.append(LinkMesh(spec.name, first, spec.elements, length, math.atan2(dy, dx),
                              spec.section))
    return FrameModel(nodes=np.concatenate(nodes), links=tuple(links), springs=lay.springs,
                      point_masses=lay.point_masses, joint_nodes=dict(lay.joint_nodes))
