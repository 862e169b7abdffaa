"""Scene files for general linkages (``linkage.type = "general"``): any one-input planar linkage
of revolute joints, its beams, joints and drive. ``scene.load_scene`` dispatches here.

Kinematics ([linkage]), one of:
  - ``[linkage.four_bar]`` ground/crank/coupler/rocker lengths;
  - ``[linkage.synthesis]`` method = "brodell-soni" (gamma_min, swing, ground), "minimax"
    (theta4i, delta, ground) or "extended-rocker" (rocker, swing, coupler_ratio, k);
  - ``[linkage.ground]`` pivots, ``[linkage.bodies.NAME]`` (joints and ``length``, or ``arms``
    and ``angles`` for three or more joints), ``[linkage.guess]`` sketch positions of the moving
    joints at the start angle, ``linkage.driver`` and optional ``linkage.transmission`` pairs.
  Four-bar sources name their joints O2, A, B, O4 and bodies crank, coupler, rocker (as in
  ``kinematics.FourBar``). ``linkage.start`` is the first input angle (or, for a four-bar,
  ``linkage.start_transmission_angle``); ``linkage.branch`` the four-bar assembly branch.
  ``[linkage.points.NAME]`` adds a joint fixed ``on`` a body, placed at the start pose at
  ``at`` times the length of body ``along`` on its axis (e.g. where a compliant strip that
  continues the rocker is clamped to the coupler).
Finite elements (optional; a kinematics-only scene has none): ``[links.NAME]`` start, end and
``[links.NAME.section]`` (width/thickness, area/second_moment, or tube_inner_radius with
tube_outer_radius or mass), material per link or shared; ``[joints]`` Kt/Kr defaults and
``[joints.NAME]`` Kt, Kr, mass, welded; ``[drive]`` as for four-bars. A section ``mass`` [kg]
sets the thickness of a flat bar or the wall of a tube from the link's length.
Optional, read by the commands: ``operation.crank_speed``, ``[[family]]`` (field, values:
overrides that make the scene's variants), ``[prb]`` (pseudo-rigid-body comparison).
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np

from flexlink.errors import InputError
from flexlink.kinematics.fourbar import BRANCHES, FourBar
from flexlink.kinematics.linkage import Body, Linkage, four_bar_linkage
from flexlink.fe.model import DriveSpec, JointSpec, LinkSpec, Section, Topology
from flexlink.scene.load import Assumption, SceneReader, _material, _unique, joint_inputs
from flexlink.kinematics.synthesis import brodell_soni, extended_rocker, minimax
from flexlink.units import parse_quantity

FOUR_BAR_BODIES = (("crank", "O2", "A"), ("coupler", "A", "B"), ("rocker", "O4", "B"))


@dataclasses.dataclass(frozen=True)
class GeneralScene:
    """A general linkage scene: kinematics, optional beam model, what to report."""

    name: str
    path: str
    linkage: Linkage
    guess: dict[str, tuple[float, float]]  # moving joints near the pose at ``start`` [m]
    start: float  # [rad]
    transmission: tuple[tuple[str, str], ...]  # body pairs whose angle at their shared joint is mu
    links: tuple[LinkSpec, ...]
    joints: tuple[JointSpec, ...]
    drive: DriveSpec | None
    synthesis: dict | None  # method, inputs and the synthesised lengths [m]
    four_bar: FourBar | None
    assumptions: tuple[Assumption, ...]
    data: dict = dataclasses.field(default_factory=dict, repr=False, compare=False)
    origin: dict = dataclasses.field(default_factory=dict, repr=False, compare=False)

    def reader(self) -> SceneReader:
        return SceneReader(self.data, self.origin, Path(self.path))

    def topology(self, elements_per_link: int | None = None) -> Topology:
        if not self.links:
            raise InputError("the scene has no [links] beams: kinematics only", source=self.path,
                             field="links")
        links = tuple(dataclasses.replace(s, elements=elements_per_link) if elements_per_link
                      else s for s in self.links)
        return Topology(links=links, joints=self.joints, drive=self.drive)


def _four_bar_source(r: SceneReader) -> tuple[FourBar, dict | None]:
    if r.has("linkage.four_bar"):
        return FourBar(*(r.quantity(f"linkage.four_bar.{k}", "length")
                         for k in ("ground", "crank", "coupler", "rocker"))), None
    method = r.raw("linkage.synthesis.method")
    s = "linkage.synthesis"
    if method == "brodell-soni":
        inputs = {"gamma_min_deg": math.degrees(r.quantity(f"{s}.gamma_min", "angle")),
                  "swing_deg": math.degrees(r.quantity(f"{s}.swing", "angle"))}
        fb = brodell_soni(math.radians(inputs["gamma_min_deg"]), math.radians(inputs["swing_deg"]),
                          r.quantity(f"{s}.ground", "length"))
    elif method == "minimax":
        inputs = {"theta4i_deg": math.degrees(r.quantity(f"{s}.theta4i", "angle")),
                  "delta_deg": math.degrees(r.quantity(f"{s}.delta", "angle"))}
        fb = minimax(math.radians(inputs["theta4i_deg"]), math.radians(inputs["delta_deg"]),
                     r.quantity(f"{s}.ground", "length"))
    elif method == "extended-rocker":
        inputs = {"rocker_design_m": r.quantity(f"{s}.rocker", "length"),
                  "swing_deg": math.degrees(r.quantity(f"{s}.swing", "angle")),
                  "coupler_ratio": r.number(f"{s}.coupler_ratio", 1.0, 1e3),
                  "k": r.number(f"{s}.k", 1e-3, 1e3, default=1.0)}
        fb = extended_rocker(inputs["rocker_design_m"], math.radians(inputs["swing_deg"]),
                             inputs["coupler_ratio"], inputs["k"])
    else:
        raise InputError(f"unknown synthesis {method!r}", source=r.src(f"{s}.method"),
                         field=f"{s}.method", expected="brodell-soni, minimax or extended-rocker")
    lengths = dict(zip(("ground", "crank", "coupler", "rocker"), fb.lengths))
    inputs = {k: round(v, 9) for k, v in inputs.items()}  # for reading: 30, not 29.999999999999996
    return fb, {"method": method, "inputs": inputs, "lengths_m": lengths}


def _point(r: SceneReader, field: str) -> tuple[float, float]:
    value = r.raw(field)
    if not (isinstance(value, list) and len(value) == 2):
        raise InputError(f"got {value!r}", source=r.src(field), field=field,
                         expected="[x, y] with units, e.g. ['458 mm', '0 mm']")
    return tuple(_length(v, r, field) for v in value)


def _length(text, r: SceneReader, field: str) -> float:
    return parse_quantity(text, "length", source=r.src(field), field=field)


def _kinematics(r: SceneReader, start: float):
    """(ground, bodies, driver, guess, transmission, four_bar, synthesis) from [linkage]."""
    if r.has("linkage.four_bar") or r.has("linkage.synthesis"):
        fb, synthesis = _four_bar_source(r)
        branch = r.raw("linkage.branch", "open")
        if branch not in BRANCHES:
            raise InputError(f"got {branch!r}", source=r.src("linkage.branch"),
                             field="linkage.branch", expected=" or ".join(BRANCHES))
        ground = {"O2": (0.0, 0.0), "O4": (fb.ground, 0.0)}
        lengths = {"crank": fb.crank, "coupler": fb.coupler, "rocker": fb.rocker}
        bodies = [Body.bar(n, a, b, lengths[n]) for n, a, b in FOUR_BAR_BODIES]
        guess = {k: v for k, v in fb.pose(start, branch).joints.items() if k in ("A", "B")}
        return ground, bodies, "crank", guess, (("coupler", "rocker"),), fb, synthesis
    ground = {name: _point(r, f"linkage.ground.{name}") for name in r.raw("linkage.ground")}
    bodies = []
    for name, spec in r.raw("linkage.bodies").items():
        field = f"linkage.bodies.{name}"
        joints = spec.get("joints") if isinstance(spec, dict) else None
        if not (isinstance(joints, list) and len(joints) >= 2
                and all(isinstance(j, str) for j in joints)):
            raise InputError(f"got {joints!r}", source=r.src(field), field=f"{field}.joints",
                             expected="a list of two or more joint names")
        if len(joints) == 2:
            bodies.append(Body.bar(name, *joints, r.quantity(f"{field}.length", "length")))
        else:
            arms = [_length(v, r, f"{field}.arms") for v in r.raw(f"{field}.arms")]
            angles = [parse_quantity(v, "angle", source=r.src(field), field=f"{field}.angles")
                      for v in r.raw(f"{field}.angles")]
            bodies.append(Body.polar(name, joints, arms, angles))
    guess = {name: _point(r, f"linkage.guess.{name}") for name in r.raw("linkage.guess")}
    pairs = r.raw("linkage.transmission", [])
    transmission = tuple(tuple(p) for p in pairs)
    return ground, bodies, r.raw("linkage.driver"), guess, transmission, None, None


def _with_points(r: SceneReader, bodies: list[Body], ground: dict, driver: str, guess: dict,
                 start: float) -> list[Body]:
    """Add the [linkage.points.NAME] joints: fixed ``on`` a body, placed where at the start
    pose the point at ``at`` times the length of body ``along`` (default: the same body) lies on
    that body's axis. E.g. the clamp of a compliant strip that continues the rocker's line."""
    if not r.has("linkage.points"):
        return bodies
    out = {b.name: b for b in bodies}
    pose = Linkage(ground=ground, bodies=tuple(bodies), driver=driver).solve(start, guess)
    for name in r.raw("linkage.points"):
        field = f"linkage.points.{name}"
        on, along = (out.get(r.raw(f"{field}.{k}", r.raw(f"{field}.on"))) for k in ("on", "along"))
        if on is None or along is None:
            raise InputError("no such body", source=r.src(field), field=f"{field}.on/along",
                             expected=f"one of {list(out)}")
        at = r.number(f"{field}.at", -1e3, 1e3)
        p0, p1 = (np.array(pose.points[j]) for j in along.joints[:2])
        point = p0 + at * (p1 - p0)
        q0, q1 = (np.array(pose.points[j]) for j in on.joints[:2])
        e = (q1 - q0) / np.linalg.norm(q1 - q0)
        local = point - q0
        shape = (float(local @ e), float(e[0] * local[1] - e[1] * local[0]))
        out[on.name] = Body(on.name, on.joints + (name,), on.shape + (shape,))
        guess[name] = tuple(point)
    return list(out.values())


def _link_length(linkage: Linkage, start: str, end: str) -> float | None:
    """Distance [m] between two joints of one body (None if no body holds both)."""
    for b in linkage.bodies:
        if start in b.joints and end in b.joints:
            p, q = (np.array(b.shape[b.joints.index(j)]) for j in (start, end))
            return float(np.linalg.norm(q - p))
    return None


def _section(r: SceneReader, link: str, material, length: float | None) -> Section:
    def field(key):
        own = f"links.{link}.section.{key}"
        return own if r.has(own) else f"section.{key}"

    label = f"{link}: {material.name}"
    if r.has(field("area")):
        area = r.quantity(field("area"), "area")
        second = r.quantity(field("second_moment"), "second moment")
        # depth of the rectangle with this A and I: only used for slenderness messages
        return Section(material.E, material.G, material.density, area, second,
                       math.sqrt(12 * second / area), name=f"{label}, A {area:.4g} m^2")
    if r.has(field("tube_inner_radius")):
        inner = r.quantity(field("tube_inner_radius"), "length")
        if r.has(field("tube_outer_radius")):
            outer = r.quantity(field("tube_outer_radius"), "length")
        else:  # the wall from the link's mass and length: m = rho pi (ro^2 - ri^2) l
            mass = r.quantity(field("mass"), "mass")
            outer = math.sqrt(inner**2 + mass / (material.density * math.pi * length))
        return Section.tube(material.E, material.G, material.density, outer, inner,
                            name=f"{label}, tube {2e3 * outer:.3f} x {1e3 * (outer - inner):.3f}"
                                 " mm")
    width = r.quantity(field("width"), "length")
    if r.has(field("thickness")):
        thickness = r.quantity(field("thickness"), "length")
    else:  # out-of-plane thickness from the link's mass: m = rho width thickness l
        thickness = r.quantity(field("mass"), "mass") / (material.density * width * length)
    return Section.rectangle(material.E, material.G, material.density, width, thickness,
                             name=f"{label}, {width * 1e3:g} x {thickness * 1e3:.3f} mm")


def load_general(r: SceneReader, path: Path) -> GeneralScene:
    """Build a GeneralScene from the merged scene data behind ``r``."""
    start = r.quantity("linkage.start", "angle", default=0.0, positive=False)
    ground, bodies, driver, guess, transmission, fb, synthesis = _kinematics(r, start)
    if fb is not None and r.has("linkage.start_transmission_angle"):
        # start where the transmission angle has this value (crank in [0, 180] deg)
        start = fb.crank_angles_for_mu(r.quantity("linkage.start_transmission_angle", "angle"))[0]
        guess = {k: v for k, v in fb.pose(start, r.raw("linkage.branch", "open")).joints.items()
                 if k in guess}
    bodies = _with_points(r, bodies, ground, driver, guess, start)
    linkage = Linkage(ground=ground, bodies=tuple(bodies), driver=driver)

    elements = r.number("mesh.elements_per_link", 1, 100000, integer=True, default=16)
    links, used = [], []
    for name in r.raw("links", {}):
        start_j, end_j = r.raw(f"links.{name}.start"), r.raw(f"links.{name}.end")
        n = r.number(f"links.{name}.elements", 1, 100000, integer=True, default=elements)
        length = _link_length(linkage, start_j, end_j)
        if length is None and r.has(f"links.{name}.section.mass"):
            raise InputError("a section from mass needs a link between two joints of one body",
                             source=r.src(f"links.{name}"), field=f"links.{name}")
        section = _section(r, name, _material(r, name), length)
        links.append(LinkSpec(name, start_j, end_j, section, n))
        used += [j for j in (start_j, end_j) if j not in used]
    joints = []
    for joint in used:
        welded = r.raw(f"joints.{joint}.welded", False)
        if not isinstance(welded, bool):
            raise InputError(f"got {welded!r}", source=r.src(f"joints.{joint}.welded"),
                             field=f"joints.{joint}.welded", expected="true or false")
        joints.append(JointSpec(joint, joint in ground, *joint_inputs(r, joint), welded))
    drive = None
    if r.has("drive"):
        drive = DriveSpec(link=r.raw("drive.link"), joint=r.raw("drive.joint"),
                          stiffness=r.quantity("drive.stiffness", "rotational stiffness",
                                               allow_zero=True))
    return GeneralScene(name=str(r.raw("name", path.stem)), path=str(path), linkage=linkage,
                        guess=guess, start=start, transmission=transmission, links=tuple(links),
                        joints=tuple(joints), drive=drive, synthesis=synthesis, four_bar=fb,
                        assumptions=tuple(_unique(r.assumptions)), data=r.data, origin=r.origin)


def as_general(scene) -> GeneralScene:
    """A four-bar ``scene.Scene`` seen as a general linkage (same joints, links and springs)."""
    if isinstance(scene, GeneralScene):
        return scene
    fb, topology = scene.linkage, scene.topology()
    start = scene.pose.crank_angle or 0.0
    guess = {k: v for k, v in fb.pose(start, scene.pose.branch).joints.items() if k in ("A", "B")}
    return GeneralScene(name=scene.name, path=scene.path, linkage=four_bar_linkage(*fb.lengths),
                        guess=guess, start=start, transmission=(("coupler", "rocker"),),
                        links=topology.links, joints=topology.joints, drive=topology.drive,
                        synthesis=None, four_bar=fb, assumptions=scene.assumptions,
                        data=scene.data, origin=scene.origin)
