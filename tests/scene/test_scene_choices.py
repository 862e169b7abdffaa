"""The scene's choices come out of the schema as enum members (``schema.choice``), so no stage
compares their text; a word that is not a choice stops the CLI with one line naming the file,
the key and every choice."""

from click.testing import CliRunner

from flexlink.cli import main
from flexlink.kinematics import Branch
from flexlink.materials.mixtures import ShearSource
from flexlink.scene import load_scene
from flexlink.scene.contract import SceneKind
from flexlink.scene.load import BUILDERS

from conftest import CASES_DIR, SCENES_DIR


def test_choices_are_members_after_loading():
    four_bar = load_scene(CASES_DIR / "case1.toml", {"pose.branch": "crossed",
                                                     "material.composite.shear_modulus":
                                                         "isotropic"})
    assert four_bar.kind is SceneKind.FOUR_BAR and four_bar.branch is Branch.CROSSED
    assert four_bar.composite.shear_modulus is ShearSource.ISOTROPIC
    general = load_scene(SCENES_DIR / "extended_rocker.toml")
    assert general.kind is SceneKind.GENERAL and general.branch is Branch.OPEN


def test_every_scene_kind_has_a_builder():
    assert set(BUILDERS) == set(SceneKind)


def test_an_unknown_linkage_type_is_one_line_naming_file_field_and_choices(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text((SCENES_DIR / "extended_rocker.toml").read_text()
                    .replace('type = "general"', 'type = "five-bar"', 1))
    result = CliRunner().invoke(main, ["modes", str(path), "-e", "2", "--out",
                                       str(tmp_path / "out")])
    assert result.exit_code == 2, result.output
    assert result.stderr.strip() == (f"flexlink: error: {path}: linkage: unknown type "
                                      "'five-bar' (expected one of 'four-bar', 'general')")
