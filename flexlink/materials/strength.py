"""Strength data of a material file: the ``[strength]`` table, each value with the range it
comes in and its source.

An isotropic metal (``materials/aisi_1080.toml``):

    [strength]
    Sut = { mean = "1300 MPa", low = "1170 MPa", high = "1440 MPa", source = "..." }
    Sy = { mean = "980 MPa", low = "880 MPa", high = "1080 MPa", source = "..." }
    endurance_limit = { mean = "650 MPa", ..., source = "..." }       # Se' of the specimen
    fatigue_coefficient = { mean = "1645 MPa", ..., source = "..." }  # sigma_f' (Basquin)
    fatigue_exponent = { mean = -0.085, low = -0.12, high = -0.05, source = "..." }  # b

Sut and Sy are required, and for a life two of endurance_limit, fatigue_coefficient and
fatigue_exponent (``materials.fatigue.specimen_curve`` says how each pair defines the S-N
line). A constituent of a composite (fibre, matrix) gives ``tensile_strength`` and
``compressive_strength``, the matrix also ``shear_strength``; ``materials.laminate`` turns them
into ply strengths. A datum that a result needs and the file does not give is an InputError
naming the file and the key: flexlink never assumes a strength.
"""

from __future__ import annotations

import dataclasses
import math
import tomllib

from flexlink.errors import InputError
from flexlink.materials.mixtures import material_path
from flexlink.units import parse_quantity

STRESS_KEYS = ("Sut", "Sy", "endurance_limit", "fatigue_coefficient", "tensile_strength",
               "compressive_strength", "shear_strength")
EXPONENT_KEY = "fatigue_exponent"


@dataclasses.dataclass(frozen=True)
class Datum:
    """One strength value [Pa] (an exponent: [-]) with its range (low <= value <= high) and
    source."""

    value: float
    low: float
    high: float
    source: str

    def __post_init__(self):
        if not (math.isfinite(self.value) and self.low <= self.value <= self.high):
            raise ValueError(f"need low <= value <= high, got {self.low}, {self.value}, "
                             f"{self.high}")


@dataclasses.dataclass(frozen=True)
class Strength:
    """The ``[strength]`` table of material file ``path``: datum name -> Datum."""

    path: str
    data: dict[str, Datum]

    def get(self, key: str) -> Datum | None:
        return self.data.get(key)

    def need(self, key: str, why: str) -> Datum:
        """The datum ``key``, else an InputError naming the file and ``strength.<key>``."""
        datum = self.data.get(key)
        if datum is None:
            raise InputError(f"missing, needed for {why}; flexlink never assumes a strength",
                             source=self.path, field=f"strength.{key}",
                             expected="{ mean = '... MPa', low = '...', high = '...', "
                                      "source = '...' }")
        return datum


def load_strength(name_or_path: str) -> Strength:
    """The ``[strength]`` table of the shipped material ``<name>`` or of a .toml path (an
    empty one if the file has none: what is missing is refused where it is needed)."""
    path = material_path(str(name_or_path))
    src = str(path)
    if not path.is_file():
        raise InputError(f"no material file {src}", field="material")
    with path.open("rb") as fh:
        table = tomllib.load(fh).get("strength", {})
    if not isinstance(table, dict):
        raise InputError(f"got {table!r}", source=src, field="strength",
                         expected="a [strength] table")
    data = {}
    for key, entry in table.items():
        if key == "source":
            continue
        if key not in STRESS_KEYS + (EXPONENT_KEY,):
            raise InputError(f"unknown key {key!r}", source=src, field=f"strength.{key}",
                             expected=f"one of {', '.join(STRESS_KEYS + (EXPONENT_KEY,))}")
        data[key] = _datum(entry, key, src, str(table.get("source", src)))
    return Strength(src, data)


def _datum(entry, key: str, src: str, default_source: str) -> Datum:
    field = f"strength.{key}"
    if not isinstance(entry, dict) or "mean" not in entry:
        raise InputError(f"got {entry!r}", source=src, field=field,
                         expected="{ mean = ..., low = ..., high = ..., source = '...' }")
    values = {}
    for part in ("mean", "low", "high"):
        raw = entry.get(part, entry["mean"])
        where = f"{field}.{part}"
        if key == EXPONENT_KEY:
            if isinstance(raw, bool) or not isinstance(raw, (int, float)) or not -1 < raw < 0:
                raise InputError(f"got {raw!r}", source=src, field=where,
                                 expected="a plain number in (-1, 0)")
            values[part] = float(raw)
        else:
            values[part] = parse_quantity(raw, "modulus", source=src, field=where)
            if not values[part] > 0:
                raise InputError(f"got {raw!r}", source=src, field=where,
                                 expected="a positive stress, e.g. '500 MPa'")
    if not values["low"] <= values["mean"] <= values["high"]:
        raise InputError(f"mean {entry['mean']!r} outside its range [{entry.get('low')!r}, "
                         f"{entry.get('high')!r}]", source=src, field=field,
                         expected="low <= mean <= high")
    return Datum(values["mean"], values["low"], values["high"],
                 str(entry.get("source", default_source)))
