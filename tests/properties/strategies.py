"""Random linkages for the property tests, drawn from the scene schema's valid ranges and
loaded the way a user's scene is: a scene TOML file read by ``flexlink.scene.load_scene``.

A ``LinkageSpec`` is plain data (SI units); ``scene_toml`` writes it as a scene file of either
kind, "four-bar" (lengths and a crank-angle pose) or "general" (ground pivots, bodies, a guess
and a driver), placed anywhere in the plane: ``origin`` [m], ``heading`` (direction of the
ground line O2 -> O4 [rad]) and ``mirror`` (reflect y before placing). The same spec placed
differently is the same physical linkage, which the invariance properties use.

Finite joint springs are drawn as ratios to the link scale (Kt to E A / L1, Kr to E I / L1),
so they stay far below the stiffness at which ``fe.rigid`` turns a spring into an exact
constraint: a drawn spring is a spring, whatever E and the lengths are.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import tempfile
from pathlib import Path

from hypothesis import assume, settings
from hypothesis import strategies as st

from flexlink.kinematics import FourBar
from flexlink.scene import load_scene

JOINTS = ("O2", "A", "B", "O4")
GROUND = ("O2", "O4")
LINKS = (("crank", "O2", "A"), ("coupler", "A", "B"), ("rocker", "O4", "B"))
RIGID = math.inf

# For properties whose every example solves fine meshes or runs a command: a quarter of the
# profile's examples (5 in ``ci``, 100 in ``thorough``).
fewer = settings(max_examples=max(3, settings().max_examples // 4))

_folder = Path(tempfile.mkdtemp(prefix="flexlink-props-"))
_count = itertools.count()


@dataclasses.dataclass(frozen=True)
class JointValues:
    """Kt [N/m], Kr [N m/rad] (inf: rigid) and the lumped mass [kg] of one joint."""

    Kt: float
    Kr: float
    mass: float = 0.0


@dataclasses.dataclass(frozen=True)
class Section:
    """A flat bar ``width`` x ``thickness`` [m] lying ``bending`` ("edgewise": width in the
    plane; "flatwise": thickness in the plane), or, with ``area`` [m^2] and ``second_moment``
    [m^4] set, the A-and-I form."""

    width: float = 0.02
    thickness: float = 0.005
    bending: str = "edgewise"
    area: float | None = None
    second_moment: float | None = None

    def toml(self) -> str:
        if self.area is not None:
            return (f'{{ area = "{self.area!r} m^2", '
                    f'second_moment = "{self.second_moment!r} m^4" }}')
        return (f'{{ width = "{self.width!r} m", thickness = "{self.thickness!r} m", '
                f'bending = "{self.bending}" }}')

    @property
    def A(self) -> float:
        return self.area if self.area is not None else self.width * self.thickness

    @property
    def I(self) -> float:
        if self.second_moment is not None:
            return self.second_moment
        depth, across = ((self.width, self.thickness) if self.bending == "edgewise"
                         else (self.thickness, self.width))
        return across * depth**3 / 12


@dataclasses.dataclass(frozen=True)
class LinkageSpec:
    """A four-bar crank-rocker with beams, joints and an optional drive; SI units."""

    lengths: tuple[float, float, float, float]  # ground, crank, coupler, rocker [m]
    crank_angle: float  # [rad] from the ground line O2 -> O4
    E: float  # [Pa]
    G: float  # [Pa]
    density: float  # [kg/m^3]
    sections: dict  # link name -> Section
    joints: dict  # joint name -> JointValues
    drive: float | None  # drive stiffness [N m/rad], inf rigid, None: no drive
    beam: str = "euler-bernoulli"
    elements: int = 3
    kind: str = "four-bar"
    branch: str = "open"
    origin: tuple[float, float] = (0.0, 0.0)
    heading: float = 0.0
    mirror: bool = False

    def placed(self, origin=(0.0, 0.0), heading=0.0, mirror=False) -> LinkageSpec:
        """The same linkage as a general scene, placed at ``origin`` with the ground line at
        ``heading`` and, with ``mirror``, reflected."""
        return dataclasses.replace(self, kind="general", origin=tuple(origin), heading=heading,
                                   mirror=mirror)

    def local_points(self) -> dict[str, tuple[float, float]]:
        """Joint positions [m] in the four-bar's own frame (O2 at 0, O4 on +x)."""
        return FourBar(*self.lengths).pose(self.crank_angle, self.branch).joints

    def place(self, p) -> tuple[float, float]:
        """A point of the four-bar's own frame in the global frame [m]."""
        x, y = p[0], -p[1] if self.mirror else p[1]
        c, s = math.cos(self.heading), math.sin(self.heading)
        return (self.origin[0] + c * x - s * y, self.origin[1] + s * x + c * y)

    def rotation_matrix(self):
        """2x2 matrix taking vectors of the four-bar's own frame to the global frame."""
        c, s = math.cos(self.heading), math.sin(self.heading)
        m = -1.0 if self.mirror else 1.0
        return ((c, -s * m), (s, c * m))

    @property
    def total_mass(self) -> float:
        """Links (rho A L) and joint masses [kg]."""
        _, crank, coupler, rocker = self.lengths
        lengths = {"crank": crank, "coupler": coupler, "rocker": rocker}
        return (sum(self.density * self.sections[n].A * lengths[n] for n in lengths)
                + sum(j.mass for j in self.joints.values()))


def _stiffness(value: float, unit: str) -> str:
    return '"rigid"' if math.isinf(value) else f'"{value!r} {unit}"'


def scene_toml(spec: LinkageSpec) -> str:
    """The scene file of ``spec``, of its ``kind``."""
    ground, crank, coupler, rocker = spec.lengths
    lines = ['name = "drawn linkage"']
    if spec.kind == "four-bar":
        if spec.origin != (0.0, 0.0) or spec.heading != 0.0 or spec.mirror:
            raise ValueError("a four-bar scene sits at the origin along +x; place a general one")
        lines += ["[linkage]", 'type = "four-bar"', f'ground = "{ground!r} m"',
                  f'crank = "{crank!r} m"', f'coupler = "{coupler!r} m"',
                  f'rocker = "{rocker!r} m"',
                  "[pose]", f'crank_angle = "{spec.crank_angle!r} rad"',
                  f'branch = "{spec.branch}"']
    else:
        local = spec.local_points()
        placed = {j: spec.place(local[j]) for j in JOINTS}
        start = spec.heading + (-spec.crank_angle if spec.mirror else spec.crank_angle)
        lines += ["[linkage]", 'type = "general"', 'driver = "crank"',
                  f'start = "{start!r} rad"', 'transmission = [["coupler", "rocker"]]',
                  "[linkage.ground]"]
        lines += [f'{j} = ["{placed[j][0]!r} m", "{placed[j][1]!r} m"]' for j in GROUND]
        for name, a, b in LINKS:
            length = {"crank": crank, "coupler": coupler, "rocker": rocker}[name]
            lines += [f"[linkage.bodies.{name}]", f'joints = ["{a}", "{b}"]',
                      f'length = "{length!r} m"']
        lines += ["[linkage.guess]"]
        lines += [f'{j} = ["{placed[j][0]!r} m", "{placed[j][1]!r} m"]' for j in ("A", "B")]
    lines += ["[material]", f'E = "{spec.E!r} Pa"', f'G = "{spec.G!r} Pa"',
              f'density = "{spec.density!r} kg/m^3"']
    for name, a, b in LINKS:
        lines += [f"[links.{name}]"]
        if spec.kind == "general":
            lines += [f'start = "{a}"', f'end = "{b}"']
        lines += [f"section = {spec.sections[name].toml()}"]
    lines += ["[joints]"]
    for name in JOINTS:
        j = spec.joints[name]
        lines += [f"[joints.{name}]", f"Kt = {_stiffness(j.Kt, 'N/m')}",
                  f"Kr = {_stiffness(j.Kr, 'N*m/rad')}", f'mass = "{j.mass!r} kg"']
    if spec.drive is not None:
        lines += ["[drive]", 'link = "crank"', 'joint = "O2"',
                  f"stiffness = {_stiffness(spec.drive, 'N*m/rad')}"]
    lines += ["[mesh]", f"elements_per_link = {spec.elements}",
              "[model]", f'beam = "{spec.beam}"']
    return "\n".join(lines) + "\n"


def write_scene(spec: LinkageSpec | str) -> Path:
    """``spec`` (or scene text) written to a new scene file (a new name each time: the scene
    reader caches a parsed file by path, modification time and size)."""
    path = _folder / f"drawn-{next(_count)}.toml"
    path.write_text(spec if isinstance(spec, str) else scene_toml(spec))
    return path


def cantilever_toml(length: float, angle: float, E: float, G: float, density: float,
                    depth: float, across: float, beam: str) -> str:
    """A general scene of one link clamped at ground joint O (Kt and Kr rigid) and free at P:
    a cantilever of ``length`` [m] at ``angle`` [rad], a flat bar of in-plane ``depth`` and
    out-of-plane ``across`` [m]."""
    tip = (length * math.cos(angle), length * math.sin(angle))
    return "\n".join([
        'name = "cantilever"', "[linkage]", 'type = "general"', 'driver = "arm"',
        f'start = "{angle!r} rad"', "[linkage.ground]", 'O = ["0 m", "0 m"]',
        "[linkage.bodies.arm]", 'joints = ["O", "P"]', f'length = "{length!r} m"',
        "[linkage.guess]", f'P = ["{tip[0]!r} m", "{tip[1]!r} m"]',
        "[material]", f'E = "{E!r} Pa"', f'G = "{G!r} Pa"', f'density = "{density!r} kg/m^3"',
        "[links.arm]", 'start = "O"', 'end = "P"',
        f'section = {{ width = "{depth!r} m", thickness = "{across!r} m", bending = "edgewise" }}',
        "[joints]", 'Kt = "rigid"', 'Kr = "rigid"', "[model]", f'beam = "{beam}"']) + "\n"


def load(spec: LinkageSpec):
    """The ``Scene`` a user would get from ``spec``'s scene file."""
    return load_scene(write_scene(spec))


# -- strategies ------------------------------------------------------------------------------
def log_uniform(low: float, high: float):
    return st.floats(math.log(low), math.log(high)).map(math.exp)


@st.composite
def crank_rockers(draw):
    """(lengths [m], crank angle [rad]): a Grashof crank-rocker (the crank turns fully) at a
    crank angle whose transmission angle is at least 25 deg from a dead centre."""
    ground = draw(log_uniform(0.05, 2.0))
    crank = draw(st.floats(0.12, 0.4))
    coupler, rocker = draw(st.floats(0.6, 1.5)), draw(st.floats(0.6, 1.5))
    longest = max(1.0, coupler, rocker)
    assume(crank + longest <= 1.0 + coupler + rocker - longest - 0.05)  # Grashof, with margin
    theta = draw(st.floats(0.0, 2 * math.pi, exclude_max=True))
    cos_mu = (rocker**2 + coupler**2 - crank**2 - 1 + 2 * crank * math.cos(theta)) / (
        2 * coupler * rocker)
    assume(abs(cos_mu) <= math.cos(math.radians(25)))
    return tuple(ground * r for r in (1.0, crank, coupler, rocker)), theta


@st.composite
def sections(draw, ground: float):
    """A section whose in-plane depth is 0.3 % to 1 % of the ground length, so every link is
    slender (the shortest crank, 0.12 ground, is still 12 depths long); either form."""
    depth = ground * draw(st.floats(0.003, 0.01))
    across = depth * draw(st.floats(0.2, 5.0))
    if draw(st.booleans()):
        return Section(area=depth * across, second_moment=across * depth**3 / 12)
    bending = draw(st.sampled_from(("edgewise", "flatwise")))
    width, thickness = (depth, across) if bending == "edgewise" else (across, depth)
    return Section(width=width, thickness=thickness, bending=bending)


@st.composite
def joint_values(draw, scale_t: float, scale_r: float, scale_m: float, masses: bool = True):
    """Kt rigid or a finite ratio of ``scale_t`` [N/m]; Kr 0, finite (ratio of ``scale_r``
    [N m/rad]) or rigid; no joint mass or a ratio of ``scale_m`` [kg]."""
    Kt = draw(st.one_of(st.just(RIGID), log_uniform(1e-2, 1e2).map(lambda r: r * scale_t)))
    Kr = draw(st.one_of(st.just(0.0), st.just(RIGID),
                        log_uniform(1e-2, 1e2).map(lambda r: r * scale_r)))
    mass = draw(st.one_of(st.just(0.0), log_uniform(1e-2, 1.0).map(lambda r: r * scale_m)))
    mass = mass if masses else 0.0
    return JointValues(Kt, Kr, mass)


@st.composite
def linkages(draw, kind=None, beam=None, drive=None, masses: bool = True,
             elements=None):
    """A ``LinkageSpec``: either scene kind, either beam theory, finite or rigid joints, joint
    masses, a rigid, finite or no drive; ``kind``, ``beam``, ``drive`` ("rigid", "finite",
    "none") pin one choice."""
    lengths, theta = draw(crank_rockers())
    E = draw(log_uniform(1e9, 4e11))
    G = E / draw(st.floats(2.2, 40.0))
    density = draw(st.floats(1000.0, 7000.0))  # times 4 stays in the plausible range
    sec = {name: draw(sections(lengths[0])) for name, _, _ in LINKS}
    crank = sec["crank"]
    scale_t, scale_r = E * crank.A / lengths[0], E * crank.I / lengths[0]
    scale_m = density * crank.A * lengths[1]  # the crank's mass [kg]
    joints = {j: draw(joint_values(scale_t, scale_r, scale_m, masses)) for j in JOINTS}
    drive = drive or draw(st.sampled_from(("rigid", "finite", "none")))
    stiffness = {"rigid": RIGID, "none": None}.get(drive)
    if drive == "finite":
        stiffness = draw(log_uniform(1e-2, 1e2)) * scale_r
    spec = LinkageSpec(lengths=lengths, crank_angle=theta, E=E, G=G, density=density,
                       sections=sec, joints=joints, drive=stiffness,
                       beam=beam or draw(st.sampled_from(("euler-bernoulli", "timoshenko"))),
                       elements=draw(st.integers(2, 3) if elements is None else elements), branch=draw(st.sampled_from(("open", "crossed"))))
    kind = kind or draw(st.sampled_from(("four-bar", "general")))
    if kind == "general":
        spec = spec.placed(*draw(placements()))
    return spec


@st.composite
def placements(draw):
    """(origin [m], heading [rad], mirror): where in the plane to put a linkage."""
    origin = (draw(st.floats(-2.0, 2.0)), draw(st.floats(-2.0, 2.0)))
    return origin, draw(st.floats(-math.pi, math.pi)), draw(st.booleans())


def scaled(spec: LinkageSpec, *, E=1.0, density=1.0, length=1.0, section=1.0, across=1.0,
           Kt=1.0, Kr=1.0, mass=1.0) -> LinkageSpec:
    """``spec`` with E and G times ``E``, density times ``density``, every length (links and
    placement) times ``length``, the in-plane section depth times ``section`` and the
    out-of-plane size times ``across`` (A times section x across, I times section^3 x
    across), finite Kt and the joint masses times ``Kt`` and ``mass``, finite Kr and a finite
    drive times ``Kr``. Rigid stays rigid and zero stays zero."""
    def sec(s: Section) -> Section:
        if s.area is not None:
            return Section(area=s.area * section * across,
                           second_moment=s.second_moment * section**3 * across)
        if s.bending == "edgewise":
            return dataclasses.replace(s, width=s.width * section, thickness=s.thickness * across)
        return dataclasses.replace(s, width=s.width * across, thickness=s.thickness * section)

    joints = {n: JointValues(j.Kt * Kt, j.Kr * Kr, j.mass * mass) for n, j in spec.joints.items()}
    drive = None if spec.drive is None else spec.drive * Kr
    return dataclasses.replace(
        spec, lengths=tuple(length * l for l in spec.lengths), E=spec.E * E, G=spec.G * E,
        density=spec.density * density, sections={n: sec(s) for n, s in spec.sections.items()},
        joints=joints, drive=drive, origin=tuple(length * c for c in spec.origin))
