"""Sensitivity of a scene's frequencies to its assumed inputs, each over its written range.

Every assumed value a scene gives a ``range`` (with its ``reason``, see ``scene/source.py``)
is evaluated at both ends of the range, the other inputs held at their values. Then a Monte
Carlo draws all ranged inputs together, with the Table I constituent spreads
(``uncertainty.py``: normal, sd = the printed spread), and gives the 2.5 and 97.5 % quantiles
of each frequency: a 95 % interval of the a-priori prediction.

How a range is sampled, decided by its ends alone (no fitting):
- a categorical range (e.g. the orientation "flatwise" / "edgewise") is evaluated at both ends
  but not sampled: the two values are different models, not a scatter, and are reported apart;
- an end written "rigid": uniform in compliance 1/k over [0, 1/low] (springs in series add
  compliances);
- both ends positive and a decade or more apart: log-uniform (the order of magnitude is what
  is uncertain);
- otherwise uniform.
"""

from __future__ import annotations

import dataclasses
import logging
import math

import numpy as np

from flexlink.analysis.families import elastic_modes
from flexlink.errors import FlexlinkError, InputError
from flexlink.meshes import DEFAULT_ELEMENTS
from flexlink.parallel import run_tasks
from flexlink.scene import load_scene
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.calibration.uncertainty import draw_samples, material_overrides, scene_inputs

log = logging.getLogger(__name__)
RIGID = "rigid"
LOG_SPAN = 10.0  # high / low from which a range is sampled log-uniformly


@dataclasses.dataclass(frozen=True)
class Span:
    """An assumed input's range: dotted ``field``, the ``value`` and both ends as written,
    and the ``reason`` for the range."""

    field: str
    value: str
    low: str
    high: str
    reason: str

    @property
    def categorical(self) -> bool:
        return _number(self.low) is None and self.low != RIGID

    def sample(self, u: float) -> str:
        """The input at quantile ``u`` in [0, 1) of its distribution (module docstring), as
        written in a file."""
        low, low_unit = _number(self.low)
        if self.high == RIGID:
            compliance = float(u) / low
            return RIGID if compliance == 0 else f"{1.0 / compliance!r} {low_unit}"
        high, high_unit = _number(self.high)
        if high_unit != low_unit:
            raise InputError(f"range ends in different units: {self.low!r}, {self.high!r}",
                             field=f"{self.field}.range", expected="both ends in one unit")
        if low > 0 and high / low >= LOG_SPAN:
            value = float(low * (high / low) ** u)
        else:
            value = float(low + u * (high - low))
        return f"{value!r} {low_unit}".strip()


def _number(text):
    """(number, unit) of a quantity written "1e5 N/m", or None for a word."""
    head, _, unit = str(text).strip().partition(" ")
    try:
        return float(head), unit.strip()
    except ValueError:
        return None


def spans(path) -> tuple[Span, ...]:
    """The ranged assumptions of the scene at ``path``."""
    scene = load_scene(path)
    return tuple(Span(a.field, a.value, str(a.range[0]), str(a.range[1]), a.reason)
                 for a in scene.assumptions if a.range)


def frequencies(path, overrides: dict, n_modes: int, elements: int | None) -> np.ndarray:
    """Elastic frequencies [Hz] of ``path`` with ``overrides``; NaN where the model fails
    (logged, and counted by the callers). The model's range warnings are kept quiet here, in
    worker processes too: each variant would repeat them, and the nominal run reports them."""
    logging.getLogger("flexlink.analysis.modal").setLevel(logging.ERROR)
    try:
        return elastic_modes(load_scene(path, overrides=overrides), n_modes, elements)[0]
    except FlexlinkError as exc:
        log.info("%s with %s: %s", path, overrides, exc)
        return np.full(n_modes, np.nan)


@dataclasses.dataclass(frozen=True)
class EndPoints:
    """For one scene: the nominal frequencies [Hz] (n_modes,) and, per span, the frequencies
    at its low and high ends, shape (2, n_modes)."""

    path: str
    nominal: np.ndarray
    spans: tuple[Span, ...]
    ends: tuple[np.ndarray, ...]

    def __post_init__(self):
        n = np.shape(self.nominal)
        check_shape("EndPoints", "nominal", self.nominal, (None,))
        if len(self.ends) != len(self.spans):
            raise ValueError(f"EndPoints.ends has {len(self.ends)} entries, expected "
                             f"{len(self.spans)} (one per span)")
        for k, ends in enumerate(self.ends):
            check_shape("EndPoints", f"ends[{k}]", ends, (2, *n))


def end_points(path, n_modes: int = 4, elements: int | None = None, n_jobs: int = 1,
               show_progress: bool = False) -> EndPoints:
    ranged = spans(path)
    tasks = [(str(path), {}, n_modes, elements)]
    for s in ranged:
        tasks += [(str(path), {s.field: s.low}, n_modes, elements),
                  (str(path), {s.field: s.high}, n_modes, elements)]
    out = run_tasks(frequencies, tasks, n_jobs=n_jobs, show_progress=show_progress, label="end points")
    return EndPoints(str(path), out[0], ranged,
                     tuple(np.array(out[1 + 2 * k: 3 + 2 * k]) for k in range(len(ranged))))


@dataclasses.dataclass(frozen=True)
class Interval:
    """Monte Carlo over the ranged assumptions and the Table I spreads: ``samples``
    (n, n_modes) [Hz] of one scene; ``failed`` draws that gave no frequency (NaN)."""

    path: str
    samples: np.ndarray
    seed: int

    def __post_init__(self):
        check_shape("Interval", "samples", self.samples, (None, None))

    @property
    def low(self) -> np.ndarray:
        return np.nanquantile(self.samples, 0.025, axis=0)

    @property
    def high(self) -> np.ndarray:
        return np.nanquantile(self.samples, 0.975, axis=0)

    @property
    def failed(self) -> int:
        return int(np.isnan(self.samples).any(axis=1).sum())

    def contains(self, reference) -> np.ndarray:
        ref = np.asarray(reference, dtype=float)[:self.samples.shape[1]]
        return (self.low[:len(ref)] <= ref) & (ref <= self.high[:len(ref)])


def draws(path, samples: int, seed: int) -> list[dict]:
    """``samples`` override sets: each ranged continuous assumption at a random quantile and
    the constituent properties drawn from their Table I spreads (material only when the
    scene's material is a composite)."""
    ranged = [s for s in spans(path) if not s.categorical]
    rng = np.random.default_rng(seed)
    quantiles = rng.random((samples, len(ranged)))
    scene = load_scene(path)
    materials = [{}] * samples
    if scene.composite is not None:
        inputs = scene_inputs(path, {}, vf_sd=0.0, thickness_sd=0.0)
        # the laminate thickness comes from the ranged ply thickness, not from here
        materials = [{k: v for k, v in material_overrides(inputs, d).items()
                      if k != "section.thickness"}
                     for d in draw_samples(inputs, samples, seed + 1)]
    return [{**materials[i], **{s.field: s.sample(u) for s, u in zip(ranged, quantiles[i])}}
            for i in range(samples)]


def interval(path, samples: int = 200, seed: int = 1, n_modes: int = 4,
             elements: int | None = None, n_jobs: int = 1, show_progress: bool = False) -> Interval:
    tasks = [(str(path), d, n_modes, elements) for d in draws(path, samples, seed)]
    out = run_tasks(frequencies, tasks, n_jobs=n_jobs, show_progress=show_progress, label="Monte Carlo")
    return Interval(str(path), np.array(out), seed)


def relative_change(points: EndPoints) -> list[tuple[str, float]]:
    """(field, largest |f_end / f_nominal - 1| over both ends and all modes), largest first."""
    rows = []
    for s, ends in zip(points.spans, points.ends):
        with np.errstate(invalid="ignore"):
            change = np.nanmax(np.abs(ends / points.nominal - 1.0)) if np.isfinite(ends).any() else math.nan
        rows.append((s.field, float(change)))
    return sorted(rows, key=lambda r: -r[1] if math.isfinite(r[1]) else 0.0)


@dataclasses.dataclass(frozen=True)
class SceneSensitivity:
    """The sensitivity study of one scene: each ranged input at both ends (``points``), the
    95 % interval over all of them (``interval``), the scene's reference columns they are read
    against ({column: values [Hz]}) and the study's mesh [elements per link]."""

    points: EndPoints
    interval: Interval
    reference: dict[str, tuple[float, ...]]
    elements: int

    def __post_init__(self):
        check_shape("SceneSensitivity", "interval.samples", self.interval.samples,
                    (None, len(self.points.nominal)))


def sensitivity_study(scene, n_modes: int = 4, samples: int = 200, seed: int = 1,
                      n_jobs: int = 1, show_progress: bool = False) -> SceneSensitivity:
    """End points and the Monte Carlo interval of ``scene`` on the study's mesh
    (``DEFAULT_ELEMENTS``), with its reference columns."""
    points = end_points(scene.path, n_modes, DEFAULT_ELEMENTS, n_jobs, show_progress)
    spread = interval(scene.path, samples, seed, n_modes, DEFAULT_ELEMENTS, n_jobs, show_progress)
    reference = dict(scene.reference.columns) if scene.reference else {}
    return SceneSensitivity(points, spread, reference, DEFAULT_ELEMENTS)
