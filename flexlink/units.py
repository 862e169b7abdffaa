"""Quantities with explicit units, as written in scene and material files.

Every dimensional value in a file is a string such as ``"300 mm"`` or ``"201 GPa"``; a bare
number is refused, so a length in millimetres can never be read as metres. Values are
converted to SI on reading and SI is used everywhere inside flexlink.
"""

from __future__ import annotations

import math
import re

import numpy as np

from flexlink.errors import InputError

RPM = 2 * math.pi / 60.0  # [rad/s] per rev/min: the one definition of the factor

# dimension -> {unit spelling: factor to SI}
UNITS: dict[str, dict[str, float]] = {
    "length": {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "in": 0.0254},
    "modulus": {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9, "N/m^2": 1.0, "N/mm^2": 1e6},
    "density": {"kg/m^3": 1.0, "g/cm^3": 1e3},
    "translational stiffness": {"N/m": 1.0, "kN/m": 1e3, "MN/m": 1e6, "N/mm": 1e3, "kN/mm": 1e6},
    "rotational stiffness": {"N*m/rad": 1.0, "N m/rad": 1.0, "Nm/rad": 1.0, "N*mm/rad": 1e-3,
                             "kN*m/rad": 1e3},
    "angle": {"deg": math.pi / 180.0, "rad": 1.0},
    "mass": {"kg": 1.0, "g": 1e-3},
    "rotary inertia": {"kg*m^2": 1.0, "kg m^2": 1.0, "g*cm^2": 1e-7},
    "area": {"m^2": 1.0, "mm^2": 1e-6, "cm^2": 1e-4},
    "second moment": {"m^4": 1.0, "mm^4": 1e-12, "cm^4": 1e-8},
    "frequency": {"Hz": 1.0, "kHz": 1e3},
    "angular speed": {"rad/s": 1.0, "rev/min": RPM, "rpm": RPM,
                      "rev/s": 2 * math.pi, "Hz": 2 * math.pi},  # Hz: turns per second
    "angular acceleration": {"rad/s^2": 1.0, "rev/s^2": 2 * math.pi},
    "torque": {"N*m": 1.0, "N m": 1.0, "Nm": 1.0, "N*mm": 1e-3},
    "force": {"N": 1.0, "kN": 1e3},
}

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_QUANTITY = re.compile(rf"^\s*({_NUMBER})\s*(.*?)\s*$")
_NOT_FINITE = re.compile(r"^\s*([-+]?(?:inf(?:inity)?|nan))\b", re.IGNORECASE)


def parse_quantity(text: object, dimension: str, *, source: str | None = None,
                   field: str | None = None) -> float:
    """Convert ``"0.3 m"``-style text to a float in SI units of ``dimension``.

    The special word ``"rigid"`` gives ``math.inf`` (only meaningful for stiffness).
    """
    table = UNITS[dimension]
    spellings = ", ".join(table)
    article = "an" if dimension[0] in "aeiou" else "a"
    expected = f"{article} {dimension} as a string with a unit, one of: {spellings}; e.g. '1 {next(iter(table))}'"
    if isinstance(text, bool) or not isinstance(text, str):
        raise InputError(f"got {text!r} without a unit", source=source, field=field,
                         expected=expected)
    if text.strip().lower() == "rigid" and "stiffness" in dimension:
        return math.inf
    match = _QUANTITY.match(text)
    if not match:
        word = _NOT_FINITE.match(text)
        if word:  # "inf rev/min": float() reads the word, the number pattern does not
            raise InputError(f"{word.group(1)} is not a finite number", source=source,
                             field=field, expected=expected)
        raise InputError(f"cannot read {text!r} as a number with a unit", source=source,
                         field=field, expected=expected)
    number, unit = float(match.group(1)), match.group(2)
    if not math.isfinite(number):  # e.g. "1e400": overflows to inf, never silently "rigid"
        raise InputError(f"{match.group(1)} is not a finite number", source=source, field=field,
                         expected=expected + ("; write 'rigid' for an infinitely stiff joint"
                                              if "stiffness" in dimension else ""))
    if unit not in table:
        other = [d for d, t in UNITS.items() if unit in t]
        hint = f"; '{unit}' is a unit of {other[0]}, not of {dimension}" if other else ""
        raise InputError(f"unknown unit {unit!r} in {text!r}{hint}", source=source, field=field,
                         expected=expected)
    return number * table[unit]


def parse_range(text: object, dimension: str, *, source: str | None = None,
                field: str | None = None) -> tuple[float, float]:
    """``"LOW:HIGH"`` with units -> (low, high) in SI units of ``dimension``: each end a
    quantity (``parse_quantity``), e.g. ``"100 mm:1 m"``; a low end written as a bare number
    takes the high end's unit (``"0:3000 rev/min"``). The one range syntax of every option."""
    parts = text.split(":") if isinstance(text, str) else []
    if len(parts) != 2:
        example = f"1:10 {next(iter(UNITS[dimension]))}"
        raise InputError(f"cannot read {text!r} as a range", source=source, field=field,
                         expected=f"LOW:HIGH with units, e.g. '{example}'")
    low, high = (p.strip() for p in parts)
    low_read, high_read = _QUANTITY.match(low), _QUANTITY.match(high)
    if low_read and not low_read.group(2) and high_read and high_read.group(2):
        low = f"{low} {high_read.group(2)}"
    # the high end first: a bare low end takes its unit, so an unreadable high end is the fault
    upper = parse_quantity(high, dimension, source=source, field=field)
    return parse_quantity(low, dimension, source=source, field=field), upper


ROUND_TRIP_ULPS = 8  # a value this close to a 12-digit decimal is that decimal


def rev_per_min(omega):
    """An angular speed ``omega`` [rad/s] (a number or an array) in rev/min; a value within
    ROUND_TRIP_ULPS of a decimal of 12 significant digits is that decimal: a speed given in
    rev/min comes back as written (2900, not the 2900.0000000000005 of the round trip through
    rad/s), any other keeps every digit."""
    return as_written(np.asarray(omega, dtype=float) / RPM)


def degrees_in_turn(angle):
    """An angle [rad] (a number or an array) in degrees in [0, 360), as written where it is
    within ROUND_TRIP_ULPS of a 12-digit decimal (a grid angle of 19 deg, not
    18.999999999999996)."""
    return as_written(np.degrees(np.asarray(angle, dtype=float)) % 360.0)


def as_written(values):
    """``values`` (a number or an array), each within ROUND_TRIP_ULPS of a decimal of 12
    significant digits replaced by that decimal, any other unchanged."""
    values = np.asarray(values, dtype=float)
    short = np.array([float(f"{v:.12g}") for v in values.ravel()]).reshape(values.shape)
    near = np.abs(short - values) <= ROUND_TRIP_ULPS * np.spacing(np.abs(values))
    out = np.where(near, short, values)
    return float(out) if out.ndim == 0 else out


def percent_error(computed, reference):
    """100 (computed - reference) / reference [%]: scalars or arrays (element by element)."""
    return 100.0 * (computed - reference) / reference


# a number with a non-zero digit before its exponent: > 0 when unsigned (no look-ahead, which
# the editors' regular expressions may lack)
_POSITIVE = r"\+?(?:0*[1-9]\d*\.?\d*|0*\.0*[1-9]\d*)(?:[eE][-+]?\d+)?"


def quantity_pattern(dimension: str, *, signed: bool = True, positive: bool = False,
                     words: tuple[str, ...] = ()) -> str:
    """A regular expression for text ``parse_quantity`` reads as ``dimension``: a number then
    one of the dimension's units (for editors' JSON Schema). ``signed=False`` refuses a minus
    sign (a quantity that must not be negative), ``positive=True`` zero as well; ``words`` are
    whole-value alternatives such as "rigid"."""
    number = (_POSITIVE if positive else _NUMBER if signed
              else _NUMBER.replace("[-+]?", r"\+?", 1))
    units = "|".join(re.escape(u).replace(r"\ ", " ")
                     for u in sorted(UNITS[dimension], key=len, reverse=True))
    alternatives = [rf"\s*{number}\s*(?:{units})\s*"] + [rf"\s*{w}\s*" for w in words]
    return "^(?:" + "|".join(alternatives) + ")$"
