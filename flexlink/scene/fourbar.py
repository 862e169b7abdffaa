"""Scene kind "four-bar": a crank-rocker O2-A-B-O4 given by ratios or lengths, analysed at one
pose (a transmission angle or a crank angle), with the links crank, coupler and rocker."""

from __future__ import annotations

from flexlink.errors import InputError, KinematicsError
from flexlink.fe.model import LinkSpec
from flexlink.kinematics import FourBar
from flexlink.kinematics.linkage import four_bar_linkage
from flexlink.scene import parts, schema
from flexlink.meshes import DEFAULT_ELEMENTS
from flexlink.scene.contract import Scene, SceneKind
from flexlink.scene.source import SceneSource

LINKS = (("crank", "O2", "A"), ("coupler", "A", "B"), ("rocker", "O4", "B"))
JOINTS = ("O2", "A", "B", "O4")
GROUND = {"O2", "O4"}


def build_four_bar(src: SceneSource, sf: schema.SceneFile) -> Scene:
    lk: schema.FourBarLinkage = sf.linkage
    if lk.R2 is not None:
        fb = FourBar.from_ratios(lk.R2, lk.R3, lk.R4, ground=lk.ground)
    else:
        fb = FourBar(lk.ground, lk.crank, lk.coupler, lk.rocker)
    names = [name for name, _, _ in LINKS]
    for name, table in sf.links.items():
        if name not in names:
            raise parts.unknown_name(src, f"links.{name}", "link", name, names)
        for key in ("start", "end", "elements"):
            if getattr(table, key) is not None:
                raise InputError("a four-bar's link ends and mesh are fixed; set "
                                       "[mesh] elements_per_link for the mesh",
                                       source=src.file_of(f"links.{name}.{key}"),
                                       field=f"links.{name}.{key}")
    pose = sf.pose
    if pose.crank_angle is not None:
        start = pose.crank_angle
    else:
        try:
            start = fb.crank_angles_for_mu(pose.transmission_angle)[0]
        except KinematicsError as exc:  # the linkage cannot take this pose: say where it is asked
            raise KinematicsError(f"{src.file_of('pose.transmission_angle')}: "
                                  f"pose.transmission_angle: {exc}") from None
    guess = {k: v for k, v in fb.pose(start, pose.branch).joints.items() if k in ("A", "B")}
    assumptions = list(src.assumptions)
    lengths = dict(zip(("crank", "coupler", "rocker"), fb.lengths[1:]))
    elements = sf.mesh.elements_per_link or DEFAULT_ELEMENTS
    links = tuple(LinkSpec(name, a, b, parts.section(src, sf, name, parts.material(
        src, sf, name, assumptions), lengths[name]), elements) for name, a, b in LINKS)
    loss = {name: parts.loss_factor(src, sf, name, assumptions) for name, _, _ in LINKS}
    return Scene(
        name=sf.name or src.path.stem, path=str(src.path), kind=SceneKind.FOUR_BAR,
        linkage=four_bar_linkage(*fb.lengths), four_bar=fb, start=start, branch=pose.branch,
        guess=guess, transmission=(("coupler", "rocker"),), links=links,
        joints=parts.joints(src, sf, list(JOINTS), GROUND, welded_allowed=False),
        drive=parts.drive(src, sf, {n: (a, b) for n, a, b in LINKS}, GROUND),
        elements_per_link=sf.mesh.elements_per_link, reference=parts.reference(sf),
        assumptions=parts.unique(assumptions + parts.default_assumptions(src, sf, list(JOINTS))), options=parts.options(src, sf, list(JOINTS)),
        composite=parts.composite(sf), loss_factors=loss, origin=dict(src.origin),
        materials={name: parts.link_material(src, sf, name) for name, _, _ in LINKS})

