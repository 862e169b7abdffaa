"""Claims of the scene stage that the mutation runs found unguarded (docs/testing.md, fourth
round): the messages' stated contents and the scene's conventions."""

import pytest
from conftest import SCENES_DIR

from flexlink.errors import InputError
from flexlink.scene import load_scene


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
