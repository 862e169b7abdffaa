"""Choices (eigen method, mass matrix, model part and family) are enums inside; the edge turns
text into them and refuses anything else with one line naming the option and the choices."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from flexlink.analysis.eigensolver import Method
from flexlink.analysis.modal import Mass, analyze
from flexlink.choices import parse_choice
from flexlink.cli import main
from flexlink.errors import InputError
from flexlink.fe.motions import ModelFamily, Part
from flexlink.scene import load_scene

from conftest import CASES_DIR

CASE = CASES_DIR / "case1.toml"


def _refusal(args: list[str]) -> str:
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 2
    assert "Traceback" not in result.output
    [line] = [l for l in result.stderr.splitlines() if l.startswith("Error:")]
    return line


def test_cli_refuses_an_unknown_method_naming_the_option_and_choices():
    assert _refusal(["modes", str(CASE), "--method", "fast"]) == (
        "Error: Invalid value for '--method': 'fast' is not one of 'auto', 'dense', 'sparse'.")


def test_cli_refuses_an_unknown_part_naming_the_option_and_choices():
    assert _refusal(["mac", str(CASE), str(CASE), "--part", "sideways"]) == (
        "Error: Invalid value for '--part': 'sideways' is not one of 'auto', 'in-plane', "
        "'out-of-plane'.")


def test_cli_refuses_an_unknown_family_naming_the_option_and_choices():
    assert _refusal(["calibrate", str(CASE), "--family", "2d"]) == (
        "Error: Invalid value for '--family': '2d' is not one of 'scene', 'planar', "
        "'out-of-plane', '3d'.")


def test_python_edge_refuses_an_unknown_mass_in_one_line():
    with pytest.raises(InputError) as caught:
        analyze(load_scene(CASE), 2, 4, mass="heavy")
    assert str(caught.value) == "mass: 'heavy' is not a choice (expected consistent or lumped)"


def test_python_edge_refuses_an_unknown_method_in_one_line_and_takes_a_known_one():
    scene = load_scene(CASE)
    with pytest.raises(InputError) as caught:
        analyze(scene, 2, 4, solver="fast")
    assert str(caught.value) == "method: 'fast' is not a choice (expected auto, dense or sparse)"
    assert analyze(scene, 2, 4, solver="sparse").modes.solver is Method.SPARSE


@pytest.mark.parametrize("kind", [Mass, Part, ModelFamily])
def test_every_value_parses_to_its_member_and_nothing_else_does(kind):
    for member in kind:
        assert parse_choice(kind, member.value, "x") is member
        assert parse_choice(kind, member, "x") is member
    with pytest.raises(InputError, match=r"^x: 'none' is not a choice \(expected .* or .*\)$"):
        parse_choice(kind, "none", "x")
