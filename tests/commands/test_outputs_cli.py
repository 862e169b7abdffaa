"""``flexlink outputs`` and ``flexlink torque-family`` on the command line: the files and the
JSON document, and bad input refused in one line naming the file and the field, exit 2, with
the results of an earlier run left as they were."""

import json
import math

import pytest
from click.testing import CliRunner

from conftest import SCENES_DIR
from flexlink.cli import main

WIPER = SCENES_DIR / "wiper.toml"
KINETO = WIPER.read_text().split("[kinetostatics]")[1]


def run(*args):
    result = CliRunner().invoke(main, [*map(str, args)])
    return result.exit_code, result.stdout, result.stderr


def wiper_with(tmp_path, table: str = KINETO, extra: str = "", name: str = "wiper") -> str:
    """The wiper scene with its [kinetostatics] table replaced by ``table`` (and ``extra``
    tables after it), written as ``name``.toml."""
    path = tmp_path / f"{name}.toml"
    path.write_text(WIPER.read_text().split("[kinetostatics]")[0] + "[kinetostatics]"
                    + table + extra)
    return path


def test_outputs_json_files_and_the_quoted_angles(tmp_path):
    code, out, err = run("outputs", WIPER, "--json", "--out", tmp_path)
    assert code == 0, err
    doc = json.loads(out)
    assert [p.split("/")[-1] for p in doc["files"]] == ["outputs.csv", "outputs.png",
                                                        "outputs.json"]
    assert json.loads((tmp_path / "wiper" / "outputs.json").read_text()) == doc
    assert [r["crank_deg"] for r in doc["at_crank_angles"]] == pytest.approx([0, 90, 180, 240],
                                                                         abs=1e-9)
    assert [d["crank_deg"] for d in doc["dead_points"]] == pytest.approx([4.857, 182.305],
                                                                         abs=1e-3)
    row = doc["at_crank_angles"][1]  # 90 deg: T_out = T_in / K of each rocker
    assert row["torques_N_m"]["rocker2"] / 80 == pytest.approx(
        row["ratios"]["T[rocker2]/T_in"], rel=1e-12)
    for peak in doc["peaks"]:
        assert math.isfinite(peak["peak"])


def test_outputs_study_writes_the_parametric_files(tmp_path):
    code, out, err = run("outputs", WIPER, "--study", "--poses", "24", "--json", "--out",
                         tmp_path)
    assert code == 0, err
    doc = json.loads(out)["parametric"]
    factors = {f["factor"]: f for f in doc["factors"]}
    assert set(factors) == {"crank speed", "input torque", "friction m", "efficiency eta"}
    # eta enters T4 as eta^2 at rest: over 0.6..1 the spread is 1 - 0.36 of the base value
    assert factors["efficiency eta"]["effect_percent"]["T[rocker2]/T_in"] == pytest.approx(
        64, rel=1e-9)
    assert factors["crank speed"]["levels"][-1] == 3000
    # at rest the ratios do not depend on the input torque (linear statics): no effect
    assert factors["input torque"]["effect_percent"]["T[rocker2]/T_in"] < 1e-9
    # and m scales T4 by (1 - m): over 0..0.9 the spread is 90 % of the base value
    assert factors["friction m"]["effect_percent"]["T[rocker2]/T_in"] == pytest.approx(90, rel=1e-9)
    for name in ("parametric.csv", "parametric.png"):
        assert (tmp_path / "wiper" / name).stat().st_size > 0


@pytest.mark.parametrize("table, field", [
    (KINETO.replace("value = 0.0, note", "value = 1.0, note"), "kinetostatics.friction"),
    (KINETO.replace("value = 0.0, note", "value = -0.1, note"), "kinetostatics.friction"),
    (KINETO.replace("value = 1.0, note", "value = 0.0, note"), "kinetostatics.efficiency"),
    (KINETO.replace("value = 1.0, note", "value = 1.2, note"), "kinetostatics.efficiency"),
    (KINETO.replace('"rocker2"]', '"rocker3"]'), "kinetostatics.outputs"),
    (KINETO.replace('"rocker2"]', '"link2"]'), "kinetostatics.outputs"),
    (KINETO.replace('input_torque = "80 N*m"\n', ""), "kinetostatics.input_torque"),
])
def test_bad_kinetostatics_table_is_one_line_and_loses_nothing(table, field, tmp_path):
    out = tmp_path / "out"
    good = wiper_with(tmp_path)
    assert run("outputs", good, "--out", out, "--poses", "12")[0] == 0
    before = {p.name: p.read_bytes() for p in (out / "wiper").iterdir()}
    path = wiper_with(tmp_path, table)  # same file name: the same output folder
    code, _, err = run("outputs", path, "--out", out, "--poses", "12")
    assert code == 2 and err.count("\n") == 1, err
    assert str(path) in err and field in err, err
    assert {p.name: p.read_bytes() for p in (out / "wiper").iterdir()} == before


def test_an_input_torque_and_a_torque_load_on_the_driver_contradict(tmp_path):
    loads = '\n[[loads]]\nkind = "torque"\nlink = "crank"\ntorque = "5 N*m"\n'
    code, _, err = run("outputs", wiper_with(tmp_path, extra=loads), "--out", tmp_path)
    assert code == 2 and err.count("\n") == 1 and "loads[0]" in err and "contradicts" in err, err
    loads = '\n[[loads]]\nkind = "torque"\nlink = "rocker2"\ntorque = "5 N*m"\n'
    code, _, err = run("outputs", wiper_with(tmp_path, extra=loads), "--out", tmp_path)
    assert code == 2 and "loads[0]" in err and "loaded output 'rocker2'" in err, err


@pytest.mark.parametrize("args, field", [
    (("--friction", "1"), "--friction"), (("--efficiency", "0"), "--efficiency"),
    (("--input-torque", "80 m"), "--input-torque"), (("--share", "2"), "--share"),
])
def test_bad_options_are_one_line_naming_the_option(args, field, tmp_path):
    code, _, err = run("outputs", WIPER, *args, "--out", tmp_path)
    assert code == 2 and err.count("\n") == 1 and "command line" in err and field in err, err
    assert not list(tmp_path.rglob("outputs.*"))


SHORT_ROCKER = """
name = "short rocker"
[linkage]
type = "general"
[linkage.synthesis]
method = "extended-rocker"
rocker = "100 mm"
swing = "30 deg"
coupler_ratio = 3.5
[operation]
crank_speed = "2000 rev/min"
[[loads]]
kind = "torque"
link = "rocker"
torque = "1 N*m"
[[family]]
field = "linkage.synthesis.k"
values = [1.0, 0.3]
"""


def test_a_family_whose_scaling_cannot_close_the_loop_names_its_entry(tmp_path):
    """Moving the pin along the rocker (k = 0.3 of the design rocker) leaves a rocker too
    short to span the loop: both commands over the family refuse it naming the entry."""
    path = tmp_path / "short.toml"
    path.write_text(SHORT_ROCKER)
    for command in ("kinematics", "torque-family"):
        code, _, err = run(command, path, "--poses", "12", "--out", tmp_path / command)
        assert code == 2 and err.count("\n") == 1, err
        assert f"{path}: family[0].values[1]: linkage.synthesis.k = 0.3" in err, err
        assert not list((tmp_path / command).rglob("*.json"))


def test_input_torque_csv_option_and_its_bad_file(tmp_path):
    """--input-torque-csv reads the file as the scene's csv key would; a CSV with a gap in
    its angles is refused naming the file and the field."""
    rows = "".join(f"{a},80\n" for a in range(0, 360, 30))
    (tmp_path / "t.csv").write_text("crank_angle_deg,torque\n" + rows)
    code, out, err = run("outputs", WIPER, "--input-torque-csv", tmp_path / "t.csv", "--json",
                         "--poses", "12", "--out", tmp_path / "out")
    assert code == 0, err
    assert json.loads(out)["input_torque_N_m"] == {"min": 80.0, "max": 80.0}
    (tmp_path / "gap.csv").write_text("crank_angle_deg,torque\n" + rows.replace("90,80\n", ""))
    code, _, err = run("outputs", WIPER, "--input-torque-csv", tmp_path / "gap.csv",
                       "--out", tmp_path / "out")
    assert code == 2 and err.count("\n") == 1, err
    assert "gap.csv" in err and "kinetostatics.csv" in err and "missing crank angle" in err, err
