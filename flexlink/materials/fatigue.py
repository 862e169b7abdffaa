"""The stress-life (S-N) curve of a metal part: the specimen's Basquin line from the material
data, the Marin factors of the part, and the mean-stress corrections.

Specimen (rotating-beam, polished) line, Basquin: sigma_a = sigma_f' (2 N)^b, with the
endurance limit Se' at N_e = 1e6 cycles. A material file gives two of (Se', sigma_f', b)
(``materials.strength``); the third follows from sigma_f' (2 N_e)^b = Se'.

Part (Marin): Se = ka kb kc kd ke Se' (Shigley's Mechanical Engineering Design, 9th ed.,
sec. 6-9, eqs. 6-18 to 6-29, Sut in MPa, d in mm):
    ka = a Sut^e                surface: ground (1.58, -0.085), machined or cold-drawn
                                (4.51, -0.265), hot-rolled (57.7, -0.718), as-forged (272, -0.995)
    kb = 1.24 d^-0.107          size, bending, 2.79 <= d <= 51 mm; 1.51 d^-0.157 to 254 mm;
                                1 below 2.79 mm and for axial loading; a non-rotating
                                rectangle b x h has d_e = 0.808 sqrt(b h)
    kc = 1 bending, 0.85 axial, 0.59 torsion
    kd = 0.975 + 0.432e-3 T - 0.115e-5 T^2 + 0.104e-8 T^3 - 0.595e-12 T^4, T in deg F
         (70 to 1000 F; 1 below 70 F, the room-temperature datum)
    ke = 1 - 0.08 z_a, z_a the standard normal variate of the reliability (0.814 at 99 %)
The part's line runs from (1e3, f Sut) to (N_e, Se), f = sigma_f' (2e3)^b / Sut the specimen's
fraction of Sut at 1e3 cycles (Shigley eqs. 6-13 to 6-16):
    S = a N^B,  a = (f Sut)^2 / Se,  B = -log10(f Sut / Se) / 3,  N = (sigma_ar / a)^(1 / B)
and a fully reversed amplitude below Se lasts indefinitely (steels; the line is not extended
below Se).

The mean-stress corrections and the counting of cycles are ``analysis.fatigue``'s.
"""

from __future__ import annotations

import dataclasses
import enum
import math
from statistics import NormalDist

import numpy as np

from flexlink.errors import InputError
from flexlink.materials.strength import Strength

MPA = 1e6
ENDURANCE_CYCLES = 1e6  # N_e
LOW_CYCLES = 1e3  # where the part's line starts (f Sut)


class Surface(enum.StrEnum):
    GROUND = "ground"
    MACHINED = "machined"  # or cold-drawn
    HOT_ROLLED = "hot-rolled"
    AS_FORGED = "as-forged"


SURFACE = {Surface.GROUND: (1.58, -0.085), Surface.MACHINED: (4.51, -0.265),
           Surface.HOT_ROLLED: (57.7, -0.718), Surface.AS_FORGED: (272.0, -0.995)}


class LoadType(enum.StrEnum):
    BENDING = "bending"
    AXIAL = "axial"
    TORSION = "torsion"


LOAD_FACTOR = {LoadType.BENDING: 1.0, LoadType.AXIAL: 0.85, LoadType.TORSION: 0.59}


def surface_factor(Sut: float, surface: Surface) -> float:
    """ka [-] of a surface finish for an ultimate strength Sut [Pa]."""
    a, e = SURFACE[Surface(surface)]
    return min(1.0, a * (Sut / MPA) ** e)


def size_factor(diameter: float, load: LoadType) -> float:
    """kb [-] for an (equivalent) diameter [m] under ``load``."""
    d = diameter * 1e3
    if LoadType(load) is LoadType.AXIAL or d < 2.79:
        return 1.0
    return 1.24 * d**-0.107 if d <= 51.0 else 1.51 * d**-0.157


def rectangle_diameter(width: float, depth: float) -> float:
    """d_e [m] of a non-rotating rectangle width x depth [m] in bending: 0.808 sqrt(b h)."""
    return 0.808 * math.sqrt(width * depth)


def temperature_factor(celsius: float) -> float:
    """kd [-] at ``celsius``; 1 at and below room temperature (70 F), refused above 1000 F."""
    T = celsius * 9.0 / 5.0 + 32.0
    if T > 1000.0:
        raise InputError(f"{celsius:g} C is above the Marin temperature fit (1000 F = 538 C)",
                         field="--temperature", expected="a temperature up to 538 C")
    if T <= 70.0:
        return 1.0
    return 0.975 + 0.432e-3 * T - 0.115e-5 * T**2 + 0.104e-8 * T**3 - 0.595e-12 * T**4


def reliability_factor(reliability: float) -> float:
    """ke = 1 - 0.08 z_a [-] for a reliability in (0, 1) (z_a the standard normal variate)."""
    if not (isinstance(reliability, (int, float)) and 0.0 < reliability < 1.0):
        raise InputError(f"got {reliability!r}", field="--reliability",
                         expected="a probability strictly between 0 and 1, e.g. 0.99")
    return 1.0 - 0.08 * NormalDist().inv_cdf(reliability)


@dataclasses.dataclass(frozen=True)
class Marin:
    """The Marin factors [-] of a part: surface ka, size kb, load kc, temperature kd,
    reliability ke."""

    ka: float
    kb: float
    kc: float
    kd: float
    ke: float

    def __post_init__(self):
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if not (math.isfinite(value) and 0.0 < value <= 1.5):
                raise ValueError(f"Marin factor {f.name} = {value!r} outside (0, 1.5]")

    @property
    def product(self) -> float:
        return self.ka * self.kb * self.kc * self.kd * self.ke


def marin_factors(Sut: float, surface: Surface, diameter: float, load: LoadType,
                  celsius: float, reliability: float) -> Marin:
    """The Marin factors of a part of ultimate strength Sut [Pa], (equivalent) diameter [m]."""
    return Marin(surface_factor(Sut, surface), size_factor(diameter, load),
                 LOAD_FACTOR[LoadType(load)], temperature_factor(celsius),
                 reliability_factor(reliability))


@dataclasses.dataclass(frozen=True)
class SpecimenCurve:
    """The specimen's line: Sut, Sy [Pa], endurance limit Se' [Pa] at ``ENDURANCE_CYCLES``,
    Basquin coefficient sigma_f' [Pa] and exponent b [-]."""

    Sut: float
    Sy: float
    endurance: float
    coefficient: float
    exponent: float

    @property
    def fraction(self) -> float:
        """f = sigma_f' (2e3)^b / Sut: the fraction of Sut at 1e3 cycles [-]."""
        return self.coefficient * (2.0 * LOW_CYCLES) ** self.exponent / self.Sut


def specimen_curve(strength: Strength) -> SpecimenCurve:
    """The specimen's line from a material's ``[strength]``: Sut and Sy, and two of
    endurance_limit, fatigue_coefficient and fatigue_exponent (the third from
    sigma_f' (2 N_e)^b = Se'); an InputError naming the file and key where one is missing."""
    why = "a fatigue life"
    Sut, Sy = strength.need("Sut", why).value, strength.need("Sy", why).value
    if Sy > Sut:
        raise InputError(f"Sy = {Sy / MPA:.4g} MPa is above Sut = {Sut / MPA:.4g} MPa",
                         source=strength.path, field="strength.Sy", expected="Sy <= Sut")
    given = {k: strength.get(k) for k in ("endurance_limit", "fatigue_coefficient",
                                          "fatigue_exponent")}
    Se, sf, b = (d.value if d is not None else None for d in given.values())
    twice = 2.0 * ENDURANCE_CYCLES
    if sf is None:
        strength.need("fatigue_coefficient", why + " (with endurance_limit or fatigue_exponent)")
    if Se is None and b is None:
        strength.need("endurance_limit", why + " (or fatigue_exponent)")
    if b is None:
        b = math.log(Se / sf) / math.log(twice)
    if Se is None:
        Se = sf * twice**b
    curve = SpecimenCurve(Sut=Sut, Sy=Sy, endurance=Se, coefficient=sf, exponent=b)
    if not 0.0 < curve.endurance < curve.fraction * Sut <= sf:
        raise InputError(f"the S-N data do not make a falling line: Se' = {Se / MPA:.4g} MPa, "
                         f"f Sut = {curve.fraction * Sut / MPA:.4g} MPa, sigma_f' = "
                         f"{sf / MPA:.4g} MPa", source=strength.path, field="strength",
                         expected="0 < Se' < f Sut <= sigma_f'")
    return curve


@dataclasses.dataclass(frozen=True)
class PartCurve:
    """The part's S-N line S = a N^B from (1e3, f Sut) to (N_e, Se) [Pa], Se = Marin Se'."""

    specimen: SpecimenCurve
    marin: Marin

    @property
    def endurance(self) -> float:
        """Se [Pa], the part's endurance limit."""
        return self.marin.product * self.specimen.endurance

    @property
    def coefficient(self) -> float:
        """a [Pa]."""
        return (self.specimen.fraction * self.specimen.Sut) ** 2 / self.endurance

    @property
    def exponent(self) -> float:
        """B [-]."""
        return -math.log10(self.specimen.fraction * self.specimen.Sut / self.endurance) / 3.0

    def cycles(self, amplitude) -> np.ndarray:
        """N [cycles] to failure at fully reversed amplitudes [Pa]; inf below Se."""
        s = np.asarray(amplitude, dtype=float)
        with np.errstate(divide="ignore"):
            n = (np.maximum(s, 1e-300) / self.coefficient) ** (1.0 / self.exponent)
        return np.where(s < self.endurance, np.inf, n)

    def strength_at(self, cycles: float) -> float:
        """The fully reversed strength [Pa] at a life of ``cycles``: Se from N_e on."""
        if cycles >= ENDURANCE_CYCLES:
            return self.endurance
        return self.coefficient * max(cycles, 1.0) ** self.exponent
