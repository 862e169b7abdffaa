"""Parametric stability of the running linkage over crank speed (Floquet): the largest
multiplier of the periodic equations (``analysis.periodic``) at each speed of a grid, and the
runs of unstable speeds, each labelled with the nearest parametric resonance or as a
quasi-static divergence."""

from __future__ import annotations

import dataclasses
import enum
from collections.abc import Callable

import numpy as np

from flexlink.analysis.periodic import (ADIABATIC_STEPS, STEP_PHASE, Integrator, PeriodicModel,
                                        multipliers_by)
from flexlink.analysis.runs import true_runs
from flexlink.parallel import on_cluster, run_tasks, workers
from flexlink.studies.array_shapes import check_shape


class RangeKind(enum.StrEnum):
    """What an unstable speed range is: a primary parametric resonance 2 f_i / k, a
    combination resonance (f_i + f_j) / k, or a divergence (K + Omega^2 K2 indefinite)."""

    PRIMARY = "primary"
    COMBINATION = "combination"
    DIVERGENCE = "divergence"


@dataclasses.dataclass(frozen=True)
class InstabilityRange:
    """Adjacent unstable speeds [rad/s] ``low`` <= ``high``, the nearest resonance (``modes``
    1-based: one for a primary resonance, two for a combination, none for a divergence;
    ``harmonic`` k >= 1, 0 for a divergence) and the largest growth rate [1/s]."""

    low: float
    high: float
    modes: tuple[int, ...]
    harmonic: int
    kind: RangeKind
    growth_rate: float

    def __post_init__(self):
        object.__setattr__(self, "kind", RangeKind(self.kind))
        if not self.low <= self.high:
            raise ValueError(f"InstabilityRange.low {self.low} is above high {self.high}")
        count = {RangeKind.PRIMARY: 1, RangeKind.COMBINATION: 2, RangeKind.DIVERGENCE: 0}
        check_shape("InstabilityRange", "modes", self.modes, (count[self.kind],))
        if (self.harmonic == 0) != (self.kind is RangeKind.DIVERGENCE) or self.harmonic < 0:
            raise ValueError(f"InstabilityRange.harmonic {self.harmonic} with kind "
                             f"{self.kind.value}: expected k >= 1, or 0 for a divergence")


@dataclasses.dataclass(frozen=True)
class StabilityMap:
    """Per speed [rad/s]: the largest multiplier modulus [-], growth rate [1/s] and stiffness
    floor [(rad/s)^2] (``PeriodicModel.stiffness_floor``: negative where the frozen frame is
    quasi-statically divergent at some crank angle); integrator: how the monodromies were
    integrated, and ``magnus_fallback`` (bool per speed): where the adiabatic steps were
    refused and the Magnus steps taken instead (fourth-order, or midpoint where those
    would be many: ``periodic.multipliers_by``); ``quasi_static`` (bool per speed): where no
    steps were needed, every frozen mode decaying fast (``periodic.quasi_static_multipliers``:
    the modulus there is an upper bound)."""

    speeds: np.ndarray
    largest_modulus: np.ndarray
    growth_rate: np.ndarray
    ranges: tuple[InstabilityRange, ...]
    stiffness_floor: np.ndarray
    integrator: Integrator
    magnus_fallback: np.ndarray
    quasi_static: np.ndarray | None = None

    def __post_init__(self):
        n = len(self.speeds)
        if self.quasi_static is None:
            object.__setattr__(self, "quasi_static", np.zeros(n, dtype=bool))
        check_shape("StabilityMap", "speeds", self.speeds, (n,))
        for name in ("largest_modulus", "growth_rate", "stiffness_floor", "magnus_fallback",
                     "quasi_static"):
            check_shape("StabilityMap", name, getattr(self, name), (n,))


def stability_map(model: PeriodicModel, speeds: np.ndarray, steps: int = 200,
                  harmonics: int = 6, show_progress: bool = False,
                  step_phase: float = STEP_PHASE,
                  integrator: Integrator = Integrator.ADIABATIC,
                  adiabatic_steps: int = ADIABATIC_STEPS,
                  on_steps: Callable[[int], None] | None = None) -> StabilityMap:
    """The largest Floquet multiplier over ``speeds`` [rad/s]. At zero speed the equations do
    not vary: nothing is parametrically excited, the modulus is 1 and the rate 0 by definition
    (the damped modes decay). The speeds go out in chunks through ``parallel.run_tasks``: in
    this process, or on the dask cluster of ``parallel.use_scheduler`` (each speed is
    computed alone, so the result is the same wherever it runs); ``show_progress``: a bar;
    ``integrator``, ``adiabatic_steps``, ``on_steps`` (progress within a speed, here only,
    not on a cluster): as ``speed_multipliers``."""
    speeds = np.asarray(speeds, dtype=float)
    # on a cluster a few chunks per worker; here one speed a chunk, for the bar
    count = 4 * workers(n_jobs=1) if on_cluster() else len(speeds)
    chunks = np.array_split(np.arange(len(speeds)), max(1, min(len(speeds), count)))
    if on_cluster():
        on_steps = None  # a callback of this process: not sent to the workers
    parts = run_tasks(_speed_chunk, [(model, speeds[c], steps, step_phase, integrator,
                                      adiabatic_steps, on_steps) for c in chunks],
                      n_jobs=1, show_progress=show_progress, label="speed chunks")
    modulus = np.concatenate([p[0] for p in parts])
    rate = np.concatenate([p[1] for p in parts])
    fallback = np.concatenate([p[2] for p in parts])
    quasi = np.concatenate([p[3] for p in parts])
    floor = np.array([model.stiffness_floor(w) for w in speeds])
    return StabilityMap(speeds, modulus, rate,
                        _ranges(model, speeds, modulus, rate, floor, harmonics), floor,
                        integrator, fallback, quasi)


def _speed_chunk(model: PeriodicModel, speeds: np.ndarray, steps: int, step_phase: float,
                 integrator: Integrator, adiabatic_steps: int, on_steps=None):
    """(largest modulus, growth rate, Magnus steps taken for refused adiabatic ones, no steps
    needed: quasi-static) at each of ``speeds`` [rad/s]."""
    modulus, rate = np.ones(len(speeds)), np.zeros(len(speeds))
    fallback, quasi = np.zeros(len(speeds), dtype=bool), np.zeros(len(speeds), dtype=bool)
    for i, speed in enumerate(speeds):
        if speed > 0.0:
            result, used = multipliers_by(model, speed, steps, step_phase, integrator,
                                          adiabatic_steps, on_steps)
            modulus[i], rate[i] = result.largest_modulus, result.growth_rate
            quasi[i] = used is Integrator.QUASI_STATIC
            fallback[i] = used is not integrator and not quasi[i]
    return modulus, rate, fallback, quasi


def _ranges(model, speeds, modulus, rate, floor, harmonics):
    """Runs of unstable speeds, each labelled with the nearest parametric resonance, or as a
    "divergence" (no modes, harmonic 0) when the stiffness is indefinite somewhere in it."""
    out = []
    for a, b in true_runs(modulus > 1.0):
        low, high = speeds[a], speeds[b - 1]
        middle = 0.5 * (low + high) / (2.0 * np.pi)  # rev/s
        modes, k, kind = _nearest(model.checked, middle, harmonics)
        if floor[a:b].min() < 0.0:
            modes, k, kind = (), 0, RangeKind.DIVERGENCE
        out.append(InstabilityRange(float(low), float(high), modes, k, kind,
                                    float(rate[a:b].max())))
    return tuple(out)


def _nearest(frequencies, revolutions, harmonics):
    """The parametric resonance (f_i + f_j) / k nearest ``revolutions`` [rev/s]."""
    best = None
    n = len(frequencies)
    for i in range(n):
        for j in range(i, n):
            for k in range(1, harmonics + 1):
                gap = abs((frequencies[i] + frequencies[j]) / k - revolutions)
                if best is None or gap < best[0]:
                    kind = RangeKind.PRIMARY if i == j else RangeKind.COMBINATION
                    best = (gap, (i + 1,) if i == j else (i + 1, j + 1), k, kind)
    return best[1:]
