"""Campbell diagram of a linkage: each tracked mode's frequency band over the crank cycle
against crank speed, the crank harmonics n x speed, and the speeds where a harmonic comes near
a band.

A linkage's natural frequencies change with the pose, not with the speed (the model has no
centrifugal or Coriolis terms), so a mode is a horizontal band [f_min, f_max] over the cycle.
Harmonic n at crank speed Omega [rad/s] is f_n = n Omega / (2 pi). With the relative margin m
of the resonance check (|f - f_n| <= m f, ``cycle.resonances``), harmonic n is critical for a
mode wherever f_n lies in [f_min (1 - m), f_max (1 + m)], i.e. for
    Omega in [2 pi f_min (1 - m) / n, 2 pi f_max (1 + m) / n],
cut to the speed range asked for. When nothing is critical, the nearest margin is the smallest
relative gap |f - f_n| / f between a harmonic line and a band edge over the speed range.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexlink.errors import InputError
from flexlink.units import rev_per_min



@dataclasses.dataclass(frozen=True)
class Band:
    """Tracked mode ``mode`` (1-based) spans [low, high] [Hz] over the cycle."""

    mode: int
    low: float
    high: float


@dataclasses.dataclass(frozen=True)
class CriticalSpeed:
    """Harmonic ``harmonic`` is within the margin of mode ``mode``'s band for crank speeds
    [low, high] [rad/s]."""

    mode: int
    harmonic: int
    low: float
    high: float


@dataclasses.dataclass(frozen=True)
class NearestMargin:
    """The smallest relative gap ``gap`` between harmonic ``harmonic`` and mode ``mode``'s band,
    reached at crank speed ``speed`` [rad/s]."""

    mode: int
    harmonic: int
    gap: float
    speed: float


def bands(frequencies: np.ndarray, to_zero=()) -> list[Band]:
    """One band per column of ``frequencies`` (poses, lines) [Hz]. Lines ``to_zero`` (1-based)
    turn into a mechanism mode at a singular pose (``tracking.vanishing_lines``): near it their
    frequency falls to 0 Hz between the sampled poses, so their band starts at 0."""
    f = np.asarray(frequencies, dtype=float)
    if not np.isfinite(f).all():
        raise InputError("a tracked mode is missing at some pose: its band is not known",
                         field="modes", expected="fewer modes (-n) or a finer mesh")
    return [Band(j + 1, 0.0 if j + 1 in to_zero else float(f[:, j].min()), float(f[:, j].max()))
            for j in range(f.shape[1])]


def _check_speeds(speeds: tuple[float, float]) -> tuple[float, float]:
    low, high = speeds
    if not (0 <= low < high and math.isfinite(high)):
        raise InputError(f"speed range {rev_per_min(low):g}:{rev_per_min(high):g} rev/min", field="speeds",
                         expected="0 <= low < high, finite")
    return low, high


def critical_speeds(found: list[Band], speeds: tuple[float, float], margin: float = 0.05,
                    harmonics: int = 10) -> list[CriticalSpeed]:
    """Crank speed ranges [rad/s] within ``speeds`` (low, high) where harmonic n = 1 ...
    ``harmonics`` is within ``margin`` (relative) of a mode's band, by mode then harmonic."""
    low, high = _check_speeds(speeds)
    out = []
    for band in found:
        for n in range(1, harmonics + 1):
            a = 2 * math.pi * band.low * (1 - margin) / n
            b = 2 * math.pi * band.high * (1 + margin) / n
            if a <= high and b >= low:
                out.append(CriticalSpeed(band.mode, n, max(a, low), min(b, high)))
    return out


def nearest_margin(found: list[Band], speeds: tuple[float, float],
                   harmonics: int = 10) -> NearestMargin | None:
    """The smallest relative gap |f - f_n| / f (f the nearer band edge) between a harmonic
    line and a band over ``speeds`` [rad/s]; 0 where a line enters a band."""
    low, high = _check_speeds(speeds)
    best = None
    for band in found:
        for n in range(1, harmonics + 1):
            f_low, f_high = n * low / (2 * math.pi), n * high / (2 * math.pi)
            if f_high < band.low:
                gap, speed = (band.low - f_high) / band.low, high
            elif f_low > band.high:
                gap, speed = (f_low - band.high) / band.high, low
            else:
                gap = 0.0
                speed = max(low, 2 * math.pi * band.low / n)
            if best is None or gap < best.gap:
                best = NearestMargin(band.mode, n, gap, speed)
    return best


def nearest_harmonic(frequencies: np.ndarray, crank_speed: float,
                     harmonics: int = 10) -> tuple[float, int, int]:
    """(smallest relative gap |f - f_n| / f over the cycle, mode, harmonic) of harmonics
    n = 1 ... ``harmonics`` of ``crank_speed`` [rad/s] to the lines ``frequencies`` (poses,
    modes) [Hz]: how far the nearest one is when none is within the margin."""
    f = np.asarray(frequencies, dtype=float)
    n = np.arange(1, harmonics + 1)[:, None, None]
    gap = np.abs(f[None] - n * crank_speed / (2 * math.pi)) / f[None]
    h, _, j = np.unravel_index(np.nanargmin(gap), gap.shape)
    return float(np.nanmin(gap)), int(j) + 1, int(h) + 1
