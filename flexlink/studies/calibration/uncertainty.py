"""Propagation of input scatter to natural frequencies: Monte Carlo and first-order sensitivities.

Uncertain inputs: the Table I constituent properties (E, G, density of fibre and matrix, each
"mean +- spread" read as a normal distribution with standard deviation = the printed spread),
the fibre volume fraction and the laminate thickness (user-given standard deviations). Each
sample goes through the same path as a scene: rule of mixtures -> beam material -> the
scene's model family, so nothing is linearised in the Monte Carlo. Samples are drawn in the
parent process from one seed, so the result does not depend on the number of workers.
Normal draws are truncated at 1 % of the mean (a modulus or density cannot be <= 0).

Sensitivities are normalised, S = d ln f / d ln p, by central differences of +-1 % in p; the
first-order standard deviation of ln f is sqrt(sum (S sd_p / p)^2) (both from
``studies.calibration.derivatives``, the formulas the calibration Jacobian uses too).
"""

from __future__ import annotations

import dataclasses
import logging

import numpy as np

from flexlink.errors import FlexlinkError, InputError
from flexlink.analysis.families import elastic_modes
from flexlink.materials.mixtures import Constituent, load_constituent, woven_composite
from flexlink.parallel import run_tasks
from flexlink.scene import load_scene
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.calibration.derivatives import central_log_slopes, central_points, first_order_sd

PROPERTIES = ("E", "G", "density")

log = logging.getLogger(__name__)


@dataclasses.dataclass(frozen=True)
class Inputs:
    """Nominal uncertain inputs and their standard deviations, as flat name -> value maps
    (SI; names like "fiber.E", "matrix.density", "vf", "thickness")."""

    nominal: dict[str, float]
    sd: dict[str, float]
    fiber_name: str
    matrix_name: str


def scene_inputs(path, base_overrides: dict, vf_sd: float, thickness_sd: float) -> Inputs:
    """The uncertain inputs of a scene with a composite material, at ``base_overrides``."""
    scene = load_scene(path, overrides=base_overrides)
    composite = scene.composite
    if composite is None:
        raise InputError("uncertainty propagation needs a composite material table",
                         source=scene.path, field="material.composite")
    fiber, matrix = load_constituent(composite.fiber), load_constituent(composite.matrix)
    nominal, sd = {}, {}
    for prefix, c in (("fiber", fiber), ("matrix", matrix)):
        for prop in PROPERTIES:
            nominal[f"{prefix}.{prop}"] = getattr(c, prop)
            sd[f"{prefix}.{prop}"] = c.spread.get(prop, 0.0)
    nominal["vf"] = composite.fiber_volume_fraction
    sd["vf"] = vf_sd
    section = scene.sections["crank"]
    nominal["thickness"] = section.strip[1]
    sd["thickness"] = thickness_sd
    return Inputs(nominal, sd, composite.fiber, composite.matrix)


def material_overrides(inputs: Inputs, values: dict[str, float]) -> dict:
    """Scene overrides for one set of input values: the whole [material] table replaced by the
    resulting beam material, and the section thickness."""
    base = {"fiber": load_constituent(inputs.fiber_name), "matrix": load_constituent(inputs.matrix_name)}
    parts: dict[str, Constituent] = {
        k: dataclasses.replace(c, **{p: values[f"{k}.{p}"] for p in PROPERTIES})
        for k, c in base.items()}
    beam = woven_composite(parts["fiber"], parts["matrix"], values["vf"])
    # float(): a NumPy scalar's repr is "np.float64(...)", which no scene file can read
    return {"material": {"E": f"{float(beam.E)!r} Pa", "G": f"{float(beam.G)!r} Pa",
                         "density": f"{float(beam.density)!r} kg/m^3"},
            "section.thickness": f"{float(values['thickness'])!r} m"}


def evaluate(paths, base_overrides: dict, inputs: Inputs, values: dict[str, float],
             n_modes: int, elements: int | None) -> np.ndarray:
    """Frequencies [Hz], shape (cases, n_modes), for one set of input values (NaN on failure)."""
    over = {**base_overrides, **material_overrides(inputs, values)}
    out = np.full((len(paths), n_modes), np.nan)
    for i, path in enumerate(paths):
        try:
            out[i] = elastic_modes(load_scene(path, overrides=over), n_modes, elements)[0]
        except FlexlinkError as exc:  # reported as NaN and counted, never silently dropped
            log.info("%s at %s: %s", path, values, exc)
    return out


def draw_samples(inputs: Inputs, samples: int, seed: int) -> list[dict[str, float]]:
    rng = np.random.default_rng(seed)
    names = sorted(inputs.nominal)
    mean = np.array([inputs.nominal[n] for n in names])
    sd = np.array([inputs.sd[n] for n in names])
    draws = rng.normal(mean, sd, size=(samples, len(names)))
    draws = np.maximum(draws, 0.01 * mean)
    if "vf" in names:
        k = names.index("vf")
        draws[:, k] = np.clip(draws[:, k], 0.01, 0.99)
    return [{n: float(v) for n, v in zip(names, row)} for row in draws]


@dataclasses.dataclass(frozen=True)
class MonteCarlo:
    """samples: (n, cases, n_modes) [Hz]; mean and the 2.5 / 97.5 % quantiles per case, mode."""

    samples: np.ndarray
    seed: int

    def __post_init__(self):
        check_shape("MonteCarlo", "samples", self.samples, (None, None, None))

    @property
    def mean(self):
        return np.nanmean(self.samples, axis=0)

    @property
    def low(self):
        return np.nanquantile(self.samples, 0.025, axis=0)

    @property
    def high(self):
        return np.nanquantile(self.samples, 0.975, axis=0)

    def contains(self, reference: np.ndarray) -> np.ndarray:
        return (self.low <= reference) & (reference <= self.high)


def monte_carlo(paths, base_overrides: dict, inputs: Inputs, samples: int, seed: int,
                n_modes: int = 4, elements: int | None = None, n_jobs: int = -1,
                show_progress: bool = False) -> MonteCarlo:
    draws = draw_samples(inputs, samples, seed)
    tasks = [(tuple(paths), base_overrides, inputs, d, n_modes, elements) for d in draws]
    results = run_tasks(evaluate, tasks, n_jobs=n_jobs, show_progress=show_progress, label="Monte Carlo samples")
    return MonteCarlo(samples=np.array(results), seed=seed)


@dataclasses.dataclass(frozen=True)
class Sensitivities:
    """values[name]: d ln f / d ln p, shape (cases, n_modes); first-order sd of ln f."""

    names: tuple[str, ...]
    values: dict[str, np.ndarray]
    sd_ln_f: np.ndarray

    def __post_init__(self):
        if set(self.values) != set(self.names):
            raise ValueError(f"Sensitivities.values has {sorted(self.values)}, expected "
                             f"{sorted(self.names)}")
        for name in self.names:
            check_shape("Sensitivities", f"values[{name!r}]", self.values[name],
                        np.shape(self.sd_ln_f))

    def ranked(self) -> list[tuple[str, float]]:
        """(name, max |S| over cases and modes), largest first."""
        return sorted(((n, float(np.nanmax(np.abs(self.values[n])))) for n in self.names),
                      key=lambda item: -item[1])


def sensitivities(paths, base_overrides: dict, inputs: Inputs, n_modes: int = 4,
                  elements: int | None = None, n_jobs: int = -1,
                  show_progress: bool = False) -> Sensitivities:
    """Central differences of ``studies.calibration.derivatives`` at the nominal inputs, every evaluation
    in one parallel pool, and the first-order sd of ln f they give."""
    names = tuple(sorted(inputs.nominal))
    tasks = [(tuple(paths), base_overrides, inputs, values, n_modes, elements)
             for values in central_points(inputs.nominal, names)]
    results = run_tasks(evaluate, tasks, n_jobs=n_jobs, show_progress=show_progress, label="sensitivity evaluations")
    values = central_log_slopes(results, names)
    return Sensitivities(names=names, values=values,
                         sd_ln_f=first_order_sd(values, inputs.nominal, inputs.sd))
