"""Claims of the scene stage that the mutation runs found unguarded (docs/testing.md, fourth
round): the messages' stated contents and the scene's conventions."""

import pytest
from conftest import CASES_DIR, SCENES_DIR

from flexlink.errors import InputError
from flexlink.scene import load_scene
from flexlink.scene.source import read_scene_source


def _refusal(tmp_path, text: str) -> InputError:
    path = tmp_path / "scene.toml"
    path.write_text(text)
    with pytest.raises(InputError) as refusal:
        load_scene(path)
    return refusal.value


def test_a_key_of_another_synthesis_method_says_which_method_declares_it(tmp_path):
    """The tagged table here is two levels down ([linkage] type = "general", then
    [linkage.synthesis] method = ...): the key must be looked up among the synthesis methods,
    not among the linkage kinds."""
    text = (SCENES_DIR / "extended_rocker.toml").read_text()
    assert "k = 1.0\n" in text
    error = _refusal(tmp_path, text.replace("k = 1.0\n", 'k = 1.0\ntheta4i = "30 deg"\n', 1))
    assert error.field == "linkage.synthesis.theta4i"
    assert ("unknown key for method = 'extended-rocker': 'theta4i' belongs to "
            "method = 'minimax'") in str(error)


def test_a_table_the_scene_replaces_whole_takes_its_origin_from_the_scene(tmp_path):
    """A [material] table replaces the base's whole (source.merge), so none of the base's
    material keys is left, and the table's file, for messages, is the scene's own."""
    path = tmp_path / "steel.toml"
    path.write_text(f'base = "{(CASES_DIR / "case1.toml").as_posix()}"\n'
                    '[material]\nisotropic = "steel"\n')
    src = read_scene_source(path)
    material = {k: v for k, v in src.origin.items() if k.split(".")[0] == "material"}
    assert material == {"material.isotropic": str(path)}
    assert src.file_of("material") == str(path)
    assert src.file_of("linkage.R2") == str(CASES_DIR / "case1.toml")  # the rest keeps its file
