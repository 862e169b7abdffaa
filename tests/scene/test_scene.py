"""Scene files: the shipped cases load; bad input names the file and the field."""

import math

import pytest

from flexlink.errors import InputError
from flexlink.scene import load_scene, scene_files

from conftest import CASES_DIR as CASES


def test_shipped_cases_load_with_assumptions():
    files = scene_files([CASES])
    assert [f.name for f in files] == ["case1.toml", "case2.toml", "case3.toml", "case4.toml"]
    scene = load_scene(files[0])
    assert math.isclose(scene.four_bar.crank, 0.267 * 0.3)
    fields = {a.field for a in scene.assumptions}
    assert {"linkage.ground", "section.width", "section.ply_thickness", "joints.Kt",
            "joints.Kr", "drive.stiffness"} <= fields
    assert scene.reference.columns["Ex"] == (33, 85, 249, 610)


def write(tmp_path, text, name="s.toml"):
    (tmp_path / "_table2.toml").write_text((CASES / "_table2.toml").read_text())
    path = tmp_path / name
    path.write_text('base = "_table2.toml"\n' + text)
    return path


GOOD = "[linkage]\nR2 = 0.267\nR3 = 0.8\nR4 = 0.667\n"


@pytest.mark.parametrize("text, field, words", [
    ("[linkage]\nR2 = 0.267\nR3 = 0.8\n", "linkage.R4", "missing"),
    (GOOD + "[section]\nwidth = 20\n", "section.width", "without a unit"),
    (GOOD + "[section]\nwidth = '20 GPa'\n", "section.width", "unit of modulus"),
    (GOOD + "[section]\nwidth = '-20 mm'\n", "section.width", "> 0"),
    (GOOD + "[joints]\nKt = '1e6 N*m/rad'\n", "joints.Kt", "rotational stiffness"),
    (GOOD + "[pose]\nbranch = 'sideways'\n", "pose.branch", "open"),
    (GOOD + "[mesh]\nelements_per_link = 2.5\n", "mesh.elements_per_link", "whole number"),
])
def test_bad_input_names_file_and_field(tmp_path, text, field, words):
    path = write(tmp_path, text)
    with pytest.raises(InputError) as info:
        load_scene(path)
    message = str(info.value)
    assert str(path) in message and field in message and words in message, message


def test_error_in_base_file_names_the_base_file(tmp_path):
    path = write(tmp_path, GOOD)
    base = tmp_path / "_table2.toml"
    base.write_text(base.read_text().replace('"0.3 mm"', '"0.3 furlongs"'))
    with pytest.raises(InputError) as info:
        load_scene(path)
    assert str(base) in str(info.value) and "section.ply_thickness" in str(info.value)


def test_negative_length_rejected(tmp_path):
    path = write(tmp_path, "[linkage]\nR2 = 0.267\nR3 = 0.8\nR4 = 0.667\nground = '-300 mm'\n")
    with pytest.raises(InputError, match="linkage.ground"):
        load_scene(path)


def test_overrides_go_through_the_same_validation():
    scene = load_scene(CASES / "case1.toml", overrides={"section.width": "25 mm"})
    assert math.isclose(scene.sections["crank"].strip[0], 0.025)
    with pytest.raises(InputError) as info:
        load_scene(CASES / "case1.toml", overrides={"joints.Kt": "5"})
    assert "overrides" in str(info.value) and "joints.Kt" in str(info.value)
