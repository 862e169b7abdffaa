"""From a stress history over one crank turn to fatigue: rainflow cycles, mean-stress
correction, life against the part's S-N line (``materials.fatigue``) and safety factors.

Counting: the history repeats every turn, so it is rotated to start (and, closed, to end) at its
largest value; the rainflow cycles (``fatpack.find_rainflow_cycles``) of that closed sequence's
turning points and of its residue joined to itself (``fatpack.concatenate_reversals``) are the
cycles of one turn, all full cycles (a sine gives one cycle of its range). The turning points
are the samples themselves (``turning_points``), not fatpack's ``find_reversals``, which
snaps them to load classes and may take a sample beside a flat peak (an amplitude error of
1e-4 on a sine of 360 samples). fatpack is used (not pylife): it is numpy only
and small, and it has the counting, the Goodman, Morrow and SWT corrections; pylife also works
on Python 3.11 but brings pandas and h5py (1.5 s to import) and corrects mean stress by the
FKM's mean-stress sensitivity, not by Sut (docs/life.md).

Mean-stress corrections give the fully reversed amplitude sigma_ar equivalent to a cycle of
amplitude sigma_a about mean sigma_m (MeanStress):
    Goodman  sigma_ar = sigma_a / (1 - sigma_m / Sut)
    Gerber   sigma_ar = sigma_a / (1 - (sigma_m / Sut)^2)
    Morrow   sigma_ar = sigma_a / (1 - sigma_m / sigma_f')
    SWT      sigma_ar = sqrt(sigma_max sigma_a), sigma_max = sigma_m + sigma_a (0 if <= 0)
and for a compressive mean (sigma_m < 0) the first three take sigma_ar = sigma_a: no credit for
compression (Shigley, sec. 6-12). The fatigue safety factor n scales the cycle (sigma_a,
sigma_m) proportionally until its sigma_ar reaches the strength S (Se, or the strength at a
required life): Goodman 1 / (sigma_a / S + sigma_m / Sut), Gerber the root of
n sigma_a / S + (n sigma_m / Sut)^2 = 1, Morrow as Goodman with sigma_f', SWT S / sigma_ar.

Damage per turn D = sum over cycles of 1 / N(sigma_ar) (Palmgren-Miner, cycles below the
part's endurance limit doing none); life = 1 / D turns. The safety factor of a history is that
of its worst cycle, against the endurance limit Se or, given a required life, against the
strength at that life; the first-cycle yield factor is Sy / max |sigma|.
"""

from __future__ import annotations

import dataclasses
import enum

import numpy as np

from flexlink.materials.fatigue import PartCurve, SpecimenCurve

class MeanStress(enum.StrEnum):
    GOODMAN = "goodman"
    GERBER = "gerber"
    MORROW = "morrow"
    SWT = "swt"


@dataclasses.dataclass(frozen=True)
class Cycles:
    """The rainflow cycles of one turn: amplitude and mean [Pa] (c,), one count each."""

    amplitude: np.ndarray
    mean: np.ndarray


def turning_points(y: np.ndarray) -> np.ndarray:
    """The values of ``y`` (m,) where it turns (its first and last values included), exact:
    the samples where the sign of its slope changes, flat stretches skipped."""
    slope = np.diff(y)
    moving = np.flatnonzero(slope != 0.0)
    keep = [0]
    turns = moving[1:][np.sign(slope[moving[1:]]) != np.sign(slope[moving[:-1]])]
    keep.extend(turns.tolist())
    keep.append(len(y) - 1)
    return y[np.array(keep)]


def turn_cycles(history) -> Cycles:
    """The rainflow cycles of one turn of the periodic ``history`` (samples,) [Pa]."""
    import fatpack

    y = np.asarray(history, dtype=float)
    if y.ndim != 1 or len(y) < 2:
        raise ValueError(f"a history over one turn, (samples,) with samples >= 2, got {y.shape}")
    y = np.roll(y, -int(np.argmax(y)))
    y = np.append(y, y[0])
    if not y.max() > y.min():
        return Cycles(np.zeros(0), np.zeros(0))
    reversals = turning_points(y)
    cycles, residue = fatpack.find_rainflow_cycles(reversals)
    if len(residue) >= 3:
        repeated, _ = fatpack.find_rainflow_cycles(fatpack.concatenate_reversals(residue,
                                                                                 residue))
        cycles = np.concatenate([np.reshape(cycles, (-1, 2)), np.reshape(repeated, (-1, 2))])
    cycles = np.reshape(cycles, (-1, 2))
    return Cycles(np.abs(cycles[:, 1] - cycles[:, 0]) / 2.0, cycles.mean(axis=1))


def equivalent_amplitude(amplitude, mean, curve: SpecimenCurve,
                         method: MeanStress = MeanStress.GOODMAN) -> np.ndarray:
    """sigma_ar [Pa] of cycles of ``amplitude`` and ``mean`` [Pa] (module docstring)."""
    import fatpack

    sa, sm = np.broadcast_arrays(np.asarray(amplitude, float), np.asarray(mean, float))
    method = MeanStress(method)
    out = sa.astype(float).copy()
    tension = sm > 0.0
    if method is MeanStress.SWT:
        peak = sm + sa
        live = peak > 0.0
        out = np.zeros_like(out)
        if live.any():  # fatpack works on ranges: S = 2 sigma_a
            out[live] = fatpack.find_swt_equivalent_stress(2 * sa[live], sm[live]) / 2.0
        return out
    if method is MeanStress.GERBER:  # not in fatpack
        out[tension] = sa[tension] / (1.0 - (sm[tension] / curve.Sut) ** 2)
    else:
        ultimate = curve.Sut if method is MeanStress.GOODMAN else curve.coefficient
        out[tension] = fatpack.find_morrow_equivalent_stress(2 * sa[tension], sm[tension],
                                                             ultimate) / 2.0
    beyond = tension & (sm >= (curve.Sut if method is not MeanStress.MORROW
                               else curve.coefficient))
    out[beyond] = np.inf  # the mean alone breaks it
    return out


def safety_factor(amplitude, mean, strength: float, curve: SpecimenCurve,
                  method: MeanStress = MeanStress.GOODMAN) -> np.ndarray:
    """n [-] scaling (sigma_a, sigma_m) until sigma_ar reaches ``strength`` S [Pa] (module
    docstring); inf for a cycle with nothing alternating or compressive only (SWT)."""
    sa, sm = np.broadcast_arrays(np.asarray(amplitude, float), np.asarray(mean, float))
    method = MeanStress(method)
    tm = np.maximum(sm, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        if method is MeanStress.SWT:
            n = strength / equivalent_amplitude(sa, sm, curve, method)
        elif method is MeanStress.GERBER:
            x, y = sa / strength, tm / curve.Sut  # n x + n^2 y^2 = 1
            n = np.where(y > 0, (-x + np.sqrt(x * x + 4 * y * y)) / (2 * y * y), 1.0 / x)
        else:
            ultimate = curve.Sut if method is MeanStress.GOODMAN else curve.coefficient
            n = 1.0 / (sa / strength + tm / ultimate)
    return np.where(np.isnan(n), np.inf, n)


@dataclasses.dataclass(frozen=True)
class Fatigue:
    """The fatigue of one stress history over a turn: damage per turn [-], life [turns] (inf:
    every cycle below the endurance limit), safety factor [-] of the worst cycle against
    ``strength`` [Pa] (Se, or the strength at the required life), that cycle's amplitude,
    mean and equivalent fully reversed amplitude [Pa], the yield factor Sy / max |sigma| [-]
    and the number of cycles per turn."""

    damage: float
    life: float
    safety: float
    strength: float
    amplitude: float
    mean: float
    equivalent: float
    yield_safety: float
    cycles: int


def history_fatigue(history, part: PartCurve, method: MeanStress = MeanStress.GOODMAN,
                    required_cycles: float | None = None) -> Fatigue:
    """``Fatigue`` of one turn of ``history`` (samples,) [Pa] on the part's S-N line; the
    safety factor against the endurance limit, or against the strength at
    ``required_cycles`` (a required life in cycles) when given."""
    counted = turn_cycles(history)
    specimen = part.specimen
    strength = part.endurance if required_cycles is None else part.strength_at(required_cycles)
    peak = float(np.abs(history).max())
    yield_safety = specimen.Sy / peak if peak > 0 else np.inf
    if len(counted.amplitude) == 0:
        return Fatigue(0.0, np.inf, np.inf, strength, 0.0, float(np.mean(history)), 0.0,
                       yield_safety, 0)
    equivalent = equivalent_amplitude(counted.amplitude, counted.mean, specimen, method)
    damage = float((1.0 / part.cycles(equivalent)).sum())
    factors = safety_factor(counted.amplitude, counted.mean, strength, specimen, method)
    worst = int(np.argmin(factors))
    return Fatigue(damage=damage, life=1.0 / damage if damage > 0 else np.inf,
                   safety=float(factors[worst]), strength=strength,
                   amplitude=float(counted.amplitude[worst]), mean=float(counted.mean[worst]),
                   equivalent=float(equivalent[worst]), yield_safety=yield_safety,
                   cycles=len(counted.amplitude))
