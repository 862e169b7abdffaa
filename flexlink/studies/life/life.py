"""Will each link survive: peak stress, range, safety factors and fatigue life of every link
over the crank turn at a crank speed (``stress_field``), from its material's strength data.

A metal link (a material file with ``[strength]``): at every element end and fibre the stress
history of one turn is counted and judged by ``analysis.fatigue`` on the part's S-N line
(``materials.fatigue``: the specimen line of the material file with the Marin factors of the
part: the given surface finish, the size of the link's section (a rectangle's equivalent
diameter 0.808 sqrt(b h), a tube's outer diameter, else the section depth), the load type of
the larger alternating part at that point (axial or bending), the temperature and the
reliability). The link's verdict is its worst point: the smallest fatigue safety factor, the
shortest life, with where (distance from the start joint, fibre) and when (the crank angle of
the peak).

A composite link (a woven laminate from constituent files): the stress along and across the
fibres in each ply (``materials.laminate``) against the ply strengths, as strength ratios by
maximum stress and Tsai-Wu; no life is given (``COMPOSITE_NOTE``).

A link whose material is written as E and density in the scene has no strength data: refused,
naming the scene file and the field. No strength is ever assumed.
"""

from __future__ import annotations

import dataclasses
import enum
import math

import numpy as np

from flexlink.analysis.fatigue import MeanStress, history_fatigue
from flexlink.errors import InputError
from flexlink.fe.model import Bending
from flexlink.materials.fatigue import (LoadType, PartCurve, Surface, marin_factors,
                                        rectangle_diameter, specimen_curve)
from flexlink.materials.laminate import (layer_stresses, max_stress_ratio, ply_strength,
                                         tsai_wu_ratio)
from flexlink.materials.mixtures import isotropic_shear, load_constituent, rule_of_mixtures
from flexlink.materials.mixtures import ShearSource
from flexlink.materials.strength import load_strength
from flexlink.scene import Scene
from flexlink.studies.life.stress_field import StressField, StressModel

COMPOSITE_NOTE = ("composite fatigue does not follow a metal's S-N rules (stiffness loss, "
                  "matrix cracking, delamination); no life is given without a measured fatigue "
                  "curve of this laminate")
HOUR = 3600.0


class LinkKind(enum.StrEnum):
    METAL = "metal"
    COMPOSITE = "composite"


@dataclasses.dataclass(frozen=True)
class Conditions:
    """How the parts are judged: surface finish, temperature [C], reliability (0, 1), the
    mean-stress correction, and a required life [h] (None: against the endurance limit)."""

    surface: Surface = Surface.MACHINED
    temperature: float = 20.0
    reliability: float = 0.5
    mean_stress: MeanStress = MeanStress.GOODMAN
    hours: float | None = None

    def __post_init__(self):
        if not (isinstance(self.reliability, (int, float)) and 0.0 < self.reliability < 1.0):
            raise InputError(f"got {self.reliability!r}", source="command line",
                             field="--reliability", expected="a probability in (0, 1), e.g. 0.99")
        if self.hours is not None and not (math.isfinite(self.hours) and self.hours > 0):
            raise InputError(f"got {self.hours!r}", source="command line", field="--hours",
                             expected="a positive finite number of hours")
        if not math.isfinite(self.temperature):
            raise InputError(f"got {self.temperature!r}", source="command line",
                             field="--temperature", expected="a temperature in C")
        object.__setattr__(self, "surface", Surface(self.surface))
        object.__setattr__(self, "mean_stress", MeanStress(self.mean_stress))


@dataclasses.dataclass(frozen=True)
class Where:
    """A point and instant: value [Pa], distance from the link's start joint [m], fibre
    (+1: y = +c, -1: y = -c), crank angle [rad]."""

    value: float
    position: float
    fibre: int
    angle: float


@dataclasses.dataclass(frozen=True)
class LinkLife:
    """One link's verdict. peak: largest |sigma|; range: the largest stress range over the
    turn at one point (its crank angle that of the point's maximum), mean: that point's mean
    stress [Pa]. Metal: safety (fatigue, [-]) at ``worst`` with that cycle's amplitude and
    mean (the Haigh point), life [turns] (inf: unlimited), yield_safety Sy / max|sigma|,
    endurance Se and Sut, Sy [Pa] of the part, the Marin factors at the worst point.
    Composite: strength ratios (max stress, Tsai-Wu) and the ply (0 at the y = -c face) where
    the smaller one is. material: the material (a shipped name or a path, as the scene writes
    it; a composite's fibre + matrix)."""

    link: str
    kind: LinkKind
    material: str
    peak: Where
    range: Where
    mean: float
    quasi_static_peak: float
    safety: float = math.nan
    worst: Where | None = None
    amplitude: float = math.nan
    cycle_mean: float = math.nan
    life: float = math.nan
    yield_safety: float = math.nan
    endurance: float = math.nan
    Sut: float = math.nan
    Sy: float = math.nan
    marin: dict = dataclasses.field(default_factory=dict)
    load_type: str = ""
    max_stress_ratio: float = math.nan
    tsai_wu_ratio: float = math.nan
    ply: int = -1

    @property
    def margin(self) -> float:
        """The number the links are ordered by (smallest first): the fatigue safety factor, or
        the smaller strength ratio of a composite."""
        if self.kind is LinkKind.METAL:
            return self.safety
        return min(self.max_stress_ratio, self.tsai_wu_ratio)


@dataclasses.dataclass(frozen=True)
class LifeStudy:
    """Every link's verdict, worst first, at crank ``speed`` [rad/s] under ``conditions``; the
    field it came from."""

    speed: float
    conditions: Conditions
    links: tuple[LinkLife, ...]
    field: StressField

    @property
    def turns_per_hour(self) -> float:
        return self.speed / (2.0 * math.pi) * HOUR

    def hours(self, link: LinkLife) -> float:
        """``link``'s life [h] at this speed."""
        return link.life / self.turns_per_hour


def check_strengths(scene: Scene, links=None) -> None:
    """Refuse (InputError naming the file and key) a link of ``scene`` (or of ``links``, names)
    whose material lacks the strength data its verdict needs; cheap, so a command checks
    before its study."""
    for name in links or [link.name for link in scene.links]:
        source = scene.materials.get(name)
        if source is None:
            raise InputError(f"no material record of link {name!r}", source=scene.path,
                             field=f"links.{name}")
        if source.composite is not None:
            c = source.composite
            ply_strength(load_constituent(c.fiber), load_strength(c.fiber),
                         load_constituent(c.matrix), load_strength(c.matrix),
                         c.fiber_volume_fraction)
        elif source.isotropic is not None:
            try:
                specimen_curve(load_strength(source.isotropic))
            except InputError as exc:  # say which link and scene asked for it
                raise InputError(f"{exc} (link {name!r}, {source.source}: "
                                 f"{source.field})") from None
        else:
            raise InputError(
                "E and density are written in the scene: no material file gives this link's "
                "strength, and none is assumed", source=source.source, field=source.field,
                expected="isotropic = 'name' of a material file with a [strength] table, "
                         "e.g. 'aisi_1080'")


def life_study(scene: Scene, model: StressModel, field: StressField,
               conditions: Conditions = Conditions()) -> LifeStudy:
    """Each link's ``LinkLife`` (module docstring), the worst (smallest margin) first."""
    check_strengths(scene, model.points.links)
    out = []
    for i, name in enumerate(model.points.links):
        source = scene.materials[name]
        index = model.points.of(name)
        common = _common(field, model, index)
        if source.composite is not None:
            out.append(_composite(name, source, model.sections[i], field, model, index, common))
        else:
            out.append(_metal(name, source, model.sections[i], field, model, index, common,
                              conditions))
    return LifeStudy(speed=field.speed, conditions=conditions,
                     links=tuple(sorted(out, key=lambda l: l.margin)), field=field)


def _where(field: StressField, model: StressModel, index, sample: int, column: int,
           value: float) -> Where:
    point = index[column]
    return Where(value=float(value), position=float(model.points.position[point]),
                 fibre=1 if model.points.fibre[point] == 0 else -1,
                 angle=float(field.angles[sample]))


def _common(field, model, index):
    """(peak Where, range Where, mean at the range's point, quasi-static peak) of a link."""
    s = field.total[:, index]
    sample, column = np.unravel_index(np.argmax(np.abs(s)), s.shape)
    peak = _where(field, model, index, sample, column, s[sample, column])
    spans = s.max(axis=0) - s.min(axis=0)
    worst = int(np.argmax(spans))
    span = _where(field, model, index, int(np.argmax(s[:, worst])), worst, spans[worst])
    return peak, span, float(s[:, worst].mean()), float(np.abs(field.quasi_static[:, index]).max())


def _diameter(section) -> float:
    """The size of the section for the Marin size factor [m]: a rectangle's (I = A h^2 / 12)
    equivalent diameter 0.808 sqrt(b h), else its depth (a round's outer diameter; for any
    other section the larger size, which gives the smaller kb)."""
    if abs(section.second_moment - section.area * section.depth**2 / 12.0) \
            <= 1e-9 * section.second_moment:
        return rectangle_diameter(*section.strip)
    return section.depth


def fibre_pair_fatigue(histories, material: str, section, conditions: Conditions = Conditions(),
                       speed: float | None = None):
    """The fatigue of stress ``histories`` (samples over one turn, points) [Pa] whose columns
    come in pairs, the fibres y = +c and y = -c of one section (so the axial and bending parts
    of each pair are known, for the Marin load factor), in ``section`` (a ``fe.model.Section``:
    its size for the Marin size factor) of the material file ``material`` (a shipped name or a
    .toml path with [strength]), under ``conditions``; ``speed`` [rad/s] turns a required life
    in hours into cycles (needed only with ``conditions.hours``). Returns (per column
    ``analysis.fatigue.Fatigue``, per column the LoadType, the part curves by LoadType, the
    specimen curve). For any stress history over a turn, e.g. a large-deflection analysis'."""
    specimen = specimen_curve(load_strength(material))
    s = np.asarray(histories, dtype=float)
    if s.ndim != 2 or s.shape[1] % 2:
        raise ValueError(f"histories must be (samples, 2 k) fibre pairs, got {s.shape}")
    required = None
    if conditions.hours is not None:
        if speed is None:
            raise ValueError("a required life in hours needs the crank speed")
        required = conditions.hours * HOUR * speed / (2.0 * math.pi)
    pair = s.reshape(len(s), -1, 2)
    axial, bending = pair.mean(axis=-1), 0.5 * (pair[..., 0] - pair[..., 1])
    kinds = [LoadType.AXIAL if a else LoadType.BENDING
             for a in np.repeat(np.ptp(axial, axis=0) > np.ptp(bending, axis=0), 2)]
    curves = {kind: PartCurve(specimen, marin_factors(
        specimen.Sut, conditions.surface, _diameter(section), kind, conditions.temperature,
        conditions.reliability)) for kind in (LoadType.BENDING, LoadType.AXIAL)}
    results = [history_fatigue(s[:, c], curves[kinds[c]], conditions.mean_stress, required)
               for c in range(s.shape[1])]
    return results, kinds, curves, specimen


def _metal(name, source, section, field, model, index, common, conditions):
    s = field.total[:, index]
    results, kinds, curves, specimen = fibre_pair_fatigue(s, source.isotropic, section,
                                                          conditions, field.speed)
    column = min(range(len(results)), key=lambda c: (results[c].safety, -results[c].damage))
    result, kind = results[column], kinds[column]
    part = curves[kind]
    peak_sample = int(np.argmax(np.abs(s[:, column])))
    peak, span, mean, quasi = common
    return LinkLife(
        link=name, kind=LinkKind.METAL, material=source.isotropic,
        peak=peak, range=span, mean=mean, quasi_static_peak=quasi, safety=result.safety,
        worst=_where(field, model, index, peak_sample, column, s[peak_sample, column]),
        amplitude=result.amplitude, cycle_mean=result.mean,
        life=float(min(r.life for r in results)),
        yield_safety=specimen.Sy / max(abs(peak.value), 1e-300), endurance=part.endurance,
        Sut=specimen.Sut, Sy=specimen.Sy, marin=dataclasses.asdict(part.marin),
        load_type=str(kind))


def _composite(name, source, section, field, model, index, common):
    c = source.composite
    fiber, matrix = load_constituent(c.fiber), load_constituent(c.matrix)
    if ShearSource(c.shear_modulus) is ShearSource.ISOTROPIC:
        fiber, matrix = isotropic_shear(fiber), isotropic_shear(matrix)
    ply = rule_of_mixtures(fiber, matrix, c.fiber_volume_fraction)
    strength = ply_strength(fiber, load_strength(c.fiber), matrix, load_strength(c.matrix),
                            c.fiber_volume_fraction)
    s = field.total[:, index]
    pair = s.reshape(len(s), -1, 2) / section.E  # laminate strain at the fibres y = +c, -c
    middle, half = pair.mean(axis=-1), 0.5 * (pair[..., 0] - pair[..., 1])
    plies = source.plies or 1
    if section.bending is Bending.FLATWISE:  # the plies stack through the in-plane depth
        faces = np.linspace(-1.0, 1.0, plies + 1)  # y / c of the ply faces, -c first
        strain = middle[..., None, None] + half[..., None, None] * np.stack([faces[:-1],
                                                                              faces[1:]], -1)
    else:  # edgewise: every ply reaches both extreme fibres
        strain = np.repeat(pair[..., None, :], plies, axis=-2)
    layers = layer_stresses(ply, strain)  # (samples, ends, plies, faces, 2 layers, 2)
    ratios = [np.min(f(layers, strength), axis=(0, 1, 3, 4)) for f in (max_stress_ratio,
                                                                        tsai_wu_ratio)]
    worst_ply = int(np.argmin(np.minimum(*ratios)))
    peak, span, mean, quasi = common
    return LinkLife(
        link=name, kind=LinkKind.COMPOSITE,
        material=f"{c.fiber} + {c.matrix}",
        peak=peak, range=span, mean=mean, quasi_static_peak=quasi,
        max_stress_ratio=float(ratios[0].min()), tsai_wu_ratio=float(ratios[1].min()),
        ply=worst_ply)


@dataclasses.dataclass(frozen=True)
class SafetySweep:
    """The smallest margin (``LinkLife.margin``) of each link (``links``) against crank
    ``speeds`` [rad/s]: margin (speeds, links), NaN where no steady state exists; the
    stability map's unstable ranges over the same speeds (``stability_map.InstabilityRange``)
    and the largest multiplier modulus per speed."""

    speeds: np.ndarray
    links: tuple[str, ...]
    margin: np.ndarray
    ranges: tuple
    largest_modulus: np.ndarray

    def __post_init__(self):
        if self.margin.shape != (len(self.speeds), len(self.links)):
            raise ValueError(f"margin must be ({len(self.speeds)}, {len(self.links)})")


def safety_sweep(scene: Scene, model: StressModel, speeds, conditions: Conditions = Conditions(),
                 progress=None) -> SafetySweep:
    """Each link's margin at each of ``speeds`` [rad/s] > 0 beside the stability map over
    them (one verdict per speed, which the stress fields then skip)."""
    from flexlink.studies.life.stress_field import stress_field
    from flexlink.studies.running.stability_map import stability_map

    speeds = np.asarray(speeds, dtype=float)
    verdict = stability_map(model.verdict, speeds)
    names = model.points.links
    margin = np.full((len(speeds), len(names)), np.nan)
    for i in (progress or iter)(range(len(speeds))):
        if verdict.largest_modulus[i] >= 1.0:
            continue
        study = life_study(scene, model, stress_field(model, speeds[i], check_stability=False),
                           conditions)
        for link in study.links:
            margin[i, names.index(link.link)] = link.margin
    return SafetySweep(speeds, names, margin, verdict.ranges, verdict.largest_modulus)
