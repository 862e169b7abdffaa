"""The declared scene schema: every table and key a scene file may hold, with unit kind, range,
default and a doc line. Nothing else reads scene tables, and a key not declared here is an error.

Both scene kinds share one root, ``SceneFile``; ``[linkage] type`` picks the kind:
"four-bar" (lengths or ratios, pose by transmission or crank angle) or "general" (any planar
linkage of revolute joints as data, or a four-bar given by lengths or synthesis).
Quantities are strings with units (``"20 mm"``, see ``units.py``) and come out in SI; stiffness
may be ``"rigid"`` (infinite: an exact constraint). Notes (``{ value = ..., note = "..." }``) are
stripped before validation by ``source.py``, so every key below also accepts that form.

Docs and editor support are generated from these models (``reference.py``).
"""

from __future__ import annotations

import dataclasses
import enum
import math
import typing
from typing import Annotated, Literal

from pydantic import (AfterValidator, BaseModel, BeforeValidator, ConfigDict, Field, StrictBool,
                      WithJsonSchema, model_validator)

from flexlink.errors import InputError
from flexlink.fe.beams import BeamTheory
from flexlink.fe.model import Bending
from flexlink.fe.motions import ModelFamily
from flexlink.kinematics import Branch
from flexlink.kinematics.kinetostatics import Sharing
from flexlink.materials.mixtures import ShearSource
from flexlink.scene.contract import LoadFrame, LoadKind, Plausibility, SceneKind
from flexlink.units import UNITS, parse_quantity, quantity_pattern


@dataclasses.dataclass(frozen=True)
class Unit:
    """Field metadata for the docs: the unit kind (a key of ``units.UNITS``, or "-" for a plain
    number) and the accepted range as a person would write it."""

    kind: str
    range: str = ""
    low: float | None = None  # the range's bounds in SI (None: unbounded), for generated tests
    high: float | None = None
    low_open: bool = True
    high_open: bool = True


def _check_range(value: float, low, high, low_open, high_open, shown):
    ok = ((low is None or (value > low if low_open else value >= low))
          and (high is None or (value < high if high_open else value <= high)))
    if not ok:
        raise ValueError(f"must be {'in ' if shown[:1] in '([' else ''}{shown}")
    return value


def quantity(kind: str, low: float | None = None, high: float | None = None, *,
             low_open: bool = True, high_open: bool = True, shown: str = "",
             rigid: bool = False):
    """A string with a unit of ``kind``, converted to SI [kind's SI unit]; range in SI."""
    def parse(value):
        if rigid and isinstance(value, str) and value.strip().lower() == "rigid":
            return math.inf
        try:
            return parse_quantity(value, kind)
        except InputError as exc:
            raise ValueError(str(exc)) from None

    def check(value):
        if math.isinf(value):
            return value
        return _check_range(value, low, high, low_open, high_open, shown)

    pattern = quantity_pattern(kind, signed=low is None or low < 0,
                               positive=low == 0 and low_open, words=("rigid",) if rigid else ())
    return Annotated[float, BeforeValidator(parse), AfterValidator(check),
                     WithJsonSchema({"type": "string", "pattern": pattern}),
                     Unit(kind, shown + (" or 'rigid'" if rigid else ""), low, high, low_open,
                          high_open)]


def number(low: float, high: float, *, integer: bool = False, low_open: bool = False,
           high_open: bool = False):
    """A plain number (no unit) in [low, high]; ``integer`` for whole numbers."""
    lb, hb = "(" if low_open else "[", ")" if high_open else "]"
    shown = f"{lb}{low:g}, {high:g}{hb}"

    def parse(value):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            hint = " (a plain number, no unit)" if isinstance(value, str) else ""
            raise ValueError(f"got {value!r}{hint}; expected a {'whole ' if integer else ''}"
                             f"number in {shown}")
        if not math.isfinite(value):
            raise ValueError(f"got {value!r}; expected a finite number in {shown}")
        if integer and not float(value).is_integer():
            raise ValueError(f"got {value!r}; expected a whole number in {shown}")
        return _check_range(value, low, high, low_open, high_open, shown)

    schema = {"type": "integer" if integer else "number"}
    schema.update({"exclusiveMinimum" if low_open else "minimum": low,
                   "exclusiveMaximum" if high_open else "maximum": high})
    return Annotated[int if integer else float, BeforeValidator(parse), WithJsonSchema(schema),
                     Unit("-", shown, low, high, low_open, high_open)]


LENGTH = quantity("length", 0.0, shown="> 0")
ANGLE = quantity("angle", shown="any")
OPEN_ANGLE = quantity("angle", 0.0, math.pi, shown="(0, 180) deg")
MODULUS = quantity("modulus", 0.0, shown="> 0")
DENSITY = quantity("density", 0.0, shown="> 0")
TRANSLATIONAL = quantity("translational stiffness", 0.0, low_open=False, shown=">= 0", rigid=True)
ROTATIONAL = quantity("rotational stiffness", 0.0, low_open=False, shown=">= 0", rigid=True)
JOINT_MASS = quantity("mass", 0.0, low_open=False, shown=">= 0")
POSITIVE_MASS = quantity("mass", 0.0, shown="> 0")


def choice(kind: type[enum.StrEnum]):
    """One of the words of ``kind`` (a StrEnum), read as its member: checked as a Literal of
    the words, so the message for another word lists them and the JSON Schema holds them in
    place (where an editor also takes the value's noted form), then turned into the member."""
    return Annotated[Literal[tuple(member.value for member in kind)], AfterValidator(kind)]


Point = Annotated[tuple[quantity("length", shown="any"), quantity("length", shown="any")],
                  Unit("length", "[x, y]")]


class MissingKey(ValueError):
    """A key a table needs (given what else it holds) is absent; ``key`` names it."""

    def __init__(self, key: str, hint: str = ""):
        self.key, self.hint = key, hint
        super().__init__(f"{key}: missing" + (f" ({hint})" if hint else ""))


class ClashingKey(ValueError):
    """A key given together with another that excludes it; ``key`` names it, ``reason`` why."""

    def __init__(self, key: str, reason: str):
        self.key, self.reason = key, reason
        super().__init__(f"{key}: {reason}")


class UnknownKey(ValueError):
    """A key a table with free-named keys cannot take; ``key`` names it, ``known`` the declared
    keys nearest to it are chosen from."""

    def __init__(self, key: str, known: list[str], hint: str = ""):
        self.key, self.known, self.hint = key, known, hint
        super().__init__(f"{key}: unknown key" + (f" ({hint})" if hint else ""))


class Table(BaseModel):
    """A scene table: unknown keys are errors, values are immutable once read."""

    model_config = ConfigDict(extra="forbid", frozen=True)


def extra_type(model: type[BaseModel]):
    """The value type of a table's free-named keys ([joints.NAME], reference columns), or None
    for a table whose keys are all declared."""
    hint = typing.get_type_hints(model, include_extras=True).get("__pydantic_extra__")
    return typing.get_args(hint)[1] if hint is not None else None


def doc(text: str, *, needed: str = "", **kwargs):
    """A field's doc line; ``needed`` says where a key the schema cannot require is required
    (e.g. in [joints] or in every [joints.NAME]), shown in the reference's default column."""
    extra = {"needed": needed} if needed else None
    return Field(description=text, json_schema_extra=extra, **kwargs)


# -- materials and sections ------------------------------------------------------------------
class CompositeTable(Table):
    fiber: str = doc("Fibre constituent: a name from the shipped materials (e.g. 'carbon_fiber') "
                     "or a path to a material .toml file.")
    matrix: str = doc("Matrix constituent: a shipped name (e.g. 'polyester') or a path.")
    fiber_volume_fraction: number(0.0, 1.0, low_open=True, high_open=True) = doc(
        "Fibre volume fraction Vf of the woven 0/90 laminate (rule of mixtures).")
    shear_modulus: choice(ShearSource) = doc(
        "Constituent shear moduli for the laminate's G (used by Timoshenko links and torsion): "
        "'printed' takes each constituent file's G; 'isotropic' takes E / 2 (1 + nu) of each "
        "(Table I's printed G conflicts with its E and nu).", default=ShearSource.PRINTED)


class MaterialTable(Table):
    """One of: a woven composite, a shipped isotropic material, or E and density."""

    composite: CompositeTable | None = doc("Woven 0/90 laminate from fibre and matrix constituents.",
                                      default=None)
    isotropic: str | None = doc("A shipped isotropic material by name (e.g. 'steel') or a path.",
                                default=None)
    E: MODULUS | None = doc("Young's modulus of an isotropic material.", default=None)
    G: MODULUS | None = doc("Shear modulus; if not given, E / 2.6 (nu = 0.3) is used and listed "
                            "as an assumption.", default=None)
    density: DENSITY | None = doc("Density (with E).", default=None)
    loss_factor: number(0.0, 1.0, high_open=True) | None = doc(
        "Material loss factor eta (dimensionless): the fraction 2 pi of the strain energy lost "
        "per cycle, giving each mode's damping ratio by strain-energy weighting. If not given, "
        "the material file's value, else 0.01 for a woven composite (carbon/epoxy laminates "
        "2e-3 to 1e-2, a polyester matrix higher) or 1e-3 for E and density (structural "
        "metals 1e-4 to 1e-3; Ashby, Materials Selection in Mechanical Design, loss-coefficient "
        "chart), listed as an assumption.", default=None)

    @model_validator(mode="after")
    def _one_kind(self):
        given = [k for k in ("composite", "isotropic", "E") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of: a [composite] table, isotropic = 'name', "
                             f"or E and density (got {given or 'none'})")
        if self.E is not None and self.density is None:
            raise MissingKey("density", "an isotropic material needs E and density")
        if self.E is None and (self.G is not None or self.density is not None):
            raise ValueError("G and density go with E, not with a composite or named material")
        return self


class SectionTable(Table):
    """A link's cross-section, in one of four forms: width with thickness (or plies times
    ply_thickness, or the link's mass); area with second_moment; a round tube."""

    width: LENGTH | None = doc("Width of a flat bar (the in-plane depth when bending is "
                               "'edgewise').", default=None)
    bending: choice(Bending) | None = doc(
        "How a flat bar lies: 'edgewise' puts the width in the mechanism plane (in-plane "
        "bending uses I = thickness width^3 / 12, the stiff way); 'flatwise' puts the "
        "thickness in the plane (I = width thickness^3 / 12, the flexible way, as in most "
        "flexible-link rigs). Required with width: the two differ by (width / thickness)^2 "
        "in stiffness (16 times for a 12 x 3 mm strip), and real links lie both ways (the "
        "Table II strips flatwise, the wiper's bars edgewise), so no default is safe.",
        default=None)
    thickness: LENGTH | None = doc("Out-of-plane thickness of a flat bar.", default=None)
    plies: number(1, 1000, integer=True) | None = doc(
        "Number of plies; thickness = plies x ply_thickness.", default=None)
    ply_thickness: LENGTH | None = doc("Cured thickness of one ply.", default=None)
    area: quantity("area", 0.0, shown="> 0") | None = doc(
        "Cross-section area (with second_moment).", default=None)
    second_moment: quantity("second moment", 0.0, shown="> 0") | None = doc(
        "Second moment of area for in-plane bending (with area).", default=None)
    tube_inner_radius: quantity("length", 0.0, low_open=False, shown=">= 0") | None = doc(
        "Inner radius of a round tube.", default=None)
    tube_outer_radius: LENGTH | None = doc("Outer radius of a round tube.", default=None)
    mass: POSITIVE_MASS | None = doc("Mass of the link: sets the thickness of a flat bar or the "
                                     "wall of a tube from the link's length.", default=None)


class LinkTable(Table):
    """A beam link: the elastic part the finite elements mesh, between two joints. Four-bar
    scenes name crank, coupler, rocker (their ends are fixed) and may only override section
    and material. In general scenes [linkage.bodies] are the rigid kinematics and [links] the
    beams laid over them: each link joins two joints of one body (start and end), a bar is
    usually one link, and a body of three joints is two or more links meeting at a joint
    (welded there when it is a ground joint; see [joints.NAME] welded). A body without links
    moves the others but has no elasticity or mass of its own."""

    start: str | None = doc("Joint at the link's start (general scenes).", default=None)
    end: str | None = doc("Joint at the link's end (general scenes).", default=None)
    section: SectionTable | None = doc("Section keys overriding the shared [section] key by key.",
                                  default=None)
    material: MaterialTable | None = doc("Material replacing the shared [material] whole.",
                                    default=None)
    elements: number(1, 100000, integer=True) | None = doc(
        "Elements of this link (general scenes; default: [mesh] elements_per_link).",
        default=None)


# -- joints and drive ------------------------------------------------------------------------
class JointTable(Table):
    """One joint's own values, overriding the shared [joints] ones."""

    Kt: TRANSLATIONAL | None = doc("Translational stiffness of the bearing or pin, in x and y.",
                                   default=None)
    Kr: ROTATIONAL | None = doc("Torsional stiffness of the bearing or pin (0: turns freely).",
                                default=None)
    Ktilt: ROTATIONAL | None = doc("Tilt stiffness about the in-plane axes (out-of-plane model "
                                   "families only).", default=None)
    mass: JOINT_MASS | None = doc("Lumped mass of the pin or bearing, on the joint's node.",
                                  default=None)
    welded: StrictBool = doc(
        "Ground joint only: the beams meeting here are welded to each other and turn together "
        "in one bearing. Needed where one body is meshed as two or more beams meeting at its "
        "ground joint (a triangular rocker of two arms): without it each beam turns freely on "
        "the pin and the body is a mechanism. Beams of one body meeting at a moving joint are "
        "joined by Kt = Kr = 'rigid' there instead.", default=False)


class JointsTable(Table):
    """Shared bearing and pin values; [joints.NAME] tables override them per joint."""

    model_config = ConfigDict(extra="allow", frozen=True)
    __pydantic_extra__: dict[str, JointTable]

    Kt: TRANSLATIONAL | None = doc(
        "Translational stiffness of every bearing and pin, in x and y ('rigid': no clearance).",
        default=None,
        needed="here or in every [joints.NAME]")
    Kr: ROTATIONAL | None = doc(
        "Torsional stiffness of every bearing and pin ('0 N*m/rad': pins turn freely).",
        default=None,
        needed="here or in every [joints.NAME]")
    Ktilt: ROTATIONAL | None = doc("Tilt stiffness of every joint (out-of-plane families; "
                                   "default rigid, listed as an assumption where used).",
                                   default=None)


class DriveTable(Table):
    """The drive: a torsional spring between the input link and ground at its ground joint
    (in parallel with that bearing's Kr), for a motor and its coupling; 'rigid' holds the
    input angle exactly. Without [drive] the input link turns freely: the linkage keeps one
    degree of freedom, reported as a mechanism mode near 0 Hz apart from the elastic modes,
    which are then those of a free-running linkage (rarely what a test rig measures)."""

    link: str = doc("The driven link (e.g. 'crank').")
    joint: str = doc("The ground joint where the drive holds it (e.g. 'O2').")
    stiffness: ROTATIONAL = doc("Torsional stiffness of the drive, in parallel with the "
                                "bearing's Kr; 'rigid' holds the crank angle exactly.")


# -- linkage ---------------------------------------------------------------------------------
class FourBarLinkage(Table):
    """A four-bar O2-A-B-O4: crank O2A, coupler AB, rocker O4B, ground O2O4. Give the ratios
    R2, R3, R4 with ground, or the four lengths."""

    type: Literal[SceneKind.FOUR_BAR] = doc("Scene kind.", default=SceneKind.FOUR_BAR)
    R2: number(1e-6, 1e6) | None = doc("Crank / ground length ratio L2/L1.", default=None)
    R3: number(1e-6, 1e6) | None = doc("Coupler / ground length ratio L3/L1.", default=None)
    R4: number(1e-6, 1e6) | None = doc("Rocker / ground length ratio L4/L1.", default=None)
    ground: LENGTH = doc("Ground link length L1 (O2 to O4).")
    crank: LENGTH | None = doc("Crank length L2 (without ratios).", default=None)
    coupler: LENGTH | None = doc("Coupler length L3 (without ratios).", default=None)
    rocker: LENGTH | None = doc("Rocker length L4 (without ratios).", default=None)

    @model_validator(mode="after")
    def _ratios_or_lengths(self):
        ratios = {"R2": self.R2, "R3": self.R3, "R4": self.R4}
        lengths = {"crank": self.crank, "coupler": self.coupler, "rocker": self.rocker}
        given_ratios = any(v is not None for v in ratios.values())
        given_lengths = any(v is not None for v in lengths.values())
        if given_ratios and given_lengths:
            raise ValueError("give R2, R3 and R4 (with ground), or crank, coupler and rocker "
                             "lengths (with ground), not a mix")
        needed = lengths if given_lengths else ratios
        missing = [k for k, v in needed.items() if v is None]
        if missing:
            raise MissingKey(missing[0], "give R2, R3 and R4 with ground, or crank, coupler and "
                                         "rocker lengths with ground")
        return self


class FourBarLengths(Table):
    ground: LENGTH = doc("Ground O2O4.")
    crank: LENGTH = doc("Crank O2A.")
    coupler: LENGTH = doc("Coupler AB.")
    rocker: LENGTH = doc("Rocker O4B.")


class BrodellSoni(Table):
    method: Literal["brodell-soni"] = doc("Crank-rocker with unit time ratio and optimum "
                                          "transmission angle (Brodell and Soni).")
    gamma_min: quantity("angle", 0.0, math.pi / 2, high_open=False, shown="(0, 90] deg") = doc(
        "Least transmission angle.")
    swing: OPEN_ANGLE = doc("Rocker swing angle.")
    ground: LENGTH = doc("Ground link length.")


class Minimax(Table):
    method: Literal["minimax"] = doc("Mini-max transmission angle, mu = 90 +- delta.")
    theta4i: OPEN_ANGLE = doc("Rocker angle at mu_min.")
    delta: quantity("angle", 0.0, math.pi / 2, shown="(0, 90) deg") = doc(
        "Half-band of the transmission angle about 90 deg.")
    ground: LENGTH = doc("Ground link length.")


class ExtendedRocker(Table):
    method: Literal["extended-rocker"] = doc("Crank-rocker driven through an extended rocker.")
    rocker: LENGTH | None = doc(
        "Design rocker length L4 (without 'tip'): k then builds the rocker k L4 long, moving "
        "the coupler pin along it (a different mechanism for every k).", default=None)
    tip: LENGTH | None = doc(
        "Extended arm L41 from the rocker pivot to the tip that carries the load (instead of "
        "'rocker'): k = L41/L4 then sets the rocker L4 = L41/k and every link scales with it, "
        "so swing, time ratio and the angular motion are the same for every k.", default=None)
    swing: OPEN_ANGLE = doc("Rocker swing angle.")
    coupler_ratio: number(1.0, 1e3) = doc("Coupler / crank ratio L3/L2.")
    k: number(1e-3, 1e3, low_open=True) = doc(
        "Rocker ratio: with 'tip', L41/L4; with 'rocker', built / design rocker length.",
        default=1.0)

    @model_validator(mode="after")
    def _rocker_or_tip(self):
        if (self.rocker is None) == (self.tip is None):
            raise MissingKey("tip", "give tip (the paper's scaling) or rocker, exactly one")
        return self


Synthesis = Annotated[BrodellSoni | Minimax | ExtendedRocker, Field(discriminator="method")]


class BodyTable(Table):
    joints: list[str] = doc("Joints the body carries, at least two; the first two define its "
                            "axis (the first arm).", min_length=2)
    length: LENGTH | None = doc("Distance between the two joints of a bar.", default=None)
    arms: list[LENGTH] | None = doc("Distances from the first joint to each of the others, in "
                                    "order (bodies of three or more joints).", default=None)
    angles: list[ANGLE] | None = doc("Angle of each arm, counter-clockwise from the first arm, "
                                     "one per arm and the first arm included: so the list "
                                     "starts with '0 deg'.", default=None)

    @model_validator(mode="after")
    def _shape(self):
        if len(self.joints) == 2 and self.length is None:
            raise MissingKey("length", "a two-joint body needs the distance between its joints")
        if len(self.joints) > 2 and (self.arms is None or self.angles is None
                                     or len(self.arms) != len(self.joints) - 1
                                     or len(self.angles) != len(self.joints) - 1):
            raise ValueError(f"a body of {len(self.joints)} joints needs {len(self.joints) - 1} "
                             "arms and as many angles")
        return self


class PointTable(Table):
    on: str = doc("Body the point is fixed on.")
    along: str | None = doc("Body along whose axis the point is placed (default: 'on').",
                            default=None)
    at: number(-1e3, 1e3) = doc("Position as a multiple of the 'along' body's length from its "
                                "first joint, at the start pose.")


class GeneralLinkage(Table):
    """Any planar linkage of revolute joints with one input. Either a four-bar source
    ([linkage.four_bar] lengths or [linkage.synthesis]) or ground, bodies, guess and driver."""

    type: Literal[SceneKind.GENERAL] = doc("Scene kind.")
    four_bar: FourBarLengths | None = doc("A four-bar by its lengths.", default=None)
    synthesis: Synthesis | None = doc("A four-bar from a synthesis method.", default=None)
    branch: choice(Branch) = doc("Assembly branch of a four-bar source.", default=Branch.OPEN)
    ground: dict[str, Point] | None = doc(
        "Ground pivots by name, each [x, y] as two unit strings in the ground frame, e.g. "
        "O1 = ['0 mm', '0 mm']: these joints never move.", default=None)
    bodies: dict[str, BodyTable] | None = doc("Rigid bodies by name.", default=None)
    guess: dict[str, Point] | None = doc(
        "Rough positions of every moving joint at the start pose, each [x, y] as two unit "
        "strings in the ground frame, e.g. a = ['41 mm', '0 mm']: the loops are closed from "
        "there, so the guess picks the assembly (which side of a line each joint lies on); a "
        "sketch is close enough.", default=None)
    driver: str | None = doc("The input body (its first joint a ground pivot).", default=None)
    start: ANGLE = doc(
        "Input angle of the analysed pose: the direction of the driver's axis (its first joint "
        "to its second), counter-clockwise from the ground frame's +x axis. Four-bar sources: "
        "the crank angle from the ground line O2->O4.", default=0.0)
    start_transmission_angle: OPEN_ANGLE | None = doc(
        "Four-bar sources: start where the transmission angle has this value.", default=None)
    transmission: list[tuple[str, str]] = doc(
        "Body pairs whose angle at their shared joint is a transmission angle.", default=[])
    points: dict[str, PointTable] | None = doc("Extra joints fixed on a body.", default=None)

    @model_validator(mode="after")
    def _source(self):
        four_bar = self.four_bar is not None or self.synthesis is not None
        bodies = any(v is not None for v in (self.ground, self.bodies, self.driver, self.guess))
        if self.four_bar is not None and self.synthesis is not None:
            raise ValueError("give [linkage.four_bar] or [linkage.synthesis], not both")
        if four_bar == bodies:
            raise ValueError("give a four-bar source ([linkage.four_bar] or [linkage.synthesis]) "
                             "or ground, bodies, guess and driver")
        for key in ("ground", "bodies", "guess", "driver"):
            if bodies and getattr(self, key) is None:
                raise MissingKey(key, "a linkage of bodies needs ground, bodies, guess and driver")
        if self.start_transmission_angle is not None and not four_bar:
            raise ValueError("start_transmission_angle needs a four-bar source")
        return self


LinkageTable = Annotated[FourBarLinkage | GeneralLinkage, Field(discriminator="type")]


class PoseTable(Table):
    """The analysed pose of a four-bar: exactly one of transmission_angle or crank_angle."""

    transmission_angle: OPEN_ANGLE | None = doc("Transmission angle mu at B.", default=None)
    crank_angle: ANGLE | None = doc("Crank angle theta2 from the ground line O2->O4.",
                                    default=None)
    branch: choice(Branch) = doc("Assembly branch.", default=Branch.OPEN)

    @model_validator(mode="after")
    def _one(self):
        if self.transmission_angle is None and self.crank_angle is None:
            raise MissingKey("transmission_angle", "or crank_angle: give exactly one")
        if self.transmission_angle is not None and self.crank_angle is not None:
            raise ValueError("give exactly one of transmission_angle or crank_angle, not both")
        return self


# -- stage options ---------------------------------------------------------------------------
class MeshTable(Table):
    elements_per_link: number(1, 100000, integer=True) | None = doc(
        "Pins the mesh; without it commands pick the coarsest mesh meeting their frequency "
        "tolerance and say so.", default=None)


class ModelTable(Table):
    family: choice(ModelFamily) = doc(
        "Model family: the paper's in-plane frame, out-of-plane bending and torsion, or both.",
        default=ModelFamily.PLANAR)
    beam: choice(BeamTheory) = doc(
        "Beam theory of the in-plane links: Euler-Bernoulli (the paper's) or Timoshenko (shear "
        "strain with k = 5/6 for rectangles, and rotary inertia).",
        default=BeamTheory.EULER_BERNOULLI)


class ChecksTable(Table):
    plausibility: choice(Plausibility) = doc(
        "Values outside plausible ranges (unit slips such as '300 m'): refuse or only warn.",
        default=Plausibility.ERROR)


class OperationTable(Table):
    crank_speed: quantity("angular speed", 0.0, shown="> 0") | None = doc(
        "Crank speed for the resonance check, the kinematics and the driving torque "
        "(magnitude; the crank turns counter-clockwise).", default=None)
    crank_acceleration: quantity("angular acceleration", shown="any") | None = doc(
        "Crank angular acceleration for the driving torque (with crank_speed; default 0: "
        "constant speed).", default=None)

    @model_validator(mode="after")
    def _speed_first(self):
        if self.crank_acceleration is not None and self.crank_speed is None:
            raise MissingKey("crank_speed", "a crank acceleration needs the speed it acts at")
        return self


class DampingTable(Table):
    """Modal damping declared directly, in place of the materials' loss factors: one ratio for
    every mode, a ratio per mode, or Rayleigh damping C = alpha M + beta K."""

    ratio: number(0.0, 1.0, high_open=True) | None = doc(
        "One viscous damping ratio zeta for every elastic mode (e.g. 0.02 from a measured "
        "decay).", default=None)
    ratios: list[number(0.0, 1.0, high_open=True)] | None = doc(
        "A damping ratio per elastic mode, lowest mode first; modes past the end of the list "
        "take its last value.", default=None)
    rayleigh_alpha: number(0.0, 1e6) | None = doc(
        "Rayleigh mass coefficient alpha [1/s] of C = alpha M + beta K: mode i gets "
        "zeta_i = alpha / (2 omega_i) + beta omega_i / 2.", default=None)
    rayleigh_beta: number(0.0, 1.0) | None = doc(
        "Rayleigh stiffness coefficient beta [s] of C = alpha M + beta K.", default=None)

    @model_validator(mode="after")
    def _one_kind(self):
        given = [k for k in ("ratio", "ratios") if getattr(self, k) is not None]
        if self.rayleigh_alpha is not None or self.rayleigh_beta is not None:
            given.append("rayleigh_alpha/rayleigh_beta")
        if len(given) != 1:
            raise ValueError("give exactly one of: ratio, ratios, or rayleigh_alpha and/or "
                             f"rayleigh_beta (got {given or 'none'})")
        if self.ratios is not None and not self.ratios:
            raise ValueError("ratios is empty; give one ratio per mode, lowest first")
        return self


class LoadTable(Table):
    """An external load on one body of the linkage, for the driving torque: a torque, or a
    force at a point of the body; constant, or over the crank angle from a CSV file."""

    kind: choice(LoadKind) = doc("What the load is: a torque (counter-clockwise positive) or "
                                 "a force at point 'at'.")
    link: str = doc("The body it acts on: a four-bar's crank, coupler or rocker; a general "
                    "scene's [linkage.bodies] name.")
    torque: quantity("torque", shown="any") | None = doc("A constant torque (kind 'torque').",
                                                         default=None)
    force: tuple[quantity("force", shown="any"), quantity("force", shown="any")] | None = doc(
        "A constant force [Fx, Fy] (kind 'force').", default=None)
    at: Point | None = doc("Where the force acts, [x, y] in the body's frame: origin at the "
                           "body's first joint, x towards its second (kind 'force').",
                           default=None)
    frame: choice(LoadFrame) = doc(
        "Force components along the fixed axes ('global') or along the body's frame, turning "
        "with it ('body').", default=LoadFrame.GLOBAL)
    csv: str | None = doc(
        "Instead of a constant: a CSV file (path relative to the scene file) with a header row, "
        "the crank angle in degrees in its first column, evenly spaced over one full turn, and "
        "the torque (one column) or Fx, Fy (two columns) in 'unit'; interpolated linearly and "
        "periodically.", default=None)
    unit: str | None = doc("Unit of the CSV's values, e.g. 'N*m' or 'N'.", default=None)

    @model_validator(mode="after")
    def _one_value(self):
        own, other = ("torque", "force") if self.kind == "torque" else ("force", "torque")
        if getattr(self, other) is not None:
            raise ValueError(f"a {self.kind} load takes '{own}' (or csv), not '{other}'")
        if getattr(self, own) is not None and self.csv is not None:
            raise ClashingKey(own, f"give a constant '{own}' or a csv file, exactly one, "
                                   "not both")
        if getattr(self, own) is None and self.csv is None:
            raise MissingKey(own, "give a constant value or a csv file, exactly one")
        if (self.csv is None) != (self.unit is None):
            raise MissingKey("unit" if self.csv else "csv", "a csv file and its unit go together")
        if self.kind == "force" and self.at is None:
            raise MissingKey("at", "a force needs the point it acts at")
        if self.kind == "torque" and (self.at is not None or self.frame != "global"):
            raise ValueError("'at' and 'frame' belong to a force")
        return self


class KinetostaticsTable(Table):
    """A declared input torque at the driver and the output bodies it drives, for the output
    torques, transmission ratios and pin forces (``flexlink outputs``)."""

    input_torque: quantity("torque", shown="any") | None = doc(
        "Constant torque on the driver (counter-clockwise positive, the sense of its angle).",
        default=None)
    csv: str | None = doc(
        "Instead of a constant: a CSV file (path relative to the scene file) with a header row, "
        "the crank angle in degrees in its first column, evenly spaced over one full turn, and "
        "the input torque in 'unit'; interpolated linearly and periodically.", default=None)
    unit: str | None = doc("Unit of the CSV's torques, e.g. 'N*m'.", default=None)
    outputs: list[str] = doc(
        "Output bodies, each turning about a ground pivot, in the order the torque flows "
        "(e.g. ['rocker1', 'rocker2']).", min_length=1)
    sharing: choice(Sharing) = doc(
        "How two or more outputs share the input: 'series' (only the last output is loaded; "
        "each earlier one passes its torque on through the next loop) or 'split' (every output "
        "loaded, taking 'share' of the input power at rest).", default=Sharing.SERIES)
    share: number(0.0, 1.0) = doc(
        "'split' with two outputs: the first output's share of the input power at rest.",
        default=0.5)
    friction: number(0.0, 1.0, high_open=True) = doc(
        "Contact-friction factor m of the first output: a torque m T opposing its motion, T the "
        "torque it is driven with (a wiper blade on the screen).", default=0.0)
    efficiency: number(0.0, 1.0, low_open=True) = doc(
        "Bearing transmission efficiency eta: every output's bearing passes eta of the torque "
        "its input link puts on it, the rest opposing its motion.", default=1.0)

    @model_validator(mode="after")
    def _one_torque(self):
        if (self.input_torque is None) == (self.csv is None):
            raise MissingKey("input_torque", "give a constant torque or a csv file, exactly one")
        if (self.csv is None) != (self.unit is None):
            raise MissingKey("unit" if self.csv else "csv", "a csv file and its unit go together")
        if len(set(self.outputs)) != len(self.outputs):
            raise ValueError(f"outputs {self.outputs} name a body twice")
        return self


class PrbTable(Table):
    """Pseudo-rigid-body comparison of a compliant strip (``flexlink prb``)."""

    strip: str = doc("The compliant link.")
    pivot: str = doc("The characteristic pivot joint.")
    link: str = doc("The PRB link body.")
    clamp: str = doc("The body the strip is clamped to.")
    gamma: number(0.5, 1.0) = doc("Characteristic radius factor.")
    K_theta: number(0.1, 10.0) = doc("Stiffness coefficient.")


class VariantTable(Table):
    name: str | None = doc("Label of the variant family.", default=None)
    field: str = doc("Dotted key the variants change, e.g. 'linkage.synthesis.k'.")
    values: list = doc("Values of that key, as written in a file.", min_length=1)


class ReferenceTable(Table):
    """Published or measured frequencies by mode order: any key ending in _Hz is a column."""

    model_config = ConfigDict(extra="allow", frozen=True)
    __pydantic_extra__: dict[str, list[number(0.0, 1e12, low_open=True)]]

    source: str = doc("Where the reference values come from.", default="")

    @model_validator(mode="before")
    @classmethod
    def _column_names(cls, data):
        for key in data if isinstance(data, dict) else ():
            if key not in cls.model_fields and not str(key).endswith("_Hz"):
                raise UnknownKey(key, list(cls.model_fields),
                                 "a reference column ends in _Hz, e.g. Ex_Hz")
        return data

    @model_validator(mode="after")
    def _columns(self):
        for key, values in (self.__pydantic_extra__ or {}).items():
            if not values:
                raise ValueError(f"{key} is empty")
        return self


class ModalTestTable(Table):
    """Where a modal test's geometry sits in the scene (``flexlink correlate``, ``calibrate
    --test``): a test point (x, y, z) in the file's unit lands at offset + R(rotation) (x, y)
    in the scene's frame; z is out of the mechanism plane and not used for placing it."""

    unit: Literal[tuple(UNITS["length"])] | None = doc(
        "Length unit of the test file's coordinates. A unit the file states itself (UFF "
        "dataset 164, a CSV column header such as 'x [mm]') must agree. Absent: the file's "
        "own unit; a file that states none is refused.", default=None)
    offset: Point = doc("The test frame's origin in the scene's frame, [x, y] as two unit "
                        "strings, e.g. ['0 mm', '0 mm'].", default=(0.0, 0.0))
    rotation: ANGLE = doc("Angle of the test frame's x axis from the scene's x axis, "
                          "counter-clockwise; measuring directions turn with it.", default=0.0)
    max_distance: LENGTH = doc(
        "Farthest a sensor may sit from a link's axis (in the plane) and still be placed on "
        "that link; a sensor farther from every link is an error naming it.", default=0.01)


class SceneFile(Table):
    """A scene: a linkage, its pose, materials, sections, joints and what to report."""

    name: str | None = doc("Display name (default: the file name).", default=None)
    base: str | None = doc("A file merged underneath this one (its keys lose to this file's).",
                           default=None)
    linkage: LinkageTable = doc("The linkage; 'type' picks the scene kind.")
    pose: PoseTable | None = doc("Four-bar scenes: the analysed pose.", default=None)
    material: MaterialTable | None = doc("Material shared by every link.", default=None)
    section: SectionTable | None = doc("Section shared by every link.", default=None)
    links: dict[str, LinkTable] = doc("Beam links by name.", default={})
    joints: JointsTable | None = doc("Bearings and pins.", default=None)
    drive: DriveTable | None = doc("The drive holding the input link (absent: it turns freely).",
                              default=None)
    mesh: MeshTable = doc("Finite-element mesh.", default=MeshTable())
    model: ModelTable = doc("Model options.", default=ModelTable())
    reference: ReferenceTable | None = doc("Reference frequencies to compare with.",
                                           default=None)
    checks: ChecksTable = doc("Input checks.", default=ChecksTable())
    operation: OperationTable = doc("Operating conditions.", default=OperationTable())
    damping: DampingTable | None = doc("Modal damping declared directly (absent: from the "
                                       "materials' loss factors).", default=None)
    loads: list[LoadTable] = doc("External loads on the bodies, for the driving torque "
                                 "(``flexlink torque``).", default=[])
    kinetostatics: KinetostaticsTable | None = doc(
        "An input torque at the driver and its output bodies (``flexlink outputs``).",
        default=None)
    prb: PrbTable | None = doc("Pseudo-rigid-body comparison.", default=None)
    test: ModalTestTable = doc("How a modal test's geometry sits in the scene's frame.",
                               default=ModalTestTable())
    family: list[VariantTable] = doc("Variants of the scene: one key over several values "
                                "(``flexlink kinematics``).", default=[])

    @model_validator(mode="after")
    def _kind_tables(self):
        if isinstance(self.linkage, FourBarLinkage):
            if self.pose is None:
                raise ValueError("a four-bar scene needs a [pose] table")
        elif self.pose is not None:
            raise ValueError("[pose] is for four-bar scenes; a general scene sets [linkage] "
                             "start or start_transmission_angle")
        return self
