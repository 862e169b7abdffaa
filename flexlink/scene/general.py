"""Scene kind "general": any planar linkage of revolute joints with one input, as data.

The kinematics come from a four-bar source (``[linkage.four_bar]`` lengths or
``[linkage.synthesis]``) or from ``[linkage.ground]`` pivots, ``[linkage.bodies]``, a
``guess`` of the moving joints and the ``driver`` body. Four-bar sources name their joints O2,
A, B, O4 and bodies crank, coupler, rocker (as ``kinematics.FourBar``). ``[linkage.points.NAME]``
adds a joint fixed ``on`` a body, placed at the start pose at ``at`` times the length of body
``along`` on its axis (e.g. where a compliant strip that continues the rocker is clamped to the
coupler). Beams are optional (a kinematics-only scene has none): ``[links.NAME]`` with start and
end joints.
"""

from __future__ import annotations

import logging
import math

import numpy as np

from flexlink.errors import InputError, KinematicsError
from flexlink.fe.model import LinkSpec
from flexlink.kinematics import Body, FourBar, Linkage
from flexlink.kinematics.synthesis import brodell_soni, extended_rocker, minimax
from flexlink.scene import parts, schema
from flexlink.meshes import DEFAULT_ELEMENTS
from flexlink.scene.contract import Scene, SceneKind
from flexlink.scene.source import SceneSource

FOUR_BAR_BODIES = (("crank", "O2", "A"), ("coupler", "A", "B"), ("rocker", "O4", "B"))

log = logging.getLogger(__name__)


def _synthesised(s) -> tuple[FourBar, dict]:
    if isinstance(s, schema.BrodellSoni):
        inputs = {"gamma_min_deg": math.degrees(s.gamma_min), "swing_deg": math.degrees(s.swing)}
        fb = brodell_soni(s.gamma_min, s.swing, s.ground)
    elif isinstance(s, schema.Minimax):
        inputs = {"theta4i_deg": math.degrees(s.theta4i), "delta_deg": math.degrees(s.delta)}
        fb = minimax(s.theta4i, s.delta, s.ground)
    else:
        inputs = {"rocker_design_m": s.rocker, "swing_deg": math.degrees(s.swing),
                  "coupler_ratio": s.coupler_ratio, "k": s.k}
        fb = extended_rocker(s.rocker, s.swing, s.coupler_ratio, s.k)
    lengths = dict(zip(("ground", "crank", "coupler", "rocker"), fb.lengths))
    inputs = {k: round(v, 9) for k, v in inputs.items()}  # for reading: 30, not 29.999999999999996
    return fb, {"method": s.method, "inputs": inputs, "lengths_m": lengths}


def _kinematics(src: SceneSource, lk: schema.GeneralLinkage):
    """(ground, bodies, driver, guess, transmission, four_bar, synthesis, start)."""
    start = lk.start
    if lk.four_bar is not None or lk.synthesis is not None:
        if lk.four_bar is not None:
            f = lk.four_bar
            fb, synthesis = FourBar(f.ground, f.crank, f.coupler, f.rocker), None
        else:
            fb, synthesis = _synthesised(lk.synthesis)
        if lk.start_transmission_angle is not None:
            # start where the transmission angle has this value (crank in [0, 180] deg)
            try:
                start = fb.crank_angles_for_mu(lk.start_transmission_angle)[0]
            except KinematicsError as exc:
                field = "linkage.start_transmission_angle"
                raise KinematicsError(f"{src.file_of(field)}: {field}: {exc}") from None
        ground = {"O2": (0.0, 0.0), "O4": (fb.ground, 0.0)}
        lengths = dict(zip(("crank", "coupler", "rocker"), fb.lengths[1:]))
        bodies = [Body.bar(n, a, b, lengths[n]) for n, a, b in FOUR_BAR_BODIES]
        guess = {k: v for k, v in fb.pose(start, lk.branch).joints.items() if k in ("A", "B")}
        return ground, bodies, "crank", guess, (("coupler", "rocker"),), fb, synthesis, start
    bodies = []
    for name, b in lk.bodies.items():
        if len(b.joints) == 2:
            bodies.append(Body.bar(name, *b.joints, b.length))
        else:
            bodies.append(Body.polar(name, b.joints, b.arms, b.angles))
    names = [b.name for b in bodies]
    if lk.driver not in names:
        raise parts.unknown_name(src, "linkage.driver", "body", lk.driver, names)
    for i, pair in enumerate(lk.transmission):
        for body in pair:
            if body not in names:
                raise parts.unknown_name(src, f"linkage.transmission[{i}]", "body", body, names)
    return (dict(lk.ground), bodies, lk.driver, dict(lk.guess), tuple(lk.transmission), None,
            None, start)


def _with_points(src: SceneSource, lk: schema.GeneralLinkage, bodies: list[Body], ground: dict,
                 driver: str, guess: dict, start: float) -> list[Body]:
    """Add the [linkage.points.NAME] joints: fixed ``on`` a body, placed where at the start
    pose the point at ``at`` times the length of body ``along`` (default: the same body) lies on
    that body's axis. E.g. the clamp of a compliant strip that continues the rocker's line."""
    if not lk.points:
        return bodies
    out = {b.name: b for b in bodies}
    pose = Linkage(ground=ground, bodies=tuple(bodies), driver=driver).solve(start, guess)
    for name, p in lk.points.items():
        for key, body in (("on", p.on), ("along", p.along or p.on)):
            if body not in out:
                raise parts.unknown_name(src, f"linkage.points.{name}.{key}", "body", body, out)
        on, along = out[p.on], out[p.along or p.on]
        p0, p1 = (np.array(pose.points[j]) for j in along.joints[:2])
        point = p0 + p.at * (p1 - p0)
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


def _across_bodies(src: SceneSource, linkage: Linkage, name: str, start: str,
                   end: str) -> InputError:
    """The error for a beam whose two joints lie on no one rigid body."""
    def holders(joint):
        names = [b.name for b in linkage.bodies if joint in b.joints]
        return ", ".join(names) or "the ground"

    return InputError(
        f"beam {name!r} joins {start} (on {holders(start)}) and {end} (on {holders(end)}), "
        "which lie on no one body: a beam is part of one rigid body of the linkage (only "
        "a compliant strip named in [prb] strip may span a pin)",
        source=src.file_of(f"links.{name}"), field=f"links.{name}",
        expected="start and end joints of one body in [linkage.bodies] (or of a four-bar's "
                 "crank, coupler or rocker)")


def structure_warnings(linkage: Linkage, links, joints) -> list[str]:
    """What the beams make of the linkage that the scene does not say:
      - a body of three or more joints meshed as beams that meet on pins without forming a
        triangle: they do not make the rigid body, and add a mechanism mode (near 0 Hz) under
        a rigid drive, unless the joint where they meet is welded (a ground joint) or rigid in
        rotation (Kr = 'rigid');
      - Kt = 0 at a ground bearing or where beams meet: the links are not connected there
        (free-free beams, rigid-body modes)."""
    out = []
    spec = {j.name: j for j in joints}
    for body in linkage.bodies:
        if len(body.joints) < 3:
            continue
        beams = [l for l in links if l.start in body.joints and l.end in body.joints]
        ends = {j for l in beams for j in (l.start, l.end)}
        if len(beams) < 2 or len(beams) >= len(ends):  # one beam, or a closed (rigid) truss
            continue
        meets = sorted(j for j in ends if sum(j in (l.start, l.end) for l in beams) > 1)
        loose = [j for j in meets if j in spec and not (spec[j].welded or math.isinf(spec[j].Kr))]
        if loose:
            names = ", ".join(l.name for l in beams)
            out.append(
                f"body {body.name}: beams {names} meet on a pin at {', '.join(loose)}, so they "
                f"do not form the rigid body {body.name}: they add a mechanism mode (near 0 Hz). "
                "Weld them: [joints.NAME] welded = true at a ground joint, Kr = 'rigid' at a "
                "moving one")
    beams_at = {j.name: sum(j.name in (l.start, l.end) for l in links) for j in joints}
    free = [j.name for j in joints if j.Kt == 0 and (j.ground or beams_at[j.name] > 1)]
    if free:
        out.append(f"Kt = 0 N/m at {', '.join(free)}: the links are disconnected there (each "
                   "beam free-free, with its own rigid-body modes), not a linkage; give the "
                   "bearings and pins a stiffness")
    return out


def build_general(src: SceneSource, sf: schema.SceneFile) -> Scene:
    lk: schema.GeneralLinkage = sf.linkage
    ground, bodies, driver, guess, transmission, fb, synthesis, start = _kinematics(src, lk)
    bodies = _with_points(src, lk, bodies, ground, driver, guess, start)
    linkage = Linkage(ground=ground, bodies=tuple(bodies), driver=driver)
    known = sorted({j for b in bodies for j in b.joints} | set(ground))
    assumptions = list(src.assumptions)
    links, used, loss = [], [], {}
    for name, table in sf.links.items():
        for key in ("start", "end"):
            joint = getattr(table, key)
            if joint is None:
                raise InputError("missing", source=src.file_of(f"links.{name}"),
                                 field=f"links.{name}.{key}", expected=f"a joint, one of {known}")
            if joint not in known:
                raise parts.unknown_name(src, f"links.{name}.{key}", "joint", joint, known)
        length = _link_length(linkage, table.start, table.end)
        compliant = sf.prb is not None and sf.prb.strip == name  # its bending is the pin
        if length is None and not compliant and not {table.start, table.end} <= set(ground):
            raise _across_bodies(src, linkage, name, table.start, table.end)
        n = table.elements or sf.mesh.elements_per_link or DEFAULT_ELEMENTS
        section = parts.section(src, sf, name, parts.material(src, sf, name, assumptions), length)
        links.append(LinkSpec(name, table.start, table.end, section, n))
        loss[name] = parts.loss_factor(src, sf, name, assumptions)
        used += [j for j in (table.start, table.end) if j not in used]
    joints = parts.joints(src, sf, used, set(ground)) if links else ()
    for warning in structure_warnings(linkage, tuple(links), joints):
        log.warning("%s: %s", src.path, warning)
    return Scene(
        name=sf.name or src.path.stem, path=str(src.path), kind=SceneKind.GENERAL, linkage=linkage,
        four_bar=fb, start=start, branch=lk.branch, guess=guess, transmission=transmission,
        links=tuple(links), joints=joints,
        drive=parts.drive(src, sf, {l.name: (l.start, l.end) for l in links}, set(ground)),
        elements_per_link=sf.mesh.elements_per_link, reference=parts.reference(sf),
        assumptions=parts.unique(assumptions + parts.default_assumptions(src, sf, used)), options=parts.options(src, sf, used),
        synthesis=synthesis, composite=parts.composite(sf), loss_factors=loss,
        origin=dict(src.origin), materials={l.name: parts.link_material(src, sf, l.name)
                                            for l in links})
