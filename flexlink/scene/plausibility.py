"""Plausibility of inputs: catch unit slips that explicit units cannot (a "300 m" link typed
for "300 mm", "53 Pa" for "53 GPa"), and warn where the model leaves its range (stubby or
shear-soft links for Euler-Bernoulli beams, poses near a dead centre, linkages whose crank cannot turn).

Ranges are deliberately wide: a value outside them is almost surely a unit mistake. A scene
that really means it sets ``[checks] plausibility = "warn"``.
"""

from __future__ import annotations

import dataclasses
import logging
import math

from flexlink.errors import InputError
from flexlink.fe.beams import BeamTheory, euler_bernoulli_pinned, timoshenko_pinned
from flexlink.scene.contract import LoadKind, Plausibility
from flexlink.units import RPM

log = logging.getLogger(__name__)

# quantity -> (low, high, SI unit, what the range covers)
RANGES = {
    "length": (1e-4, 100.0, "m", "a link of a machine, 0.1 mm to 100 m"),
    "section": (1e-6, 10.0, "m", "a section size, 1 um to 10 m"),
    "E": (1e5, 2e12, "Pa", "soft elastomers (0.1 MPa) to diamond (1.2 TPa)"),
    "density": (1.0, 3e4, "kg/m^3", "foams (10 kg/m^3) to osmium (22600 kg/m^3)"),
    "crank speed": (0.0, 1e6 * RPM, "rad/s",
                    "up to 1e6 rev/min, past the fastest dental turbines (4e5 rev/min)"),
}
LOAD_REACH = 10.0  # a load point farther than this many body sizes from its body: a unit slip
# prefixes tried for a "did you mean" hint: (factor from the slip to SI, spelling); every
# spelling is one units.py reads (a test checks), so the hint can be pasted into the file
HINTS = {"m": ((1e-3, "mm"), (1e-2, "cm")), "Pa": ((1e9, "GPa"), (1e6, "MPa")),
         "kg/m^3": ((1e3, "g/cm^3"),)}
SLIPS = (1e-3, 1e3)  # else: the value in the SI unit, a factor 1000 off
SLENDER_LIMIT = 10.0  # L/h below this: shear and rotary inertia matter (Euler-Bernoulli off)
SHEAR_WARN = 0.05  # ... or where they lower the first bending frequency by more than this
TOGGLE_WARN_DEG = 10.0  # mu within this of 0 or 180 deg: near a dead centre


@dataclasses.dataclass(frozen=True)
class Finding:
    source: str
    field: str
    message: str


def _range_finding(kind, value, source, field) -> Finding | None:
    low, high, unit, covers = RANGES[kind]
    if low <= value <= high:
        return None
    hint = ""
    for factor, spelling in HINTS.get(unit, ()):
        if low <= value * factor <= high:
            hint = f"; did you mean {value:g} {spelling}?"
            break
    else:
        for slip in SLIPS if unit in HINTS else ():  # a speed's slip is no factor 1000
            if low <= value * slip <= high:
                hint = f"; did you mean {value * slip:g} {unit}?"
                break
    return Finding(source, field, f"{value:g} {unit} is outside the plausible range "
                   f"[{low:g}, {high:g}] {unit} ({covers}){hint}")


def given_fields(origin) -> set[str]:
    """Every dotted key of ``origin`` (``Scene.origin``) and every table above it: the fields
    ``Scene.has_field`` says the scene gives, as one set (a calibration asks ~50 times per
    evaluation, and each ``has_field`` scans every key)."""
    parts = (key.split(".") for key in origin)
    return {".".join(p[:i]) for p in parts for i in range(1, len(p) + 1)}


def scene_findings(scene) -> list[Finding]:
    """Implausible lengths, section sizes, moduli and densities of a scene (a
    ``contract.Scene``)."""
    present = given_fields(scene.origin)

    def where(*fields):
        field = next((f for f in fields if f in present), fields[-1])
        return scene.file_of(field), field

    found = []
    if scene.four_bar is not None:
        for name, value in zip(("ground", "crank", "coupler", "rocker"), scene.four_bar.lengths):
            found.append(_range_finding("length", value, *where(
                f"linkage.{name}", f"linkage.four_bar.{name}", "linkage.ground")))
    for link, s in scene.sections.items():
        width, thickness = s.strip
        for kind, key, value in (("section", "width", width), ("section", "thickness", thickness),
                                 ("E", "E", s.E), ("density", "density", s.density)):
            if kind == "section":
                fields = (f"links.{link}.section.{key}", f"section.{key}")
            else:
                fields = (f"links.{link}.material.{key}", f"links.{link}.material",
                          f"material.{key}", "material")
            found.append(_range_finding(kind, value, *where(*fields)))
    if scene.options.crank_speed is not None:
        found.append(_range_finding("crank speed", scene.options.crank_speed,
                                    *where("operation.crank_speed")))
    found += [load_finding(scene, load) for load in scene.loads]
    unique = {}
    for f in found:
        if f is not None:
            unique.setdefault((f.source, f.field, f.message), f)
    return list(unique.values())


def load_finding(scene, load) -> Finding | None:
    """A force's point ``at`` more than LOAD_REACH body sizes (the largest distance between
    the body's joints) from the body's first joint: a unit slip, not a lever."""
    if load.kind is not LoadKind.FORCE:
        return None
    body = scene.linkage.body(load.body)
    size = max(math.dist(a, b) for a in body.shape for b in body.shape)
    reach = math.hypot(*load.at)
    if reach <= LOAD_REACH * size:
        return None
    return Finding(scene.file_of("loads"), f"{load.field}.at",
                   f"the point is {reach:g} m from body {load.body}'s first joint, more than "
                   f"{LOAD_REACH:g} times the body's size ({size:g} m): outside the plausible "
                   "range for a point of the body")


def check_speeds(scene, speeds, field: str) -> None:
    """Crank speeds [rad/s] given on the command line (``field``, e.g. "--speed") against the
    plausible range, refused or logged as the scene's [checks] plausibility says."""
    for speed in speeds:
        finding = _range_finding("crank speed", abs(float(speed)), "command line", field)
        if finding is not None:
            _report([finding], scene)
            return


def check_scene(scene) -> None:
    """Raise InputError on the first implausible value, or log them all when the scene says
    ``[checks] plausibility = "warn"``."""
    _report(scene_findings(scene), scene)


def _report(findings: list[Finding], scene) -> None:
    """Raise InputError on the first of ``findings``, or log them all when ``scene`` says
    ``[checks] plausibility = "warn"``."""
    if not findings:
        return
    if scene.options.plausibility is Plausibility.WARN:
        for f in findings:
            log.warning("%s: %s: %s", f.source, f.field, f.message)
        return
    first = findings[0]
    raise InputError(first.message + (f" (and {len(findings) - 1} more)" if len(findings) > 1 else ""),
                     source=first.source, field=first.field,
                     expected="a value in the range, or [checks] plausibility = \"warn\"")


def timoshenko_drop(section, length: float) -> float:
    """Relative drop of a pinned-pinned beam's first bending frequency from shear and rotary
    inertia (Timoshenko, shear factor 5/6) against Euler-Bernoulli: 1 - 1/sqrt(1 + a (1 + E/(k G)))
    with a = (pi r / L)^2, r = h / sqrt(12)."""
    a = (math.pi * section.depth / math.sqrt(12) / length) ** 2
    return 1.0 - 1.0 / math.sqrt(1.0 + a * (1.0 + section.E / (5.0 / 6.0 * section.G)))


def exact_timoshenko_drop(section, length: float) -> float:
    """1 - f_T / f_EB: the relative drop of the link's first bending frequency as a
    pinned-pinned beam [-] once shear strain and rotary inertia count, from the exact
    solutions of both theories (``fe.beams.timoshenko_pinned``, ``euler_bernoulli_pinned``),
    which flexlink's Timoshenko and Euler-Bernoulli elements converge to
    (tests/fe/test_timoshenko.py). Exact where ``timoshenko_drop`` is a first-order estimate, and
    a few microseconds: scenes are loaded thousands of times in a calibration."""
    return 1.0 - timoshenko_pinned(section, length) / euler_bernoulli_pinned(section, length)


def model_warnings(model) -> list[str]:
    """Links outside Euler-Bernoulli theory: stubby (L/h < SLENDER_LIMIT), or so soft in shear
    (E/G large, as in fabric composites) that Timoshenko theory lowers the first bending
    frequency by more than SHEAR_WARN. The first-order estimate picks the links; the drop
    quoted is the exact one of Timoshenko theory for that link (``exact_timoshenko_drop``).
    Links already modelled with Timoshenko elements are not Euler-Bernoulli beams: no warning."""
    out = []
    for link in model.links:
        s = link.section
        if s.beam is not BeamTheory.EULER_BERNOULLI:
            continue
        ratio, drop = link.length / s.depth, timoshenko_drop(s, link.length)
        if ratio < SLENDER_LIMIT or drop > SHEAR_WARN:
            exact = exact_timoshenko_drop(s, link.length)
            out.append(f"link {link.name}: slenderness L/h = {ratio:.3g} with E/G = {s.E / s.G:.3g} "
                       "is outside Euler-Bernoulli theory (no shear strain, no rotary inertia): "
                       "Timoshenko theory puts its first bending frequency as a pinned-pinned "
                       f"beam {100 * exact:.3g} % lower (exact solution; [model] beam = "
                       "\"timoshenko\" uses Timoshenko elements for the whole scene)")
    return out


def pose_warnings(four_bar, pose) -> list[str]:
    """Poses near a dead centre (a transmission angle near 0 or 180 deg) and four-bars
    (``four_bar``, None for other linkages) whose crank cannot turn."""
    out = []
    if four_bar is not None and not four_bar.crank_turns_fully():
        out.append(f"the linkage is {four_bar.grashof_class()}: its input link cannot turn "
                   "fully; the pose is one of a limited range")
    elif four_bar is not None and four_bar.flat_poses():
        flat = ", ".join(f"{math.degrees(t):g}" for t in four_bar.flat_poses())
        out.append("the linkage is change-point: its crank turns fully, but at crank "
                   f"{flat} deg every link lies on the ground line (a flat pose), where the "
                   "linkage can change assembly branch and has a mechanism mode")
    for pair, mu_rad in pose.transmission.items():
        mu = math.degrees(mu_rad)
        distance = min(mu, 180.0 - mu)
        if distance < TOGGLE_WARN_DEG:
            out.append(f"transmission angle {pair} {mu:.3f} deg is {distance:.3g} deg from a dead "
                       "centre (0 or 180 deg): the pose and the joint loads are very sensitive "
                       "there")
    return out
