"""Constituent materials: the physical admissibility of a constituent, the isotropic shear law
and the material file's schema. Written against mutants of flexlink/materials/mixtures.py that
the suite let through (docs/testing.md, mutation testing)."""


import pytest

from flexlink.errors import InputError
from flexlink.materials.mixtures import (
    Constituent,
    isotropic,
    isotropic_shear,
    load_constituent,
    rule_of_mixtures,
    woven_composite,
)

STEEL = dict(name="steel", E=200e9, G=80e9, density=7850.0, poisson=0.3)


@pytest.mark.parametrize("nu", [-0.9999, 0.0, 0.4999])
def test_poisson_ratios_inside_the_stability_bounds_are_accepted(nu):
    """An isotropic solid is stable (bulk modulus E/3(1 - 2 nu) and shear modulus
    E/2(1 + nu) both positive) exactly for -1 < nu < 1/2."""
    assert Constituent(**{**STEEL, "poisson": nu}).poisson == nu


@pytest.mark.parametrize("nu", [-1.0, 0.5, -1.5, 0.7])
def test_poisson_ratios_at_or_beyond_the_stability_bounds_are_refused(nu):
    with pytest.raises(InputError) as info:
        Constituent(**{**STEEL, "poisson": nu})
    assert (info.value.source, info.value.field) == ("steel", "poisson")
    assert str(nu) in str(info.value)


@pytest.mark.parametrize("field", ["E", "G", "density"])
@pytest.mark.parametrize("value", [0.0, -1.0])
def test_moduli_and_density_must_be_positive(field, value):
    """A zero or negative modulus or density gives no (or an imaginary) frequency."""
    with pytest.raises(InputError) as info:
        Constituent(**{**STEEL, field: value})
    assert (info.value.source, info.value.field) == ("steel", field)
    assert "positive" in str(info.value)


def test_isotropic_shear_is_the_elasticity_identity():
    """G = E / 2(1 + nu): 200 GPa and nu = 0.3 give 76.923 GPa; nothing else changes."""
    steel = Constituent(**STEEL)
    sheared = isotropic_shear(steel)
    assert sheared.G == pytest.approx(200e9 / 2.6, rel=1e-15)  # one division, rounding only
    assert (sheared.E, sheared.density, sheared.poisson) == (200e9, 7850.0, 0.3)


def test_a_woven_laminate_of_one_isotropic_material_is_that_material():
    """Fibre = matrix: every rule of mixtures returns the material itself, for either source
    of the shear modulus (printed G, or E / 2(1 + nu))."""
    steel = Constituent(**STEEL)
    printed = woven_composite(steel, steel, 0.4, shear="printed")
    derived = woven_composite(steel, steel, 0.4, shear="isotropic")
    assert printed.G == pytest.approx(80e9, rel=1e-14)  # harmonic mean of two equal values
    assert derived.G == pytest.approx(200e9 / 2.6, rel=1e-14)
    for beam in (printed, derived):
        assert beam.E == pytest.approx(200e9, rel=1e-12)  # no Poisson stiffening (one material)
        assert beam.density == pytest.approx(7850.0, rel=1e-14)
    assert "steel/steel" in printed.name and "0.4" in printed.name


def test_unknown_shear_source_is_refused_naming_the_choices():
    steel = Constituent(**STEEL)
    with pytest.raises(InputError) as info:
        woven_composite(steel, steel, 0.4, shear="measured")
    assert info.value.field == "shear_modulus"
    assert info.value.expected == "printed or isotropic"  # choices.spelled, every choice


def test_isotropic_beam_material_carries_the_constituent_values():
    beam = isotropic(Constituent(**STEEL))
    assert (beam.name, beam.E, beam.G, beam.density) == ("steel", 200e9, 80e9, 7850.0)


GOOD = '''name = "resin"
E = { mean = "3 GPa", spread = "0.1 GPa" }
G = { mean = "1.1 GPa" }
density = { mean = "1.2 g/cm^3", spread = "0.01 g/cm^3" }
poisson = { mean = 0.36 }
'''


def test_a_material_file_is_read_in_si_with_absent_spreads_zero(tmp_path):
    path = tmp_path / "resin_batch_7.toml"  # the name inside wins over the file's
    path.write_text(GOOD)
    resin = load_constituent(path)
    assert (resin.name, resin.E, resin.G, resin.density, resin.poisson) == (
        "resin", 3e9, 1.1e9, 1200.0, 0.36)
    assert resin.spread == pytest.approx({"E": 0.1e9, "G": 0.0, "density": 10.0}, rel=1e-12)


def test_a_material_file_without_a_name_takes_its_file_name(tmp_path):
    path = tmp_path / "epoxy.toml"
    path.write_text(GOOD.replace('name = "resin"\n', ""))
    assert load_constituent(path).name == "epoxy"


@pytest.mark.parametrize("field, broken", [
    ("E.mean", GOOD.replace('E = { mean = "3 GPa", spread = "0.1 GPa" }', 'E = "3 GPa"')),
    ("G.mean", GOOD.replace('G = { mean = "1.1 GPa" }\n', "")),
    ("density.mean", GOOD.replace('mean = "1.2 g/cm^3", ', "")),
    ("poisson.mean", GOOD.replace("poisson = { mean = 0.36 }", 'poisson = { mean = "0.36" }')),
    ("poisson.mean", GOOD.replace("poisson = { mean = 0.36 }", "poisson = 0.36")),
])
def test_a_material_file_missing_a_value_names_the_key_and_the_file(tmp_path, field, broken):
    path = tmp_path / "resin.toml"
    path.write_text(broken)
    with pytest.raises(InputError) as info:
        load_constituent(path)
    assert info.value.field == field
    assert info.value.source == str(path)
    assert info.value.expected  # says what would have been accepted


@pytest.mark.parametrize("key", ["E", "density"])
def test_a_spread_in_the_wrong_unit_kind_names_its_key(tmp_path, key):
    path = tmp_path / "resin.toml"
    path.write_text(GOOD.replace('spread = "0.1 GPa"' if key == "E" else 'spread = "0.01 g/cm^3"',
                                 'spread = "2 mm"'))
    with pytest.raises(InputError) as info:
        load_constituent(path)
    assert info.value.field == f"{key}.spread"


def test_a_file_rewritten_within_one_clock_tick_is_read_again(tmp_path):
    """Coarse file clocks give two writes the same mtime; the size tells them apart."""
    import os

    path = tmp_path / "resin.toml"
    path.write_text(GOOD)
    stamp = path.stat().st_mtime_ns
    assert load_constituent(path).density == pytest.approx(1200.0)
    path.write_text(GOOD.replace('mean = "1.2 g/cm^3"', 'mean = "1.25 g/cm^3"'))
    os.utime(path, ns=(stamp, stamp))
    assert load_constituent(path).density == pytest.approx(1250.0)


def test_an_unknown_material_says_what_would_be_accepted():
    with pytest.raises(InputError) as info:
        load_constituent("unobtainium")
    assert info.value.expected and "material" in info.value.expected


@pytest.mark.parametrize("key, broken", [
    ("E", GOOD.replace('mean = "3 GPa"', 'mean = "3 mm"')),
    ("G", GOOD.replace('mean = "1.1 GPa"', 'mean = "1.1 kg/m^3"')),
    ("density", GOOD.replace('mean = "1.2 g/cm^3"', 'mean = "1.2 GPa"')),
])
def test_a_mean_in_the_wrong_unit_kind_names_the_file_and_its_key(tmp_path, key, broken):
    """The schema gives each value a unit kind (modulus, density); a value of another kind is
    refused with the file and the dotted key, so the user knows which line to fix."""
    path = tmp_path / "resin.toml"
    path.write_text(broken)
    with pytest.raises(InputError) as info:
        load_constituent(path)
    assert (info.value.source, info.value.field) == (str(path), f"{key}.mean")
    assert str(path) in str(info.value) and f"{key}.mean" in str(info.value)


def test_a_spread_in_the_wrong_unit_kind_names_the_file(tmp_path):
    path = tmp_path / "resin.toml"
    path.write_text(GOOD.replace('spread = "0.1 GPa"', 'spread = "2 mm"'))
    with pytest.raises(InputError) as info:
        load_constituent(path)
    assert (info.value.source, info.value.field) == (str(path), "E.spread")


@pytest.mark.parametrize("field", ["E", "G", "density"])
def test_any_positive_modulus_or_density_is_admissible(field):
    """Positivity is the only physical bound: a graphene aerogel weighs 0.16 kg/m^3, and a
    value below 1 in SI units must not be taken for a non-positive one."""
    assert getattr(Constituent(**{**STEEL, field: 0.16}), field) == 0.16


@pytest.mark.parametrize("fraction", [0.0, 1.0, -0.1, 1.5])
def test_a_fibre_fraction_outside_the_open_unit_interval_names_its_field(fraction):
    """A volume fraction of 0 or 1 leaves one constituent absent, and the harmonic means of
    the rule of mixtures then divide by zero."""
    steel = Constituent(**STEEL)
    with pytest.raises(InputError) as info:
        rule_of_mixtures(steel, steel, fraction)
    assert info.value.field == "fiber_volume_fraction"
