"""Scene files: a linkage, its pose, materials, sections, joints and reference data (TOML).

Every dimensional value carries its unit (``"300 mm"``, see ``units.py``). Any value may be
written as ``{ value = "...", note = "..." }``; notes starting with "assumed" are collected as
the scene's assumptions and reported with every result. ``base = "file.toml"`` merges a shared
file underneath the scene (the scene's own keys win), so shared defaults live in one place.
Files whose name starts with "_" are bases, never scenes on their own.
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
from pathlib import Path

from flexlink.errors import InputError
from flexlink.kinematics.fourbar import BRANCHES, FourBar
from flexlink.materials.mixtures import BeamMaterial, isotropic, load_constituent, woven_composite
from flexlink.fe.model import DriveSpec, JointSpec, LinkSpec, Section, Topology
from flexlink.scene.plausibility import check_scene
from flexlink.units import parse_quantity

FOUR_BAR_LINKS = (("crank", "O2", "A"), ("coupler", "A", "B"), ("rocker", "O4", "B"))
FOUR_BAR_JOINTS = (("O2", True), ("A", False), ("B", False), ("O4", True))


@dataclasses.dataclass(frozen=True)
class Assumption:
    field: str
    value: str
    note: str
    source: str


@dataclasses.dataclass(frozen=True)
class Reference:
    """Published/measured frequencies [Hz] to compare with, by mode order."""

    source: str
    columns: dict[str, tuple[float, ...]]  # e.g. {"Ex": (...), "FE": (...)}


@dataclasses.dataclass(frozen=True)
class PoseSpec:
    transmission_angle: float | None  # [rad]
    crank_angle: float | None  # [rad]
    branch: str


@dataclasses.dataclass(frozen=True)
class Scene:
    name: str
    path: str
    linkage: FourBar
    pose: PoseSpec
    sections: dict[str, Section]
    joints: tuple[JointSpec, ...]
    drive: DriveSpec | None
    elements_per_link: int
    reference: Reference | None
    assumptions: tuple[Assumption, ...]
    data: dict = dataclasses.field(default_factory=dict, repr=False, compare=False)
    origin: dict = dataclasses.field(default_factory=dict, repr=False, compare=False)

    def reader(self) -> "SceneReader":
        """Typed, error-naming access to tables this module does not interpret itself (e.g. a
        later stage's own options), so new stages need no change here."""
        return SceneReader(self.data, self.origin, Path(self.path))

    def topology(self, elements_per_link: int | None = None) -> Topology:
        n = elements_per_link or self.elements_per_link
        links = tuple(LinkSpec(name, a, b, self.sections[name], n) for name, a, b in FOUR_BAR_LINKS)
        return Topology(links=links, joints=self.joints, drive=self.drive)

    def rigid_pose(self):
        if self.pose.crank_angle is not None:
            return self.linkage.pose(self.pose.crank_angle, self.pose.branch)
        return self.linkage.pose_at_mu(self.pose.transmission_angle, self.pose.branch)


# -- reading ---------------------------------------------------------------------------------
def _read_toml(path: Path) -> dict:
    try:
        with path.open("rb") as fh:
            return tomllib.load(fh)
    except FileNotFoundError:
        raise InputError("file not found", source=str(path)) from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"not valid TOML: {exc}", source=str(path)) from None


REPLACED_WHOLE = {"material"}  # a scene's own material table replaces its base's, never mixes


def _merge(base: dict, top: dict) -> dict:
    """Deep-merge ``top`` over ``base``; the scene's own keys win."""
    out = dict(base)
    for key, value in top.items():
        if (isinstance(value, dict) and "value" not in value and isinstance(out.get(key), dict)
                and key not in REPLACED_WHOLE):
            out[key] = _merge(out[key], value)
        else:
            out[key] = value
    return out


def _flatten_origin(data: dict, file: str, prefix="") -> dict:
    out = {}
    for key, value in data.items():
        dotted = f"{prefix}{key}"
        if isinstance(value, dict) and "value" not in value:
            out.update(_flatten_origin(value, file, dotted + "."))
        else:
            out[dotted] = file
    return out


def _load_with_base(path: Path, depth=0) -> tuple[dict, dict]:
    if depth > 5:
        raise InputError("base files nest too deeply (a loop?)", source=str(path), field="base")
    data = _read_toml(path)
    origin = _flatten_origin(data, str(path))
    base_name = data.pop("base", None)
    origin.pop("base", None)
    if base_name is None:
        return data, origin
    if not isinstance(base_name, str):
        raise InputError("must be a file name", source=str(path), field="base",
                         expected="a path relative to this file, e.g. '_table2.toml'")
    base_data, base_origin = _load_with_base(path.parent / base_name, depth + 1)
    return _merge(base_data, data), {**base_origin, **origin}


class SceneReader:
    """Typed access to the merged scene data; every error names the file and the field."""

    def __init__(self, data: dict, origin: dict, path: Path):
        self.data, self.origin, self.path = data, origin, path
        self.assumptions: list[Assumption] = []

    def src(self, field):
        return self.origin.get(field, str(self.path))

    def raw(self, field, default=...):
        node = self.data
        for part in field.split("."):
            if not isinstance(node, dict) or part not in node:
                if default is ...:
                    raise InputError("missing", source=self.src(field), field=field)
                return default
            node = node[part]
        if isinstance(node, dict) and "value" in node:
            note = str(node.get("note", ""))
            value = node["value"]
            if note.lower().startswith("assumed"):
                self.assumptions.append(Assumption(field, str(value), note, self.src(field)))
            return value
        return node

    def has(self, field):
        return self.raw(field, None) is not None

    def quantity(self, field, dimension, default=..., positive=True, allow_zero=False):
        value = self.raw(field, default)
        if value is None:
            return None
        if value is default and not isinstance(value, str):
            return value
        q = parse_quantity(value, dimension, source=self.src(field), field=field)
        if positive and (q < 0 or (q == 0 and not allow_zero) or math.isnan(q)):
            raise InputError(f"must be {'>= 0' if allow_zero else '> 0'}, got {value!r}",
                             source=self.src(field), field=field, expected=f"a positive {dimension}")
        return q

    def number(self, field, low, high, default=..., integer=False):
        value = self.raw(field, default)
        if value is None:
            return None
        ok = isinstance(value, (int, float)) and not isinstance(value, bool)
        if integer:
            ok = ok and float(value).is_integer()
        if not ok or not (low <= value <= high):
            kind = "a whole number" if integer else "a plain number (no unit)"
            raise InputError(f"got {value!r}", source=self.src(field), field=field,
                             expected=f"{kind} in [{low}, {high}]")
        return int(value) if integer else float(value)


def _material(r: SceneReader, link: str) -> BeamMaterial:
    """A link's own [links.<link>.material] table replaces the shared [material] whole."""
    prefix = f"links.{link}.material" if r.has(f"links.{link}.material") else "material"
    if r.has(f"{prefix}.composite"):
        c = f"{prefix}.composite"
        fiber = load_constituent(r.raw(f"{c}.fiber"))
        matrix = load_constituent(r.raw(f"{c}.matrix"))
        vf = r.number(f"{c}.fiber_volume_fraction", 0.0, 1.0)
        return woven_composite(fiber, matrix, vf)
    if r.has(f"{prefix}.isotropic"):
        return isotropic(load_constituent(r.raw(f"{prefix}.isotropic")))
    if r.has(f"{prefix}.E"):
        E = r.quantity(f"{prefix}.E", "modulus")
        density = r.quantity(f"{prefix}.density", "density")
        G = r.quantity(f"{prefix}.G", "modulus", default=None) or E / 2.6
        return BeamMaterial(name=prefix, E=E, G=G, density=density)
    raise InputError("no material given", source=r.src(prefix), field=prefix,
                     expected="a 'composite' table, 'isotropic = \"name\"', or E and density")


def _section(r: SceneReader, link: str, material: BeamMaterial) -> Section:
    """Each section key may be overridden per link in [links.<link>.section]."""
    def field(key):
        own = f"links.{link}.section.{key}"
        return own if r.has(own) else f"section.{key}"

    width = r.quantity(field("width"), "length")
    if r.has(field("thickness")):
        thickness = r.quantity(field("thickness"), "length")
    else:
        plies = r.number(field("plies"), 1, 1000, integer=True)
        thickness = plies * r.quantity(field("ply_thickness"), "length")
    return Section.rectangle(material.E, material.G, material.density, width, thickness,
                             name=f"{link}: {material.name}, {width * 1e3:g} x {thickness * 1e3:g} mm")


def _set_dotted(data: dict, origin: dict, field: str, value):
    node = data
    parts = field.split(".")
    for part in parts[:-1]:
        node = node.setdefault(part, {})
        if not isinstance(node, dict):
            raise InputError("cannot override inside a plain value", source="overrides", field=field)
    node[parts[-1]] = value
    origin[field] = "overrides"


def joint_inputs(r: SceneReader, joint: str) -> tuple[float, float, float]:
    """(Kt [N/m], Kr [N m/rad], mass [kg]) of ``joint``: its own [joints.<joint>] value where
    given, else the shared [joints] one; mass defaults to 0."""
    def stiff(key, dim):
        specific = f"joints.{joint}.{key}"
        field = specific if r.has(specific) else f"joints.{key}"
        return r.quantity(field, dim, positive=True, allow_zero=True)

    mass = (r.quantity(f"joints.{joint}.mass", "mass", allow_zero=True)
            if r.has(f"joints.{joint}.mass") else 0.0)
    return stiff("Kt", "translational stiffness"), stiff("Kr", "rotational stiffness"), mass


def load_scene(path: str | Path, overrides: dict | None = None):
    """Read and validate a scene file (and its base): a ``Scene`` for a four-bar, a
    ``scene_general.GeneralScene`` for ``linkage.type = "general"``. Raises InputError naming
    file and field.

    ``overrides`` maps dotted fields to values as they would be written in the file, e.g.
    ``{"section.width": "25 mm", "joints.Kt": "1e7 N/m"}``: sweeps, calibration and Monte Carlo
    vary inputs this way, through the same validation as a file."""
    path = Path(path)
    data, origin = _load_with_base(path)
    for field, value in (overrides or {}).items():
        _set_dotted(data, origin, field, value)
    r = SceneReader(data, origin, path)
    name = r.raw("name", path.stem)

    kind = r.raw("linkage.type", "four-bar")
    if kind == "general":
        from flexlink.scene.general import load_general  # any linkage as data; see that module
        return load_general(r, path)
    if kind != "four-bar":
        raise InputError(f"unknown linkage type {kind!r}", source=r.src("linkage.type"),
                         field="linkage.type", expected="'four-bar' or 'general'")
    if r.has("linkage.R2"):
        ratios = [r.number(f"linkage.{k}", 1e-6, 1e6) for k in ("R2", "R3", "R4")]
        ground = r.quantity("linkage.ground", "length")
        linkage = FourBar.from_ratios(*ratios, ground=ground)
    else:
        linkage = FourBar(*(r.quantity(f"linkage.{k}", "length")
                            for k in ("ground", "crank", "coupler", "rocker")))

    branch = r.raw("pose.branch", "open")
    if branch not in BRANCHES:
        raise InputError(f"got {branch!r}", source=r.src("pose.branch"), field="pose.branch",
                         expected=" or ".join(repr(b) for b in BRANCHES))
    mu = r.quantity("pose.transmission_angle", "angle", default=None)
    theta2 = r.quantity("pose.crank_angle", "angle", default=None, positive=False)
    if (mu is None) == (theta2 is None):
        raise InputError("give exactly one of transmission_angle or crank_angle",
                         source=r.src("pose"), field="pose", expected="e.g. transmission_angle = '90 deg'")
    if mu is not None and not 0 < mu < math.pi:
        raise InputError(f"{math.degrees(mu):g} deg is outside (0, 180) deg",
                         source=r.src("pose.transmission_angle"), field="pose.transmission_angle")
    pose = PoseSpec(mu, theta2, branch)

    sections = {link: _section(r, link, _material(r, link)) for link, _, _ in FOUR_BAR_LINKS}

    joints = [JointSpec(joint, ground, *joint_inputs(r, joint)) for joint, ground in FOUR_BAR_JOINTS]

    drive = None
    if r.has("drive"):
        drive = DriveSpec(link=r.raw("drive.link"), joint=r.raw("drive.joint"),
                          stiffness=r.quantity("drive.stiffness", "rotational stiffness",
                                               allow_zero=True))
    elements = r.number("mesh.elements_per_link", 1, 100000, integer=True, default=16)

    reference = None
    if r.has("reference"):
        columns = {}
        for key, value in data["reference"].items():
            if key.endswith("_Hz"):
                if not (isinstance(value, list) and all(isinstance(v, (int, float)) and v > 0
                                                        for v in value)):
                    raise InputError(f"got {value!r}", source=r.src(f"reference.{key}"),
                                     field=f"reference.{key}",
                                     expected="a list of positive frequencies in Hz")
                columns[key[:-3]] = tuple(float(v) for v in value)
        reference = Reference(source=str(r.raw("reference.source", "")), columns=columns)

    scene = Scene(name=str(name), path=str(path), linkage=linkage, pose=pose, sections=sections,
                  joints=tuple(joints), drive=drive, elements_per_link=elements,
                  reference=reference, assumptions=tuple(_unique(r.assumptions)), data=data,
                  origin=origin)
    check_scene(scene)  # unit slips such as "300 m" for "300 mm" (plausibility.py)
    return scene


def _unique(items):
    seen, out = set(), []
    for a in items:
        key = (a.field, a.value)
        if key not in seen:
            seen.add(key)
            out.append(a)
    return out


def scene_files(paths) -> list[Path]:
    """Expand files and folders into scene files (folders: *.toml not starting with '_')."""
    out = []
    for p in map(Path, paths):
        if p.is_dir():
            found = sorted(f for f in p.glob("*.toml") if not f.name.startswith("_"))
            if not found:
                raise InputError("folder holds no scene files (*.toml)", source=str(p))
            out.extend(found)
        elif p.is_file():
            out.append(p)
        else:
            raise InputError("no such scene file or folder", source=str(p))
    return out
