"""An interim fatigue life of a steel strip from its stress history over one turn: the
stress-life (S-N) estimate of Shigley's Mechanical Engineering Design (ch. 6), kept small and
apart until the fatigue chain of ``studies.life`` (rainflow, mean-stress options, material
files with [strength]) is the one to call.

At each point, one turn is one stress cycle between the history's largest and smallest value
(a history with one maximum and one minimum per turn, as a strip bent back and forth by a
crank-rocker, has exactly that one rainflow cycle; smaller reversals are not counted here):
    sigma_a = (max - min) / 2,  sigma_m = (max + min) / 2
    Goodman's fully reversed equivalent  sigma_ar = sigma_a / (1 - sigma_m / Sut)
The specimen: Se' = 0.5 Sut (steels, Sut <= 1400 MPa; 700 MPa above), sigma_f' = Sut + 345 MPa,
so the fraction of Sut at 10^3 cycles is f = sigma_f' (2 10^3)^b / Sut with
b = log10(Se' / sigma_f') / log10(2 10^6). The part: Se = ka kb kc kd ke Se' with
    ka = 4.51 Sut[MPa]^-0.265 (machined or cold-drawn surface),
    kb = (d_e / 7.62 mm)^-0.107, d_e = 0.808 sqrt(h b) (a non-rotating rectangle h x b in
         bending; 1 below 2.79 mm, where Shigley's fit ends),
    kc = 1 (bending), kd = 1 (room temperature), ke = 1 - 0.08 z (reliability, z its normal
         quantile: 1 at 0.5, 0.814 at 0.99);
and the life  N = (sigma_ar / a)^(1/b'),  a = (f Sut)^2 / Se,  b' = -log10(f Sut / Se) / 3,
infinite when sigma_ar <= Se.
"""

from __future__ import annotations

import dataclasses
import enum
import math

import numpy as np
from scipy.stats import norm

from flexlink.errors import InputError

ENDURANCE_CYCLES = 1e6


@dataclasses.dataclass(frozen=True)
class SteelStrength:
    """Ultimate and yield strength [Pa] of a steel, with where they come from."""

    Sut: float
    Sy: float
    source: str

    def __post_init__(self):
        if not (0 < self.Sy <= self.Sut < 3e9):
            raise InputError(f"need 0 < Sy <= Sut < 3 GPa, got Sy {self.Sy!r}, Sut {self.Sut!r}",
                             source=self.source, field="strength", expected="Pa")


class StripSteel(enum.StrEnum):
    """Steels whose strength ranges this module knows."""

    AISI_1080_QT315 = "aisi-1080-qt315"


# The compliant wiper's strip: AISI 1080, oil quenched and tempered at 315 C (Ashby, CES data):
# the two ends of its published ranges
AISI_1080_QT315 = (
    SteelStrength(1170e6, 880e6, "Ashby (CES): AISI 1080 Q&T 315 C, low end (Sut 1170, Sy 880 MPa)"),
    SteelStrength(1440e6, 1080e6, "Ashby (CES): AISI 1080 Q&T 315 C, high end (Sut 1440, Sy 1080 MPa)"),
)
STRENGTHS = {StripSteel.AISI_1080_QT315: AISI_1080_QT315}


@dataclasses.dataclass(frozen=True)
class StripLife:
    """The worst point's verdict: ``amplitude``, ``mean``, ``equivalent`` (Goodman) and
    ``peak`` (largest |sigma|) [Pa], the part's endurance limit ``endurance`` [Pa], the
    Marin factors, ``cycles`` (inf: below the endurance limit), ``point`` (its column),
    ``yield_margin`` Sy / peak [-] and the strength used."""

    amplitude: float
    mean: float
    equivalent: float
    peak: float
    endurance: float
    marin: dict[str, float]
    cycles: float
    point: int
    yield_margin: float
    strength: SteelStrength


def marin(Sut: float, depth: float, width: float, reliability: float) -> dict[str, float]:
    """The Marin factors (module doc) of a rectangle ``depth`` x ``width`` [m] in bending."""
    if not 0 < reliability < 1:
        raise InputError(f"got {reliability!r}", field="reliability",
                         expected="a probability in (0, 1)")
    d_e = 0.808 * math.sqrt(depth * width) * 1e3  # [mm]
    return {"ka": 4.51 * (Sut / 1e6) ** -0.265,
            "kb": (d_e / 7.62) ** -0.107 if d_e >= 2.79 else 1.0,
            "kc": 1.0, "kd": 1.0,
            "ke": 1.0 - 0.08 * float(norm.ppf(reliability))}


def strip_life(histories, strength: SteelStrength, depth: float, width: float,
               reliability: float = 0.5) -> StripLife:
    """The worst point of ``histories`` (samples over one turn, points) [Pa] (module doc)."""
    s = np.asarray(histories, dtype=float)
    top, bottom = s.max(axis=0), s.min(axis=0)
    amplitude, mean = (top - bottom) / 2, (top + bottom) / 2
    Sut = strength.Sut
    equivalent = amplitude / (1 - mean / Sut)
    factors = marin(Sut, depth, width, reliability)
    specimen = 0.5 * Sut if Sut <= 1400e6 else 700e6
    coefficient = Sut + 345e6
    b = math.log10(specimen / coefficient) / math.log10(2 * ENDURANCE_CYCLES)
    f = coefficient * (2e3) ** b / Sut
    endurance = specimen * math.prod(factors.values())
    a, b_part = (f * Sut) ** 2 / endurance, -math.log10(f * Sut / endurance) / 3
    point = int(np.argmax(equivalent))
    sigma = float(equivalent[point])
    cycles = math.inf if sigma <= endurance else (sigma / a) ** (1 / b_part)
    peak = float(np.abs(s).max())
    return StripLife(float(amplitude[point]), float(mean[point]), sigma, peak, endurance,
                     factors, cycles, point, strength.Sy / peak, strength)
