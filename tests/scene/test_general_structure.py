"""General scenes whose beams are not the linkage they describe (scene/general.py): a beam
across two bodies is refused; beams that do not form their rigid body, and joints with no
translational stiffness, are warned about, and the model shows what the warning says."""

import logging

import pytest
from conftest import SCENES_DIR

from flexlink.analysis.modal import pose_modes
from flexlink.errors import InputError
from flexlink.scene import load_scene

WIPER = SCENES_DIR / "wiper.toml"
FOUR_BAR = SCENES_DIR / "kineto_aluminium.toml"
LOGGER = "flexlink.scene.general"


def _mechanism_modes(scene, elements=4):
    """Rigid-body/mechanism modes of the scene's model at its pose (a coarse mesh: the count
    does not depend on it)."""
    _, modes, _ = pose_modes(scene.topology(elements), scene.rigid_pose().joints, 2)
    return len(modes.kinds) - len(modes.elastic)


def test_a_beam_across_two_bodies_is_an_error_naming_it():
    # link1 from a (crank, link1) to d (link2, rocker2): no body holds both
    with pytest.raises(InputError) as info:
        load_scene(WIPER, overrides={"links.link1.end": "d"})
    message = str(info.value)
    assert "links.link1" in message and "'link1'" in message and "no one body" in message


def test_a_compliant_strip_may_span_a_pin():
    # the [prb] strip runs from the coupler's clamp to the rocker's ground pivot on purpose
    load_scene(SCENES_DIR / "compliant_wiper.toml")


def test_the_shipped_scenes_draw_no_structure_warning(caplog):
    with caplog.at_level(logging.WARNING, logger=LOGGER):
        for path in (WIPER, FOUR_BAR, SCENES_DIR / "change_point.toml"):
            load_scene(path)
    assert not [r for r in caplog.records if r.name == LOGGER]


def test_beams_of_a_body_on_a_pin_warn_and_are_a_mechanism(caplog):
    with caplog.at_level(logging.WARNING, logger=LOGGER):
        loose = load_scene(WIPER, overrides={"joints.O2.welded": False})
    [record] = [r for r in caplog.records if r.name == LOGGER]
    text = record.getMessage()
    assert "rocker1" in text and "arm_b, arm_c" in text and "O2" in text and "welded" in text
    # what the warning says: one mechanism mode more than the welded rocker has (none)
    assert _mechanism_modes(load_scene(WIPER)) == 0
    assert _mechanism_modes(loose) == 1


def test_zero_translational_stiffness_warns_that_the_links_are_disconnected(caplog):
    with caplog.at_level(logging.WARNING, logger=LOGGER):
        free = load_scene(FOUR_BAR, overrides={"joints.Kt": "0 N/m"})
    [record] = [r for r in caplog.records if r.name == LOGGER]
    assert "Kt = 0" in record.getMessage() and "disconnected" in record.getMessage()
    # three free-free beams: 3 in-plane rigid-body modes each, less the crank rotation that
    # the rigid drive holds
    assert _mechanism_modes(free) == 3 * len(free.links) - 1
