"""Unit spellings convert to SI by the factors a handbook gives (one check per spelling), and
values without a unit or with a unit of another dimension are refused."""

import math

import pytest

from flexlink.errors import InputError
from flexlink.units import UNITS, parse_quantity

# (text, dimension, SI value written out by hand)
CASES = [
    ("2 m", "length", 2.0), ("2 cm", "length", 0.02), ("2 mm", "length", 0.002),
    ("2 um", "length", 2e-6), ("2 in", "length", 0.0508),
    ("3 Pa", "modulus", 3.0), ("3 kPa", "modulus", 3e3), ("3 MPa", "modulus", 3e6),
    ("3 GPa", "modulus", 3e9), ("3 N/m^2", "modulus", 3.0), ("3 N/mm^2", "modulus", 3e6),
    ("1250 kg/m^3", "density", 1250.0), ("1.25 g/cm^3", "density", 1250.0),
    ("4 N/m", "translational stiffness", 4.0), ("4 kN/m", "translational stiffness", 4e3),
    ("4 MN/m", "translational stiffness", 4e6), ("4 N/mm", "translational stiffness", 4e3),
    ("4 kN/mm", "translational stiffness", 4e6),
    ("5 N*m/rad", "rotational stiffness", 5.0), ("5 N m/rad", "rotational stiffness", 5.0),
    ("5 Nm/rad", "rotational stiffness", 5.0), ("5 N*mm/rad", "rotational stiffness", 5e-3),
    ("5 kN*m/rad", "rotational stiffness", 5e3),
    ("90 deg", "angle", math.pi / 2), ("0.5 rad", "angle", 0.5),
    ("6 kg", "mass", 6.0), ("6 g", "mass", 6e-3),
    ("7 kg*m^2", "rotary inertia", 7.0), ("7 kg m^2", "rotary inertia", 7.0),
    ("7 g*cm^2", "rotary inertia", 7e-7),  # 1e-3 kg * 1e-4 m^2
    ("8 m^2", "area", 8.0), ("8 mm^2", "area", 8e-6), ("8 cm^2", "area", 8e-4),
    ("9 m^4", "second moment", 9.0), ("9 mm^4", "second moment", 9e-12),
    ("9 cm^4", "second moment", 9e-8),
    ("50 Hz", "frequency", 50.0), ("1.5 kHz", "frequency", 1500.0),
    ("3 rad/s", "angular speed", 3.0), ("60 rev/min", "angular speed", 2 * math.pi),
    ("30 rpm", "angular speed", math.pi), ("2 rev/s", "angular speed", 4 * math.pi),
    ("2 Hz", "angular speed", 4 * math.pi),
    ("3 rad/s^2", "angular acceleration", 3.0), ("3 rev/s^2", "angular acceleration", 6 * math.pi),
    ("4 N*m", "torque", 4.0), ("4 N m", "torque", 4.0), ("4 Nm", "torque", 4.0),
    ("4 N*mm", "torque", 4e-3), ("5 N", "force", 5.0), ("5 kN", "force", 5e3),
]


@pytest.mark.parametrize("text, dimension, si", CASES)
def test_spelling_converts_to_si(text, dimension, si):
    assert math.isclose(parse_quantity(text, dimension), si, rel_tol=1e-15)


def test_every_spelling_is_checked():
    """A unit added to the table without a hand value here would go unchecked."""
    checked = {(d, t.split(" ", 1)[1]) for t, d, _ in CASES}
    declared = {(d, u) for d, table in UNITS.items() for u in table}
    assert declared == checked


def test_number_forms_and_rigid():
    assert parse_quantity("  -1.5e-3  mm ", "length") == pytest.approx(-1.5e-6, rel=1e-15)
    assert parse_quantity(".5 m", "length") == 0.5
    assert parse_quantity("rigid", "translational stiffness") == math.inf
    with pytest.raises(InputError):
        parse_quantity("rigid", "length")  # only a stiffness can be rigid


@pytest.mark.parametrize("value, problem", [
    (0.3, "got 0.3 without a unit"), (1, "got 1 without a unit"), (True, "got True without a unit"),
    (None, "got None without a unit"), ("0.3", "unknown unit ''"),
    ("0.3 furlong", "unknown unit 'furlong'"), ("mm 3", "cannot read 'mm 3'")])
def test_values_without_a_known_unit_are_refused(value, problem):
    """The message names the file, the field, what was wrong and every accepted spelling."""
    with pytest.raises(InputError) as info:
        parse_quantity(value, "length", source="s.toml", field="linkage.ground")
    message = str(info.value)
    assert message.startswith("s.toml: linkage.ground: ") and problem in message
    assert "a length as a string with a unit, one of: m, cm, mm, um, in; e.g. '1 m'" in message


def test_unit_of_another_dimension_is_named():
    with pytest.raises(InputError, match="'N/mm' is a unit of translational stiffness"):
        parse_quantity("3 N/mm", "modulus", source="s.toml", field="material.E")


def test_range_syntax_is_one_for_every_option():
    """LOW:HIGH, each end with a unit, or a bare low end taking the high end's unit."""
    from flexlink.units import RPM, parse_range
    assert parse_range("100 mm:1 m", "length") == (pytest.approx(0.1), 1.0)
    assert parse_range("0:3000 rev/min", "angular speed") == (0.0, pytest.approx(3000 * RPM))
    assert parse_range("1e4:1e9 N/m", "translational stiffness") == (1e4, 1e9)
    for bad in ("3000 rev/min", "1:2:3 rad/s", "0:3000"):
        with pytest.raises(InputError):
            parse_range(bad, "angular speed", field="--speeds")


def test_speed_and_percent_conversions():
    """rev/min back and forth to the last bit or two (one rounding each way); the percent
    error's sign and size."""
    from flexlink.units import parse_quantity, percent_error, rev_per_min
    for rpm in (60, 1000, 2000, 3000):
        assert rev_per_min(parse_quantity(f"{rpm} rev/min", "angular speed")) == pytest.approx(
            rpm, rel=4e-16)
    assert rev_per_min(2 * math.pi) == pytest.approx(60.0, rel=1e-15)  # one turn per second
    assert percent_error(110.0, 100.0) == pytest.approx(10.0, rel=1e-14)
    assert percent_error(90.0, 100.0) == pytest.approx(-10.0, rel=1e-14)
