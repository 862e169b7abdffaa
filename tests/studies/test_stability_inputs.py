"""What the stability checks build from the user's scene, read without running the checks:
the change-point four-bar of the singular-pose checks, and the refusal of a general scene."""

import pytest
from conftest import SCENES_DIR

from flexlink import load_scene
from flexlink.errors import InputError
from flexlink.studies.verification import self_checks as st


def test_a_four_bar_given_by_lengths_becomes_the_change_point_one(tmp_path):
    """A four-bar written with lengths (not ratios) is changed to the lengths of
    scenes/change_point.toml, 300, 100, 250 and 150 mm, whatever its own lengths were."""
    text = (SCENES_DIR / "change_point.toml").read_text()
    own = text.replace('ground = "300 mm"', 'ground = "400 mm"').replace(
        'crank = "100 mm"', 'crank = "120 mm"').replace(
        'coupler = "250 mm"', 'coupler = "330 mm"').replace('rocker = "150 mm"', 'rocker = "260 mm"')
    assert own.count("mm") == text.count("mm") and own != text
    path = tmp_path / "by_lengths.toml"
    path.write_text(own)
    fb = st._change_point(load_scene(path)).four_bar
    # the scene's lengths pass through mm -> m only: equal to 1e-15 m
    assert (fb.ground, fb.crank, fb.coupler, fb.rocker) == pytest.approx(
        (0.300, 0.100, 0.250, 0.150), abs=1e-15)


def test_a_general_scene_is_refused_naming_its_file_and_field():
    path = SCENES_DIR / "wiper.toml"
    with pytest.raises(InputError) as refused:
        st.run_checks(load_scene(path))
    assert str(refused.value.source) == str(path) and refused.value.field == "linkage.type"
    assert str(path) in str(refused.value)
