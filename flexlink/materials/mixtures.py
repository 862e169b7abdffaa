"""Constituent materials and the rule of mixtures for a woven 0/90 composite laminate.

All values SI: moduli in Pa, density in kg/m^3.

Fabric formula (chosen, and why). A woven 0/90 carbon fabric ply holds equal amounts of fibre
in the two directions. Each ply is modelled as a balanced cross-ply of two unidirectional
layers whose properties come from the rule of mixtures:

    E1   = Vf Ef + (1 - Vf) Em                 (Voigt, along the fibres)
    E2   = 1 / (Vf/Ef + (1 - Vf)/Em)           (Reuss, across the fibres)
    G12  = 1 / (Vf/Gf + (1 - Vf)/Gm)           (Reuss)
    nu12 = Vf nuf + (1 - Vf) num
    rho  = Vf rhof + (1 - Vf) rhom

Classical lamination theory for the balanced 0/90 ply gives in-plane stiffnesses
A11 = A22 = (Q11 + Q22)/2 and A12 = Q12 per unit thickness, with Q11 = E1/(1 - nu12 nu21),
Q22 = E2/(1 - nu12 nu21), Q12 = nu12 Q22. A narrow strip (a link) is free to contract
sideways, so its beam modulus is the reciprocal of the axial compliance:

    E_beam = A11 - A12^2 / A22

Because all five plies are the same balanced fabric, the laminate is homogeneous through the
thickness at ply scale and the flexural modulus equals this in-plane value. With Table I means
and Vf = 0.5: E1 = 101.7 GPa, E2 = 4.74 GPa and E_beam = 53.4 GPa (about (E1 + E2)/2; the
Poisson term changes it by 0.1 %). Waviness (crimp) of the weave would lower it; the paper
gives no crimp data, so none is applied.
"""

from __future__ import annotations

import dataclasses
import enum
import functools
import os
import stat as statmode
import tomllib
from importlib import resources
from importlib.resources.abc import Traversable
from pathlib import Path

from flexlink.choices import parse_choice
from flexlink.errors import InputError
from flexlink.units import parse_quantity



@functools.lru_cache(maxsize=1)
def shipped_materials() -> Traversable:
    """The folder of shipped material files: the package data ``flexlink.materials.data``,
    which pyproject.toml maps from the repository's ``materials/`` folder (in a wheel and in an
    editable install; ``materials/__init__.py`` makes it a package the editable finder maps). A
    source checkout (a ``pyproject.toml`` beside the package) reads its own ``materials/``
    folder: code run from one git worktree with another's editable install must not read the
    other's files."""
    checkout = Path(__file__).resolve().parents[2]
    if (checkout / "pyproject.toml").is_file() and (checkout / "materials").is_dir():
        return checkout / "materials"  # a source checkout: its own files, not another's install
    try:
        return resources.files("flexlink.materials.data")
    except ModuleNotFoundError:
        return checkout / "materials"

def shipped_names() -> list[str]:
    """Names of the shipped materials (``materials/<name>.toml``), sorted."""
    shipped = shipped_materials()
    return sorted(p.name.removesuffix(".toml") for p in shipped.iterdir()
                  if p.name.endswith(".toml")) if shipped.is_dir() else []


_FIELDS = {"E": "modulus", "G": "modulus", "density": "density"}


@dataclasses.dataclass(frozen=True)
class LossFactor:
    """A material loss factor eta [-] in [0, 1) with its plausible range (low, high) and the
    source of the value."""

    value: float
    low: float
    high: float
    source: str


@dataclasses.dataclass(frozen=True)
class Constituent:
    """An isotropic constituent. E, G [Pa], density [kg/m^3], poisson [-].

    ``spread`` holds the +- value printed for each field (same units), 0 where none is given.
    """

    name: str
    E: float
    G: float
    density: float
    poisson: float
    spread: dict[str, float] = dataclasses.field(default_factory=dict)
    loss: LossFactor | None = None  # the file's material loss factor, if it gives one

    def __post_init__(self):
        for field in ("E", "G", "density"):
            if not getattr(self, field) > 0:
                raise InputError(f"{field} must be positive, got {getattr(self, field)!r}",
                                 source=self.name, field=field)
        if not -1.0 < self.poisson < 0.5:
            raise InputError(f"poisson ratio {self.poisson} outside (-1, 0.5)",
                             source=self.name, field="poisson")


@dataclasses.dataclass(frozen=True)
class Lamina:
    """Unidirectional ply properties from the rule of mixtures (SI)."""

    E1: float
    E2: float
    G12: float
    nu12: float
    density: float

    @property
    def nu21(self) -> float:
        return self.nu12 * self.E2 / self.E1


def load_constituent(name_or_path: str | Path) -> Constituent:
    """Read the shipped material ``<name>`` (``materials/<name>.toml``) or a given .toml path
    into a Constituent."""
    path = _material_path(str(name_or_path))
    try:  # one stat: whether the file is there, and the cache key below
        stat = os.stat(str(path))
    except OSError:  # no such file, or inside a zipped package (no file to stat)
        stat = None
    if stat is not None and statmode.S_ISREG(stat.st_mode):
        return _cached_constituent(str(path), stat.st_mtime_ns, stat.st_size)
    if not path.is_file():
        what = (f"no material file {path}" if Path(str(name_or_path)).suffix == ".toml"
                else f"unknown material {str(name_or_path)!r}")
        raise InputError(f"{what}; shipped materials: {', '.join(shipped_names())}",
                         expected="a shipped material's name or a path to a material .toml file")
    return _read_constituent(path)  # e.g. inside a zipped package: read it every time


def material_path(name_or_path: str) -> Traversable:
    """The file ``load_constituent`` reads for ``name_or_path``: a .toml path as given, else
    the shipped ``materials/<name>.toml``."""
    return _material_path(str(name_or_path))


@functools.lru_cache(maxsize=64)
def _material_path(name_or_path: str) -> Traversable:
    """Where ``load_constituent`` looks for ``name_or_path``: a .toml path as given, else the
    shipped ``<name>.toml``. Cached: finding the shipped folder costs an import attempt, and a
    calibration asks for the same few names thousands of times."""
    path = Path(name_or_path)
    return path if path.suffix == ".toml" else shipped_materials() / f"{name_or_path}.toml"


@functools.lru_cache(maxsize=64)
def _cached_constituent(path: str, mtime_ns: int, size: int) -> Constituent:
    """``_read_constituent`` of the file as it was at (mtime_ns, size), the cache key: a
    calibration reads the same two constituents for every evaluation."""
    return _read_constituent(Path(path))


def _read_constituent(path: Traversable) -> Constituent:
    src = str(path)
    with path.open("rb") as fh:
        data = tomllib.load(fh)
    values, spread = {}, {}
    for field, dim in _FIELDS.items():
        entry = data.get(field)
        if not isinstance(entry, dict) or "mean" not in entry:
            raise InputError("missing", source=src, field=f"{field}.mean",
                             expected=f"{field} = {{ mean = '...', spread = '...' }} in {dim} units")
        values[field] = parse_quantity(entry["mean"], dim, source=src, field=f"{field}.mean")
        spread[field] = (parse_quantity(entry["spread"], dim, source=src, field=f"{field}.spread")
                         if "spread" in entry else 0.0)
    nu = data.get("poisson", {}).get("mean") if isinstance(data.get("poisson"), dict) else None
    if not isinstance(nu, (int, float)):
        raise InputError("missing or not a number", source=src, field="poisson.mean",
                         expected="a dimensionless number in (-1, 0.5)")
    return Constituent(name=data.get("name", path.name.removesuffix(".toml")), E=values["E"],
                       G=values["G"], density=values["density"], poisson=float(nu), spread=spread,
                       loss=_read_loss(data.get("loss_factor"), src))


def _read_loss(entry, src: str) -> LossFactor | None:
    """``loss_factor = { mean = ..., low = ..., high = ..., source = "..." }`` of a material
    file (plain numbers in [0, 1)), or None when the file gives none."""
    if entry is None:
        return None
    expected = "loss_factor = { mean = 0.001, low = 1e-4, high = 3e-3, source = '...' } in [0, 1)"
    if not isinstance(entry, dict):
        raise InputError(f"got {entry!r}", source=src, field="loss_factor", expected=expected)
    values = {}
    for key in ("mean", "low", "high"):
        value = entry.get(key, entry.get("mean"))
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0 <= value < 1:
            raise InputError(f"got {value!r}", source=src, field=f"loss_factor.{key}",
                             expected="a plain number in [0, 1)")
        values[key] = float(value)
    return LossFactor(values["mean"], values["low"], values["high"], str(entry.get("source", src)))


def rule_of_mixtures(fiber: Constituent, matrix: Constituent, fiber_fraction: float) -> Lamina:
    """Unidirectional ply from fibre and matrix at fibre volume fraction ``fiber_fraction``."""
    vf = fiber_fraction
    if not 0.0 < vf < 1.0:
        raise InputError(f"fiber volume fraction {vf} outside (0, 1)", field="fiber_volume_fraction")
    vm = 1.0 - vf
    return Lamina(
        E1=vf * fiber.E + vm * matrix.E,
        E2=1.0 / (vf / fiber.E + vm / matrix.E),
        G12=1.0 / (vf / fiber.G + vm / matrix.G),
        nu12=vf * fiber.poisson + vm * matrix.poisson,
        density=vf * fiber.density + vm * matrix.density,
    )


def woven_beam_modulus(ply: Lamina) -> float:
    """Axial (= flexural) modulus [Pa] of a narrow strip of balanced woven 0/90 plies."""
    denom = 1.0 - ply.nu12 * ply.nu21
    q11, q22 = ply.E1 / denom, ply.E2 / denom
    q12 = ply.nu12 * q22
    a11 = 0.5 * (q11 + q22)  # = A22 for the balanced ply
    return a11 - q12**2 / a11


@dataclasses.dataclass(frozen=True)
class BeamMaterial:
    """What a beam element needs: modulus E [Pa], shear modulus G [Pa], density [kg/m^3]."""

    name: str
    E: float
    G: float
    density: float


class ShearSource(enum.StrEnum):
    """Where a composite's constituent shear moduli come from: the constituent files' own G
    (PRINTED), or E / 2 (1 + nu) of each (ISOTROPIC)."""

    PRINTED = "printed"
    ISOTROPIC = "isotropic"


def isotropic_shear(material: Constituent) -> Constituent:
    """The constituent with G = E / 2 (1 + nu) [Pa] in place of its printed G."""
    return dataclasses.replace(material, G=material.E / (2.0 * (1.0 + material.poisson)))


def woven_composite(fiber: Constituent, matrix: Constituent, fiber_fraction: float,
                    shear: ShearSource | str = ShearSource.PRINTED) -> BeamMaterial:
    """Beam material of a woven 0/90 laminate (see the module docstring for the formula).
    ``shear`` (a ``ShearSource`` or its text): PRINTED uses the constituents' G as given,
    ISOTROPIC E / 2 (1 + nu) of each (Table I's printed G values conflict with its E and nu;
    both are shown where G matters)."""
    if parse_choice(ShearSource, shear, "shear_modulus") is ShearSource.ISOTROPIC:
        fiber, matrix = isotropic_shear(fiber), isotropic_shear(matrix)
    ply = rule_of_mixtures(fiber, matrix, fiber_fraction)
    return BeamMaterial(name=f"woven {fiber.name}/{matrix.name} Vf={fiber_fraction:g}",
                        E=woven_beam_modulus(ply), G=ply.G12, density=ply.density)


def isotropic(material: Constituent) -> BeamMaterial:
    return BeamMaterial(name=material.name, E=material.E, G=material.G, density=material.density)
