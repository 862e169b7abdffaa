"""The scene's ``[[loads]]`` tables as the schema states them (flexlink/scene/loads.py): a CSV
load is a header row, then the crank angle [deg] and one value column per component, evenly
spaced over exactly one turn (a closing row at +360 deg repeats the first and is dropped),
read in the table's unit; anything else is refused naming the CSV file, the field and the row.
Written against mutants of flexlink/scene that the scene tests let through (docs/testing.md)."""

import math

import numpy as np
import pytest

from conftest import CASES_DIR
from flexlink.errors import InputError
from flexlink.scene import load_scene

CASE3 = CASES_DIR / "case3.toml"
TORQUE = '[[loads]]\nkind = "torque"\nlink = "rocker"\ncsv = "load.csv"\nunit = "{unit}"\n'
FORCE = ('[[loads]]\nkind = "force"\nlink = "coupler"\ncsv = "load.csv"\nunit = "N"\n'
         'at = ["10 mm", "0 m"]\n')


def loads_of(tmp_path, table: str, csv: str | None):
    if csv is not None:
        (tmp_path / "load.csv").write_text(csv)
    path = tmp_path / "loaded.toml"
    path.write_text(f'base = "{CASE3.as_posix()}"\n{table}')
    return load_scene(path).loads


def grid(angles, *columns, header="crank_angle_deg,torque"):
    return header + "\n" + "".join(
        ",".join(str(v) for v in (a, *values)) + "\n" for a, *values in zip(angles, *columns))


def refusal(tmp_path, table, csv) -> InputError:
    with pytest.raises(InputError) as info:
        loads_of(tmp_path, table, csv)
    assert info.value.source == str(tmp_path / "load.csv")
    assert info.value.field == "loads[0].csv"
    assert info.value.expected  # what would have been accepted
    return info.value


def test_a_torque_over_one_turn_is_read_in_si_with_the_closing_row_dropped(tmp_path):
    """12 rows every 30 deg from 15 deg (a turn need not start at 0), values in N mm, and a
    closing row at 375 deg equal to the first: 12 samples in N m at radians(15 + 30 k)."""
    angles = np.arange(15, 376, 30)
    values = 1.0 + np.sin(np.radians(angles))
    values[-1] = values[0]
    (load,) = loads_of(tmp_path, TORQUE.format(unit="N*mm"), grid(angles, values))
    np.testing.assert_allclose(load.angles, np.radians(angles[:-1]), rtol=1e-15)
    np.testing.assert_allclose(load.values[:, 0], 1e-3 * values[:-1], rtol=1e-15)
    assert (load.kind, load.body, load.field) == ("torque", "rocker", "loads[0]")


def test_angles_within_the_grid_tolerance_are_on_the_grid(tmp_path):
    """Seven steps of 360/7 deg written to 7 decimals: each angle is within 5e-8 deg of the
    even grid, so the turn is whole (the rounding adds up to 2e-7 deg over the turn, inside
    the tolerance of 1e-6 deg per row)."""
    angles = [round(k * 360 / 7, 7) for k in range(7)]
    (load,) = loads_of(tmp_path, TORQUE.format(unit="N*m"), grid(angles, [1.0] * 7))
    np.testing.assert_allclose(load.angles, np.radians(angles), rtol=1e-15)


def test_a_csv_load_is_periodic_and_linear_between_samples(tmp_path):
    """value_at: the sample itself at a sample angle, the mean of two neighbours midway, and
    the same value a whole turn (or several) away, including across the wrap-around."""
    angles = np.arange(0, 360, 90)
    (load,) = loads_of(tmp_path, TORQUE.format(unit="N*m"), grid(angles, [1.0, 3.0, 7.0, 5.0]))
    at = lambda deg: float(load.value_at(math.radians(deg))[0])  # noqa: E731
    assert at(90) == pytest.approx(3.0, rel=1e-12)
    assert at(135) == pytest.approx(5.0, rel=1e-12)  # midway between 3 and 7
    assert at(315) == pytest.approx(3.0, rel=1e-12)  # midway between 5 (270) and 1 (360 = 0)
    for deg in (45.0, 315.0):
        assert at(deg + 720) == pytest.approx(at(deg), rel=1e-12)
        assert at(deg - 360) == pytest.approx(at(deg), rel=1e-12)


def test_a_force_csv_has_two_components_at_its_point(tmp_path):
    angles = np.arange(0, 360, 120)
    (load,) = loads_of(tmp_path, FORCE, grid(angles, [1, 2, 3], [4, 5, 6],
                                             header="crank_angle_deg,Fx,Fy"))
    np.testing.assert_array_equal(load.values, [[1, 4], [2, 5], [3, 6]])  # integers, parsed
    assert load.at == (0.01, 0.0)


def test_a_constant_torque_has_one_row_no_angles_and_acts_at_the_origin(tmp_path):
    (load,) = loads_of(tmp_path, '[[loads]]\nkind = "torque"\nlink = "rocker"\n'
                                 'torque = "2 N*m"\n', None)
    assert load.angles is None and load.values.tolist() == [[2.0]] and load.at == (0.0, 0.0)
    assert float(load.value_at(1.0)[0]) == 2.0  # a constant load's one row, not interpolated


@pytest.mark.parametrize("csv, words", [
    ("", "empty"),
    ("crank_angle_deg,torque,extra\n0,1,1\n120,1,1\n240,1,1\n", "header has 3 column(s)"),
    ("crank_angle_deg,torque\n0,1\n120,1,2\n240,1\n", "row 3 has 3 column(s)"),
    ("crank_angle_deg,torque\n0,1\n180,1\n", "2 row(s)"),
    ("crank_angle_deg,torque\n0,1\n120,1\n120,1\n240,1\n", "do not increase at row 4"),
    ("crank_angle_deg,torque\n0,1\n120,2\n240,1\n360,1.5\n", "differs from the one at 0 deg"),
    # equal means equal to 1e-9 relative, with no absolute floor: a torque 0 is not 1e-9
    ("crank_angle_deg,torque\n0,0\n120,2\n240,1\n360,1e-9\n", "differs from the one at 0 deg"),
    ("crank_angle_deg,torque\n0,1\n120,1\n240,inf\n", "row 4, column 'torque': unreadable"),
    (grid(range(0, 340, 10), [1.0] * 34), "not one full turn"),
    (grid(range(0, 720, 10), [1.0] * 72), "not one full turn"),
])
def test_a_csv_off_the_schema_is_refused_naming_the_file_field_and_row(tmp_path, csv, words):
    error = refusal(tmp_path, TORQUE.format(unit="N*m"), csv)
    assert words in str(error), str(error)


def test_a_missing_csv_file_is_refused_naming_it(tmp_path):
    error = refusal(tmp_path, TORQUE.format(unit="N*m"), None)
    assert "no such file" in str(error)
