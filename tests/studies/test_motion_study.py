"""The rigid-motion study's result types check themselves on construction (each wrong field
refused with a message naming it); the rocker's swing and time ratio against the closed-form
toggle positions of the four-bar; the JSON document keeps its field names."""

import dataclasses
import math

import pytest

from flexlink.kinematics.motion import Extremes
from flexlink.output.cycle.rigid_motion import kinematics_document
from flexlink.scene import load_scene
from flexlink.studies.cycle.rigid_motion import BodyMotion, motion_study

from conftest import CASES_DIR

SPEED = 10.0  # rad/s: any nonzero crank speed, so omega and alpha are part of the study


@pytest.fixture(scope="module")
def study():
    return motion_study(load_scene(CASES_DIR / "case1.toml"), 36, SPEED)


def test_the_rocker_swings_between_the_closed_form_toggles(study):
    """Crank and coupler collinear, |O2 B| = L3 + L2 (extended) or L3 - L2 (folded): the law
    of cosines in O2 O4 B gives the crank angles, and the rocker angle there; the swing is
    their difference and the time ratio the longer crank turn between them over the shorter."""
    fb = study.scene.four_bar
    L1, L2, L3, L4 = fb.ground, fb.crank, fb.coupler, fb.rocker
    crank, rocker = [], []
    for d, turn in ((L3 + L2, 0.0), (L3 - L2, math.pi)):
        phi = math.acos((L1**2 + d**2 - L4**2) / (2 * L1 * d))  # O2->B above O2->O4
        crank.append(math.degrees(phi + turn) % 360)
        beta = math.acos((L1**2 + L4**2 - d**2) / (2 * L1 * L4))  # at O4, between O4->O2 and O4->B
        rocker.append(180.0 - math.degrees(beta))
    body = study.bodies["rocker"]
    forward = (crank[1] - crank[0]) % 360
    # Newton on K to |K| < 1e-13 leaves the toggles ~1e-12 deg off; 1e-8 is ample
    assert body.swing == pytest.approx(abs(rocker[1] - rocker[0]), abs=1e-8)
    assert body.time_ratio == pytest.approx(max(forward, 360 - forward)
                                            / min(forward, 360 - forward), rel=1e-9)
    assert study.bodies["crank"].limits == () and study.bodies["crank"].swing is None


def test_a_wrong_cycle_shape_is_refused_naming_it(study):
    short = dataclasses.replace(study.cycle, K=study.cycle.K[:-1])
    with pytest.raises(ValueError, match=r"MotionStudy\.cycle\.K"):
        dataclasses.replace(study, cycle=short)


def test_bodies_must_be_the_cycles_bodies(study):
    bodies = {k: v for k, v in study.bodies.items() if k != "coupler"}
    with pytest.raises(ValueError, match=r"MotionStudy\.bodies has"):
        dataclasses.replace(study, bodies=bodies)


def test_omega_is_given_exactly_at_a_crank_speed(study):
    with pytest.raises(ValueError, match=r"MotionStudy\.bodies\['crank'\] has omega given"):
        dataclasses.replace(study, crank_speed=None)


@pytest.mark.parametrize("change, named", [
    ({"swing": None}, "BodyMotion.swing"),
    ({"time_ratio": None}, "BodyMotion.time_ratio"),
    ({"time_ratio": 0.5}, "BodyMotion.time_ratio is 0.5"),
    ({"limits": ()}, "BodyMotion.swing"),
])
def test_a_body_without_the_parts_its_limit_positions_imply_is_refused(study, change, named):
    with pytest.raises(ValueError, match=named.replace(".", r"\.")):
        dataclasses.replace(study.bodies["rocker"], **change)


def test_a_time_ratio_needs_exactly_two_limit_positions(study):
    rocker = study.bodies["rocker"]
    with pytest.raises(ValueError, match=r"BodyMotion\.time_ratio"):
        BodyMotion(rocker.summary, rocker.limits[:1] + rocker.limits, rocker.swing, 1.0)


def test_omega_alpha_and_peak_alpha_come_together(study):
    summary = study.bodies["rocker"].summary
    with pytest.raises(ValueError, match=r"BodySummary has only some"):
        dataclasses.replace(summary, peak_alpha=None)
    assert dataclasses.replace(summary, omega=None, alpha=None, peak_alpha=None).omega is None


@pytest.mark.parametrize("values, named", [
    ((2.0, 0.0, 1.0, 0.0), "Extremes.min"),
    ((0.0, -1.0, 1.0, 0.0), "Extremes.min_at_deg"),
    ((0.0, 0.0, 1.0, 361.0), "Extremes.max_at_deg"),
])
def test_extremes_are_ordered_and_at_crank_angles_of_one_turn(values, named):
    with pytest.raises(ValueError, match=named.replace(".", r"\.")):
        Extremes(*values)


def test_the_document_keeps_its_field_names(study):
    """The names (and order) of the JSON document's fields, which scripts read."""
    doc = kinematics_document(study, (), ["a.csv"])
    assert list(doc) == ["command", "poses", "crank_speed_rev_per_min", "scene", "synthesis",
                         "bodies", "transmission_angle_deg", "family", "files", "assumptions"]
    assert doc["crank_speed_rev_per_min"] == pytest.approx(SPEED * 60 / (2 * math.pi),
                                                           rel=1e-15)
    assert list(doc["bodies"]["crank"]) == ["angle_deg", "K", "L", "omega_rad_s",
                                            "alpha_rad_s2", "peak_abs_alpha"]
    assert list(doc["bodies"]["rocker"]) == [
        "angle_deg", "K", "L", "torque_ratio_min_abs", "omega_rad_s", "alpha_rad_s2",
        "peak_abs_alpha", "limit_positions", "swing_deg", "time_ratio"]
    rocker = doc["bodies"]["rocker"]
    assert list(rocker["limit_positions"][0]) == ["crank_deg", "angle_deg", "K"]
    assert list(rocker["torque_ratio_min_abs"]) == ["value", "at_deg"]
    assert list(rocker["peak_abs_alpha"]) == ["value_rad_s2", "at_deg"]
    assert list(doc["transmission_angle_deg"]["coupler/rocker"]) == [
        "min", "min_at_deg", "max", "max_at_deg"]


def test_an_extreme_at_360_deg_is_allowed():
    """x % 360.0 rounds to 360.0 for x just below 0, so an extreme may be found there."""
    assert Extremes(0.0, 0.0, 1.0, 360.0).max_at_deg == 360.0
