"""``plausibility.given_fields``: the set form of ``Scene.has_field`` the plausibility checks use
(a calibration evaluation asks it ~50 times)."""


import pytest

from flexlink.scene import load_scene
from flexlink.scene.plausibility import given_fields

from conftest import ROOT
SCENES = [ROOT / "cases" / f"case{i}.toml" for i in (1, 2, 3, 4)] + [ROOT / "scenes" / "wiper.toml"]


@pytest.mark.parametrize("path", SCENES, ids=lambda p: p.stem)
def test_given_fields_is_has_field_as_a_set(path):
    scene = load_scene(path, overrides={"section.width": "21 mm"})
    present = given_fields(scene.origin)
    assert "section.width" in present  # the override is a given field
    # every given field, near misses (a longer name, an unknown sibling) and the checks' own
    candidates = (present | {k + "x" for k in present}
                  | {k.rpartition(".")[0] + ".nope" for k in present}
                  | {"linkage.ground", "material", "material.E", "links.crank.section.width"})
    for field in candidates:
        assert (field in present) == scene.has_field(field), field
