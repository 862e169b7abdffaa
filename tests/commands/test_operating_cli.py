"""``flexlink modes --speed``: the JSON document and files, the static column equal to plain
``modes``, and one-line errors for bad speeds and scenes that cannot run at speed."""

import json

import pytest
from click.testing import CliRunner

from conftest import CASES_DIR, SCENES_DIR
from flexlink.cli import main


def run(*args):
    return CliRunner().invoke(main, ["modes", *map(str, args)])


def test_json_beside_the_static_modes(tmp_path):
    result = run(SCENES_DIR / "rotor.toml", "--speed", "300 rev/min", "-e", "16", "--json",
                 "--out", tmp_path)
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    case = doc["cases"][0]
    assert case["speed_rad_s"] == pytest.approx(300 * 2 * 3.141592653589793 / 60, rel=1e-15)
    static = json.loads(run(SCENES_DIR / "rotor.toml", "-e", "16", "--json", "--out",
                            tmp_path / "static").stdout)["cases"][0]["modes"]
    for row, plain in zip(case["modes"], static):
        assert row["static_Hz"] == pytest.approx(plain["computed_Hz"], rel=1e-12)
        assert row["change_Hz"] == pytest.approx(row["frequency_Hz"] - row["static_Hz"], rel=1e-12)
        assert row["frequency_Hz"] > row["static_Hz"]  # a spinning bar stiffens (tension)
    assert case["largest_axial_force"]["link"] == "rotor" and case["largest_axial_force"]["N"] > 0
    assert case["stable"] and case["assumptions"]
    own = json.loads((tmp_path / "rotor" / "modes_at_speed.json").read_text())
    assert own["cases"] == [case]
    assert (tmp_path / "rotor" / "modes_at_speed.csv").read_text().count("\n") == 1 + 4


def test_text_names_a_divergence(tmp_path):
    result = run(SCENES_DIR / "kineto_aluminium.toml", "--speed", "2000 rev/min", "--out",
                 tmp_path)
    assert result.exit_code == 0, result.output
    assert "diverges" in result.output and "warning: negative stiffness" in result.output


@pytest.mark.parametrize("args, words", [
    (["--speed", "2000 m"], ["--speed", "angular speed"]),
    (["--speed", "nan rev/min"], ["--speed"]),
    (["--speed", "1e999 rev/min"], ["--speed", "finite"]),
    (["--crank-angle", "30 deg"], ["--speed"]),
    (["--speed", "100 rev/min", "--crank-angle", "30 mm"], ["--crank-angle", "angle"]),
])
def test_bad_speed_is_one_clear_line(tmp_path, args, words):
    result = run(CASES_DIR / "case1.toml", *args, "-e", "4", "--out", tmp_path)
    assert result.exit_code == 2
    assert all(w in result.output for w in words), result.output
    assert "Traceback" not in result.output and len(result.output.strip().splitlines()) == 1


def test_a_scene_without_a_body_per_link_is_refused(tmp_path):
    # the compliant wiper's strip joins two bodies: its rigid motion is not one body's
    result = run(SCENES_DIR / "compliant_wiper.toml", "--speed", "100 rev/min", "--out", tmp_path)
    assert result.exit_code == 2
    assert "compliant_wiper.toml" in result.output and "links.strip" in result.output
    assert "Traceback" not in result.output


@pytest.mark.parametrize("extra", [["--sensitivity"], ["--method", "dense"]])
def test_static_only_options_are_refused_at_speed(tmp_path, extra):
    result = run(CASES_DIR / "case1.toml", "--speed", "100 rev/min", *extra, "-e", "4", "--out",
                 tmp_path)
    assert result.exit_code == 2 and extra[0] in result.output


def test_a_scene_that_fails_costs_the_others_nothing(tmp_path):
    """Two scenes, the first unable to run at speed: the second's files are written and
    listed, the failure is listed with its file, and the exit status is 2."""
    wiper, rotor = SCENES_DIR / "compliant_wiper.toml", SCENES_DIR / "rotor.toml"
    result = run(wiper, rotor, "--speed", "300 rev/min", "-e", "4", "--json", "--out", tmp_path)
    assert result.exit_code == 2, result.output
    doc = json.loads(result.stdout)
    written = [str(tmp_path / "rotor" / f"modes_at_speed.{ext}") for ext in ("json", "csv")]
    assert [case["file"] for case in doc["cases"]] == [str(rotor)]
    assert doc["files"] == written
    assert [failure["file"] for failure in doc["failures"]] == [str(wiper)]
    assert "links.strip" in doc["failures"][0]["error"] and "links.strip" in result.stderr
    own = json.loads((tmp_path / "rotor" / "modes_at_speed.json").read_text())
    assert own == {"command": "modes --speed", "cases": doc["cases"], "files": written}
    assert not (tmp_path / "compliant_wiper" / "modes_at_speed.json").exists()
