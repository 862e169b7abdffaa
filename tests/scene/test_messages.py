"""Messages that once misled (issue 21, item 6): each bad input gets the message that says what
is wrong and what would be right, on one line with exit status 2."""

from __future__ import annotations

import json
import re

import pytest
from click.testing import CliRunner
from conftest import CASES_DIR

from flexlink.cli import main
from flexlink.scene import plausibility
from flexlink.units import parse_quantity

RATIOS = "[linkage]\nR2 = 0.267\nR3 = 0.800\nR4 = 0.667\n"
BASE = (CASES_DIR / "_table2.toml").read_text()


def run(*args):
    return CliRunner().invoke(main, [*args])


def error_line(result) -> str:
    assert result.exit_code == 2, (result.output, result.exception)
    lines = [line for line in result.stderr.splitlines() if line.startswith("flexlink: error")]
    assert len(lines) == 1, result.stderr
    return lines[0]


def scene(tmp_path, text: str) -> str:
    (tmp_path / "_table2.toml").write_text(BASE)
    path = tmp_path / "s.toml"
    path.write_text('base = "_table2.toml"\n' + RATIOS + text)
    return str(path)


def whole(tmp_path, old: str, new: str) -> str:
    """The Table II base with ``old`` replaced by ``new``, as one file with case 1's ratios."""
    assert old in BASE
    text = BASE.replace(old, new).replace('type = "four-bar"\n',
                                          'type = "four-bar"\nR2 = 0.267\nR3 = 0.8\nR4 = 0.667\n')
    path = tmp_path / "s.toml"
    path.write_text(text)
    return str(path)


@pytest.mark.parametrize("verbose", [[], ["-v"]])
@pytest.mark.parametrize("old, new, problems", [
    ('link = "crank"\n', 'lnk = "crank"\n',
     ["drive.lnk: unknown key; did you mean link?", "drive.link: missing"]),
    ('fiber = "carbon_fiber"\n', 'fibre = "carbon_fiber"\n',
     ["material.composite.fibre: unknown key; did you mean fiber?",
      "material.composite.fiber: missing"]),
])
def test_every_problem_of_a_table_is_shown_with_its_hint(tmp_path, old, new, problems, verbose):
    path = whole(tmp_path, old, new)
    line = error_line(run(*verbose, "modes", path, "--out", str(tmp_path / "out")))
    assert line.startswith(f"flexlink: error: {path}: {problems[0]}"), line
    for problem in problems:
        assert problem in line, line


def test_a_misspelt_reference_key_is_an_unknown_key(tmp_path):
    line = error_line(run("modes", scene(tmp_path, '[reference]\nsorce = "tap test"\n'),
                          "--out", str(tmp_path / "out")))
    assert ": reference.sorce: unknown key; did you mean source?" in line, line
    assert "valid list" not in line, line


def test_a_general_key_in_a_four_bar_says_where_it_belongs(tmp_path):
    path = whole(tmp_path, 'type = "four-bar"\n', 'type = "four-bar"\ndriver = "crank"\n')
    line = error_line(run("modes", path, "--out", str(tmp_path / "out")))
    assert ("linkage.driver: unknown key for type = 'four-bar': 'driver' belongs to "
            "type = 'general'") in line, line
    assert "rocker" not in line, line


def test_an_unknown_material_lists_the_shipped_ones(tmp_path):
    path = whole(tmp_path, '[material.composite]            # Table I constituents, rule of '
                           'mixtures (paper, section II.D)\nfiber = "carbon_fiber"\nmatrix = '
                           '"polyester"\nfiber_volume_fraction = 0.5\n',
                 '[material]\nisotropic = "aluminium"\n')
    line = error_line(run("modes", path, "--out", str(tmp_path / "out")))
    assert (f"{path}: material.isotropic: unknown material 'aluminium'; shipped materials: "
            "aisi_1020_cd, aisi_1080, carbon_fiber, polyester, steel") in line, line
    assert "material: material" not in line and "materials/" not in line, line


def test_a_density_slip_suggests_a_value_the_parser_reads(tmp_path):
    text = BASE.split("[material.composite]")[0] + '[material]\nE = "70 GPa"\ndensity = "1e5 kg/m^3"\n' \
        + "[section]" + BASE.split("[section]", 1)[1]
    text = text.replace('type = "four-bar"\n', 'type = "four-bar"\nR2 = 0.267\nR3 = 0.8\nR4 = 0.667\n')
    path = tmp_path / "s.toml"
    path.write_text(text)
    line = error_line(run("modes", str(path), "--out", str(tmp_path / "out")))
    hint = re.search(r"did you mean (.+?)\?", line)
    assert hint, line
    assert parse_quantity(hint[1], "density") == pytest.approx(100.0), line


@pytest.mark.parametrize("unit", sorted(plausibility.HINTS))
def test_every_slip_hint_is_a_spelling_the_parser_reads(unit):
    kind = {"m": "length", "Pa": "modulus", "kg/m^3": "density"}[unit]
    for factor, spelling in plausibility.HINTS[unit]:
        assert parse_quantity(f"3 {spelling}", kind) == pytest.approx(3 * factor)


@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
def test_a_tolerance_that_is_not_a_number_is_refused(tmp_path, value):
    result = run("modes", str(CASES_DIR / "case1.toml"), "--tol", value,
                 "--out", str(tmp_path / "out"))
    assert result.exit_code == 2 and f"'{value}' is not a number" in result.stderr, result.output
    assert "double precision" not in result.stderr


def test_millihertz_frequencies_are_printed_with_significant_digits(tmp_path):
    path = whole(tmp_path, '[material.composite]            # Table I constituents, rule of '
                           'mixtures (paper, section II.D)\nfiber = "carbon_fiber"\nmatrix = '
                           '"polyester"\nfiber_volume_fraction = 0.5\n',
                 '[material]\nE = "1 Pa"\ndensity = "1500 kg/m^3"\n[checks]\nplausibility = "warn"\n')
    out = tmp_path / "out"
    text = run("modes", path, "-e", "4", "--out", str(out))
    assert text.exit_code == 0, text.output
    computed = json.loads((out / "s" / "modes.json").read_text())["cases"][0]["modes"]
    rows = [line.split() for line in text.stdout.splitlines()
            if re.match(r"^\s+\d+\s+\S+\s", line)]
    printed = [float(r[1]) for r in rows[:len(computed)]]
    assert len(printed) == len(computed)
    for shown, mode in zip(printed, computed):
        assert mode["computed_Hz"] < 0.01  # the case the fix is for: E = 1 Pa, mHz modes
        # four significant digits: within half a unit in the fourth digit
        assert shown == pytest.approx(mode["computed_Hz"], rel=5e-4), (shown, mode)


def test_a_folder_of_only_base_files_says_they_are_bases(tmp_path):
    (tmp_path / "_table2.toml").write_text(BASE)
    line = error_line(run("modes", str(tmp_path), "--out", str(tmp_path / "out")))
    assert "holds only base files (_table2.toml)" in line and "'_'" in line, line
