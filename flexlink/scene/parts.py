"""What both scene kinds build the same way from validated tables: materials, sections, joints,
the drive, the reference table and the stage options. Hidden defaults become assumptions here."""

from __future__ import annotations

import dataclasses
import difflib
import math

from flexlink.errors import InputError
from flexlink.fe.model import DriveSpec, JointSpec, Section
from flexlink.fe.motions import ModelFamily
from flexlink.materials.mixtures import (BeamMaterial, LossFactor, isotropic, load_constituent,
                                         woven_composite)
from flexlink.scene import schema
from flexlink.scene.contract import (Composite, LinkMaterial, ModalDamping, ModalTestFrame,
                                     Options, PrbOptions,
                                     Reference, Variant)
from flexlink.scene.source import Assumption, SceneSource

DEFAULT_G_RATIO = 2.6  # E / G of an isotropic solid with nu = 0.3: 2 (1 + nu)


def tube_shear_factor(outer: float, inner: float, nu: float = 0.3) -> float:
    """Timoshenko shear factor k of a round tube (Cowper 1966), m = inner / outer:
    6 (1 + nu)(1 + m^2)^2 / ((7 + 6 nu)(1 + m^2)^2 + (20 + 12 nu) m^2); 0.886 for a solid rod
    at nu = 0.3, 0.53 for a thin wall."""
    q = 1.0 + (inner / outer) ** 2
    return 6 * (1 + nu) * q * q / ((7 + 6 * nu) * q * q + (20 + 12 * nu) * (inner / outer) ** 2)


def closest(name: str, choices) -> list[str]:
    """Up to two of ``choices`` nearest to ``name`` (spelling, then case)."""
    choices = list(choices)
    close = difflib.get_close_matches(name, choices, n=2, cutoff=0.5)
    return close or [c for c in choices if c.lower() == name.lower()]


def near(name: str, choices, fmt: str = "{}") -> str:
    """'; did you mean X?' for the closest of ``choices``, else the list of them."""
    close = closest(name, choices)
    if close:
        return f"; did you mean {' or '.join(fmt.format(c) for c in close)}?"
    return f"; known: {', '.join(fmt.format(c) for c in choices)}" if choices else ""


def unknown_name(src: SceneSource, field: str, what: str, name: str, choices) -> InputError:
    return InputError(f"unknown {what} {name!r}{near(name, choices)}", source=src.file_of(field),
                      field=field)


def material(src: SceneSource, sf: schema.SceneFile, link: str,
             assumptions: list[Assumption]) -> BeamMaterial:
    """A link's own [links.<link>.material] replaces the shared [material] whole."""
    own = sf.links.get(link)
    field = f"links.{link}.material" if own is not None and own.material else "material"
    m = own.material if own is not None and own.material else sf.material
    if m is None:
        raise InputError("no material given", source=src.file_of(field), field=field,
                         expected="a [material] table: composite, isotropic = 'name', or E and "
                                  "density")
    def constituent(key: str, name: str):
        try:
            return load_constituent(name)
        except InputError as exc:
            raise InputError(str(exc), source=src.file_of(f"{field}.{key}"),
                             field=f"{field}.{key}") from None

    if m.composite is not None:
        c = m.composite
        fibre, matrix = constituent("composite.fiber", c.fiber), constituent("composite.matrix", c.matrix)
        try:
            return woven_composite(fibre, matrix, c.fiber_volume_fraction, shear=c.shear_modulus)
        except InputError as exc:
            raise InputError(str(exc), source=src.file_of(field), field=field) from None
    if m.isotropic is not None:
        return isotropic(constituent("isotropic", m.isotropic))
    G = m.G
    if G is None:
        G = m.E / DEFAULT_G_RATIO
        assumptions.append(Assumption(f"{field}.G", f"{G / 1e9:.4g} GPa",
                                      f"assumed (default): G = E / {DEFAULT_G_RATIO} (an isotropic "
                                      "solid with nu = 0.3); G is not given",
                                      src.file_of(f"{field}.E")))
    return BeamMaterial(name=field, E=m.E, G=G, density=m.density)


# Loss factors [-] where neither the scene nor the material file gives one (Ashby, Materials
# Selection in Mechanical Design, loss-coefficient chart): a woven carbon laminate's is matrix
# dominated (carbon/epoxy 2e-3 to 1e-2, a polyester matrix higher); E and density are taken as
# a structural metal's (1e-4 to 1e-3), the range widened to 1e-2 since the material is unnamed.
WOVEN_LOSS = LossFactor(0.01, 2e-3, 2e-2, "Ashby, loss-coefficient chart (CFRP 2e-3 to 1e-2)")
GENERIC_LOSS = LossFactor(1e-3, 1e-4, 1e-2, "Ashby, loss-coefficient chart (metals 1e-4 to 1e-3)")


def loss_factor(src: SceneSource, sf: schema.SceneFile, link: str,
                assumptions: list[Assumption]) -> float:
    """A link's material loss factor eta [-]: as written in its material table, else its named
    material file's, else ``WOVEN_LOSS`` or ``GENERIC_LOSS``; a value not written in the scene
    is listed as an assumption with its range. A scene that declares [damping] uses no loss
    factor, so none is assumed."""
    own = sf.links.get(link)
    field = f"links.{link}.material" if own is not None and own.material else "material"
    m = own.material if own is not None and own.material else sf.material
    if m is None or m.loss_factor is not None:
        return 0.0 if m is None else m.loss_factor
    if sf.damping is not None:
        return 0.0
    try:
        named = load_constituent(m.isotropic).loss if m.isotropic is not None else None
    except InputError as exc:
        raise InputError(str(exc), source=src.file_of(field), field=field) from None
    default = named or (WOVEN_LOSS if m.composite is not None else GENERIC_LOSS)
    where = "the material file" if named else "default"
    assumptions.append(Assumption(
        f"{field}.loss_factor", f"{default.value:g}",
        f"assumed ({where}): material loss factor {default.value:g}, plausible "
        f"{default.low:g} to {default.high:g} ({default.source}); loss_factor is not given",
        src.file_of(field)))  # no sampled range: frequencies do not depend on it
    return default.value


def link_material(src: SceneSource, sf: schema.SceneFile, link: str) -> LinkMaterial:
    """Where ``link``'s material comes from (``contract.LinkMaterial``)."""
    own = sf.links.get(link)
    field = f"links.{link}.material" if own is not None and own.material else "material"
    m = own.material if own is not None and own.material else sf.material
    keys, _ = merged_section(sf, link)
    c = m.composite if m is not None else None
    return LinkMaterial(
        field=field, source=src.file_of(field), isotropic=m.isotropic if m is not None else None,
        composite=None if c is None else Composite(c.fiber, c.matrix, c.fiber_volume_fraction,
                                                   c.shear_modulus),
        plies=keys.get("plies"))


def merged_section(sf: schema.SceneFile, link: str) -> tuple[dict, dict[str, str]]:
    """The section keys of ``link``: its own [links.<link>.section] keys over the shared
    [section] ones, key by key; and the dotted field each key came from."""
    shared = sf.section.model_dump(exclude_none=True) if sf.section else {}
    own_table = sf.links.get(link).section if link in sf.links else None
    own = own_table.model_dump(exclude_none=True) if own_table else {}
    fields = {k: f"section.{k}" for k in shared}
    fields.update({k: f"links.{link}.section.{k}" for k in own})
    return {**shared, **own}, fields


def section(src: SceneSource, sf: schema.SceneFile, link: str, mat: BeamMaterial,
            length: float | None) -> Section:
    """A link's Section from its merged section keys (see ``schema.SectionTable`` for the forms)."""
    keys, fields = merged_section(sf, link)
    where = fields.get(next(iter(keys), ""), "section")
    label = f"{link}: {mat.name}"
    args = (mat.E, mat.G, mat.density)
    beam = sf.model.beam

    def need_length(key):
        if length is None:
            raise InputError(f"a section from {key} needs a link between two joints of one body",
                             source=src.file_of(fields[key]), field=fields[key])
        return length

    if "area" in keys or "second_moment" in keys:
        if not {"area", "second_moment"} <= set(keys):
            raise InputError("give area and second_moment together", source=src.file_of(where),
                             field=where)
        area, second = keys["area"], keys["second_moment"]
        # depth of the rectangle with this A and I: only used for slenderness messages
        return Section(*args, area, second, math.sqrt(12 * second / area),
                       name=f"{label}, A {area:.4g} m^2", beam=beam)
    if "tube_inner_radius" in keys:
        inner = keys["tube_inner_radius"]
        if "tube_outer_radius" in keys:
            outer = keys["tube_outer_radius"]
        elif "mass" in keys:  # the wall from the link's mass: m = rho pi (ro^2 - ri^2) l
            outer = math.sqrt(inner**2 + keys["mass"] / (mat.density * math.pi * need_length("mass")))
        else:
            raise InputError("a tube needs tube_outer_radius or mass", source=src.file_of(where),
                             field=where)
        return dataclasses.replace(Section.tube(
            *args, outer, inner, name=f"{label}, tube {2e3 * outer:.3f} x {1e3 * (outer - inner):.3f} mm"),
            beam=beam, shear_factor=tube_shear_factor(outer, inner))
    if "width" not in keys:
        raise InputError("no section given", source=src.file_of(where), field=f"links.{link}.section",
                         expected="width with thickness (or plies and ply_thickness, or mass), "
                                  "area with second_moment, or a tube")
    width = keys["width"]
    if "thickness" in keys:
        thickness = keys["thickness"]
    elif "plies" in keys and "ply_thickness" in keys:
        thickness = keys["plies"] * keys["ply_thickness"]
    elif "mass" in keys:  # out-of-plane thickness from the link's mass: m = rho width thickness l
        thickness = keys["mass"] / (mat.density * width * need_length("mass"))
    else:
        raise InputError("a flat bar needs thickness, plies with ply_thickness, or mass",
                         source=src.file_of(fields["width"]), field=fields["width"])
    if "bending" not in keys:  # I differs by (width / thickness)^2 between the two: no default
        raise InputError("missing", source=src.file_of(fields["width"]),
                         field=fields["width"].removesuffix("width") + "bending",
                         expected="bending = 'flatwise' (thickness in the plane of motion) or "
                                  "'edgewise' (width in the plane) for a flat bar")
    bending = keys["bending"]
    return Section.rectangle(*args, width, thickness, bending=bending, beam=beam,
                             name=f"{label}, {width * 1e3:g} x {thickness * 1e3:.4g} mm {bending}")


def joints(src: SceneSource, sf: schema.SceneFile, names: list[str], ground: set[str],
           welded_allowed: bool = True) -> tuple[JointSpec, ...]:
    """JointSpecs for ``names``: each joint's own [joints.<name>] values over the shared ones."""
    table = sf.joints or schema.JointsTable()
    own = dict(table.__pydantic_extra__ or {})
    for name in own:
        if name not in names:
            raise unknown_name(src, f"joints.{name}", "joint", name, names)
    out = []
    for name in names:
        mine = own.get(name, schema.JointTable())
        values = {}
        for key in ("Kt", "Kr"):
            value = getattr(mine, key) if getattr(mine, key) is not None else getattr(table, key)
            if value is None:
                raise InputError("missing", source=src.file_of("joints"), field=f"joints.{key}",
                                 expected="a stiffness for every bearing and pin, e.g. "
                                          "Kt = '1e6 N/m', Kr = '0 N*m/rad' (or 'rigid')")
            values[key] = value
        if mine.welded and not welded_allowed:
            raise InputError("welded joints are for general scenes", field=f"joints.{name}.welded",
                             source=src.file_of(f"joints.{name}.welded"))
        out.append(JointSpec(name, name in ground, values["Kt"], values["Kr"],
                             mine.mass or 0.0, mine.welded))
    return tuple(out)


def tilt(sf: schema.SceneFile, names: list[str]) -> dict[str, float]:
    """Ktilt [N m/rad] per joint; absent means rigid (stated as an assumption by the
    out-of-plane families, which alone use it)."""
    table = sf.joints or schema.JointsTable()
    own = table.__pydantic_extra__ or {}
    out = {}
    for name in names:
        mine = own.get(name)
        value = mine.Ktilt if mine is not None and mine.Ktilt is not None else table.Ktilt
        out[name] = math.inf if value is None else value
    return out


def drive(src: SceneSource, sf: schema.SceneFile, link_ends: dict[str, tuple[str, str]],
          ground: set[str]) -> DriveSpec | None:
    if sf.drive is None:
        return None
    d = sf.drive
    if d.link not in link_ends:
        raise unknown_name(src, "drive.link", "link", d.link, link_ends)
    if d.joint not in link_ends[d.link] or d.joint not in ground:
        ends = [j for j in link_ends[d.link] if j in ground]
        raise InputError(f"{d.joint!r} is not a ground joint of link {d.link!r}",
                         source=src.file_of("drive.joint"), field="drive.joint",
                         expected=" or ".join(repr(j) for j in ends) or "a link with a ground end")
    return DriveSpec(link=d.link, joint=d.joint, stiffness=d.stiffness)


def reference(sf: schema.SceneFile) -> Reference | None:
    if sf.reference is None:
        return None
    columns = {key[:-3]: tuple(float(v) for v in values)
               for key, values in (sf.reference.__pydantic_extra__ or {}).items()}
    return Reference(source=sf.reference.source, columns=columns)


def default_assumptions(src: SceneSource, sf: schema.SceneFile,
                        joint_names: list[str]) -> list[Assumption]:
    """Defaults that are modelling choices, listed like written assumptions: a rigid tilt
    stiffness where an out-of-plane family needs one and the scene gives none."""
    table = sf.joints or schema.JointsTable()
    own = table.__pydantic_extra__ or {}
    untilted = [j for j in joint_names
                if table.Ktilt is None and (j not in own or own[j].Ktilt is None)]
    if sf.model.family is ModelFamily.PLANAR or not untilted:
        return []
    return [Assumption("joints.Ktilt", "rigid", "assumed (default): joints " + ", ".join(untilted)
                       + " hold both out-of-plane bending moments (Ktilt rigid); Ktilt is not "
                       "given", src.file_of("model.family"))]


def options(src: SceneSource, sf: schema.SceneFile, joint_names: list[str]) -> Options:
    prb = None
    if sf.prb is not None:
        p = sf.prb
        prb = PrbOptions(p.strip, p.pivot, p.link, p.clamp, p.gamma, p.K_theta)
    variants = tuple(Variant(v.name or v.field, v.field, tuple(v.values)) for v in sf.family)
    return Options(family=sf.model.family, crank_speed=sf.operation.crank_speed,
                   crank_acceleration=sf.operation.crank_acceleration,
                   plausibility=sf.checks.plausibility, prb=prb, variants=variants,
                   tilt=tilt(sf, joint_names), damping=modal_damping(sf.damping),
                   test=ModalTestFrame(sf.test.unit, tuple(sf.test.offset), sf.test.rotation,
                                  sf.test.max_distance))


def modal_damping(table: schema.DampingTable | None) -> ModalDamping | None:
    if table is None:
        return None
    if table.ratio is not None or table.ratios is not None:
        return ModalDamping(ratios=(table.ratio,) if table.ratio is not None else tuple(table.ratios))
    return ModalDamping(alpha=table.rayleigh_alpha or 0.0, beta=table.rayleigh_beta or 0.0)


def unique(assumptions) -> tuple[Assumption, ...]:
    """Each (field, value) once, first occurrence kept."""
    return tuple({(a.field, a.value): a for a in assumptions}.values())


def composite(sf: schema.SceneFile) -> Composite | None:
    c = sf.material.composite if sf.material is not None else None
    return None if c is None else Composite(c.fiber, c.matrix, c.fiber_volume_fraction,
                                            c.shear_modulus)
