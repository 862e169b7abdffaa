"""The scene contract: every key declared once (typos are errors with the nearest names), one
Scene for both kinds, generated reference and JSON Schema kept in step with the schema."""

import json
import math
import tomllib
from pathlib import Path

import jsonschema
import pytest

from flexlink.errors import InputError
from flexlink.scene import load_scene, scene_files
from flexlink.scene.reference import json_schema, reference_markdown
from flexlink.scene.source import merge

from conftest import ROOT
CASE1 = ROOT / "cases" / "case1.toml"
SHIPPED = scene_files([ROOT / "cases", ROOT / "scenes"])
RATIOS = "[linkage]\nR2 = 0.267\nR3 = 0.800\nR4 = 0.667\n"


def scene_file(tmp_path, text, name="s.toml"):
    """A Table II case 1 scene with ``text`` added (over the shipped base file)."""
    (tmp_path / "_table2.toml").write_text((ROOT / "cases" / "_table2.toml").read_text())
    path = tmp_path / name
    path.write_text('base = "_table2.toml"\n' + text)
    return path


# Each typo once ran and printed the unmodified answer (issue 10): now each names the file,
# the key path and the nearest valid name.
@pytest.mark.parametrize("text, where, hint", [
    (RATIOS + '[section]\nwidht = "10 mm"\n', "section.widht", "did you mean width"),
    (RATIOS + '[secton]\nwidth = "10 mm"\n', "[secton]", "did you mean [section]"),
    ("[linkage]\nR2 = 0.267\nR3 = 0.8\nR4 = 0.667\ngrond = '300 mm'\n", "linkage.grond",
     "did you mean ground"),
    (RATIOS + '[joints.O5]\nKt = "1e6 N/m"\n', "joints.O5", "did you mean O4"),
    (RATIOS + '[links.cranck.section]\nwidth = "10 mm"\n', "links.cranck", "did you mean crank"),
    (RATIOS + '[joints.a]\nmass = "1 g"\n', "joints.a", "did you mean A"),
    (RATIOS + "[mesh]\nelements_per_lnk = 8\n", "mesh.elements_per_lnk",
     "did you mean elements_per_link"),
    (RATIOS + '[drivee]\nlink = "crank"\n', "[drivee]", "did you mean [drive]"),
    (RATIOS + '[joints]\nKr_ = "1 N*m/rad"\n', "joints.Kr_", "did you mean Kr"),
    (RATIOS.replace("[linkage]\n", '[linkage]\ntype = "fourbar"\n'), "linkage",
     "'four-bar', 'general'"),
])
def test_misspelt_keys_are_errors_with_the_nearest_name(tmp_path, text, where, hint):
    path = scene_file(tmp_path, text)
    with pytest.raises(InputError) as info:
        load_scene(path)
    message = str(info.value)
    assert message.startswith(f"{path}: {where}:") and hint in message, message


def test_unknown_table_message_reads_as_the_issue_asks(tmp_path):
    path = scene_file(tmp_path, RATIOS + '[secton]\nwidth = "10 mm"\n')
    with pytest.raises(InputError, match=r": \[secton\]: unknown table; did you mean \[section\]"):
        load_scene(path)


def test_a_typo_in_the_base_file_names_the_base_file(tmp_path):
    path = scene_file(tmp_path, RATIOS)
    base = tmp_path / "_table2.toml"
    base.write_text(base.read_text().replace("[joints]", "[joints]\nKrr = '1 N*m/rad'"))
    with pytest.raises(InputError) as info:
        load_scene(path)
    assert str(info.value).startswith(f"{base}: joints.Krr: unknown key; did you mean Kr")


@pytest.mark.parametrize("text, where, words", [
    (RATIOS + "[reference]\nEx_Hz = [inf, 85, 249, 610]\n", "reference.Ex_Hz[0]", "finite"),
    (RATIOS + "[reference]\nEx_Hz = [0, 85]\n", "reference.Ex_Hz[0]", "(0, 1e+12]"),
    (RATIOS + '[joints]\nKt = "1e400 N/m"\n', "joints.Kt", "not a finite number"),
    (RATIOS + '[pose]\ntransmission_angle = "180 deg"\n', "pose.transmission_angle",
     "(0, 180) deg"),
    (RATIOS + '[section]\nwidth = "0 mm"\n', "section.width", "> 0"),
    (RATIOS + '[joints.A]\nmass = "-1 g"\n', "joints.A.mass", ">= 0"),
    (RATIOS + '[joints]\nKr = "-1 N*m/rad"\n', "joints.Kr", ">= 0"),
    (RATIOS + "[reference]\nEx = [1, 2]\n", "reference.Ex", "ends in _Hz"),
    ("[linkage]\nR2 = 0.267\nR3 = 0.8\n", "linkage.R4", "missing"),
])
def test_values_out_of_range_name_field_and_range(tmp_path, text, where, words):
    path = scene_file(tmp_path, text)
    with pytest.raises(InputError) as info:
        load_scene(path)
    message = str(info.value)
    assert message.startswith(f"{path}: {where}:") and words in message, message


def test_non_utf8_scene_is_an_input_error_naming_the_file(tmp_path):
    path = tmp_path / "binary.toml"
    path.write_bytes(b"name = 'x'\n\xff\xfe\x00")
    with pytest.raises(InputError, match=rf"{path}: not UTF-8 text \(byte 11, line 2\)"):
        load_scene(path)


def test_shipped_scenes_load_unchanged():
    kinds = {p.name: load_scene(p).kind for p in SHIPPED}
    assert kinds == {"case1.toml": "four-bar", "case2.toml": "four-bar", "case3.toml": "four-bar",
                     "case4.toml": "four-bar", "compliant_wiper.toml": "general",
                     "extended_rocker.toml": "general", "kineto_aluminium.toml": "general",
                     "rotor.toml": "general", "wiper.toml": "general",
                     "change_point.toml": "four-bar"}


def test_both_kinds_give_one_contract():
    four_bar, general = load_scene(CASE1), load_scene(ROOT / "scenes" / "kineto_aluminium.toml")
    assert type(four_bar) is type(general)
    # the four-bar's pose: mu = 90 deg at the crank angle of the closed form (law of cosines)
    fb = four_bar.four_bar
    L1, L2, L3, L4 = fb.lengths
    theta2 = math.acos((L1**2 + L2**2 - L3**2 - L4**2) / (2 * L1 * L2))  # cos mu = 0
    pose = four_bar.rigid_pose()
    assert pose.crank_angle == pytest.approx(theta2, abs=1e-12)
    assert pose.mu == pytest.approx(math.pi / 2, abs=1e-12)
    # the general scene's pose: its joints close the loop with the given lengths
    joints = general.rigid_pose().joints
    for a, b, length in (("O2", "A", 0.10795), ("A", "B", 0.2794), ("O4", "B", 0.27051)):
        assert math.dist(joints[a], joints[b]) == pytest.approx(length, rel=1e-12)


def test_hidden_default_g_is_a_listed_assumption():
    scene = load_scene(ROOT / "scenes" / "kineto_aluminium.toml")  # E and density, no G
    notes = {a.field: a for a in scene.assumptions}
    assert "material.G" in notes and "E / 2.6" in notes["material.G"].note
    assert scene.sections["coupler"].G == pytest.approx(71.016e9 / 2.6)
    # a scene that gives G lists no such assumption
    explicit = load_scene(ROOT / "scenes" / "kineto_aluminium.toml",
                          overrides={"material.G": "26.7 GPa"})
    assert "material.G" not in {a.field for a in explicit.assumptions}


def test_generated_reference_is_not_stale():
    committed = (ROOT / "docs" / "scene-reference.md").read_text()
    assert committed == reference_markdown(), \
        "regenerate: flexlink schema --markdown > docs/scene-reference.md"


def test_committed_json_schema_is_not_stale():
    committed = json.loads((ROOT / "docs" / "scene.schema.json").read_text())
    assert committed == json.loads(json.dumps(json_schema())), \
        "regenerate: flexlink schema --json --out /tmp/x > docs/scene.schema.json"


def test_reference_lists_every_declared_key_with_its_unit():
    text = reference_markdown()
    for row in ("| `width` | length | > 0 |", "| `Kt` | translational stiffness | >= 0 or 'rigid' |",
                "| `transmission_angle` | angle | (0, 180) deg |", "### `[joints.NAME]`",
                "### `[[family]]`"):
        assert row in text, row


def _as_written(path: Path) -> dict:
    data = tomllib.loads(path.read_text())
    if "base" in data:
        data = merge(tomllib.loads((path.parent / data["base"]).read_text()), data)
    return data


@pytest.fixture(scope="module")
def editor_validator():
    """The editor schema's validator, its schema checked against the meta-schema once (as
    ``jsonschema.validate`` does on every call)."""
    schema = json_schema()
    cls = jsonschema.validators.validator_for(schema)
    cls.check_schema(schema)
    return cls(schema)


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_editor_schema_accepts_shipped_scenes(path, editor_validator):
    editor_validator.validate(_as_written(path))


def test_editor_schema_rejects_a_typo_inside_a_noted_table(editor_validator):
    data = _as_written(ROOT / "scenes" / "wiper.toml")
    data["links"]["crank"]["section"]["widht"] = "1 mm"
    with pytest.raises(jsonschema.ValidationError, match="widht"):
        editor_validator.validate(data)


def test_rigid_tilt_default_is_listed_only_where_a_family_uses_it():
    planar = load_scene(CASE1)
    assert "joints.Ktilt" not in {a.field for a in planar.assumptions}
    out_of_plane = load_scene(CASE1, overrides={"model.family": "out-of-plane"})
    note = {a.field: a.note for a in out_of_plane.assumptions}["joints.Ktilt"]
    assert "O2, A, B, O4" in note and "rigid" in note
    given = load_scene(CASE1, overrides={"model.family": "3d", "joints.Ktilt": "10 N*m/rad"})
    assert "joints.Ktilt" not in {a.field for a in given.assumptions}
    assert set(given.options.tilt.values()) == {10.0}


def test_every_command_takes_a_general_scene_or_refuses_it_clearly(tmp_path):
    from click.testing import CliRunner

    from flexlink.cli import main

    wiper = str(ROOT / "scenes" / "wiper.toml")
    run = CliRunner().invoke(main, ["modes", wiper, "-e", "4", "--json", "--out", str(tmp_path)])
    assert run.exit_code == 0, run.output
    case = json.loads(run.stdout)["cases"][0]
    assert case["pose"]["theta2_deg"] == 0.0 and len(case["modes"]) == 4
    # the same frequencies as the library's analysis of the same scene
    from flexlink.analysis.modal import analyze
    expected = analyze(load_scene(wiper), 4, 4).elastic_frequencies(4)
    assert [m["computed_Hz"] for m in case["modes"]] == pytest.approx(expected, rel=1e-12)
    for command in (["verify"], ["calibrate", "--starts", "1"]):
        run = CliRunner().invoke(main, [command[0], wiper, *command[1:], "--out", str(tmp_path)])
        assert run.exit_code == 2 and "general scene" in run.stderr, run.output
        assert run.stderr.count("\n") == 1
