"""Grashof's criterion with its equality, and poses at exact toggles (dead centres, the flat
pose of a change-point linkage): oracles from the geometry of the diagonal O4-A."""

import math

import pytest
from conftest import SCENES_DIR
from hypothesis import given
from hypothesis import strategies as st

from flexlink.errors import KinematicsError
from flexlink.kinematics.fourbar import FourBar
from flexlink.scene import RigidPose, load_scene
from flexlink.scene.plausibility import pose_warnings

CHANGE_POINT = FourBar(0.300, 0.100, 0.250, 0.150)  # 100 + 300 = 250 + 150 mm
FOLDED = FourBar(0.300, 0.200, 0.300, 0.150)  # reaches |coupler - rocker| = 150 mm: mu = 0


def _turns_by_diagonal(fb: FourBar) -> bool:
    """The crank turns fully iff the diagonal O4-A, which runs from |L1 - L2| (crank along the
    ground line) to L1 + L2 (crank opposite), always stays within [|L3 - L4|, L3 + L4]: the
    range where coupler and rocker can span it. Equality is a toggle, which closes."""
    L1, L2, L3, L4 = fb.lengths
    return L1 + L2 <= L3 + L4 and abs(L1 - L2) >= abs(L3 - L4)


lengths = st.integers(min_value=1, max_value=60)  # whole mm: the equality cases are drawn too


@given(lengths, lengths, lengths, lengths)
def test_crank_turns_fully_is_grashof_with_its_equality(l1, l2, l3, l4):
    ls = sorted((l1, l2, l3, l4))
    if ls[3] >= sum(ls[:3]):
        return  # cannot close at all: FourBar refuses it
    fb = FourBar(l1 / 1e3, l2 / 1e3, l3 / 1e3, l4 / 1e3)
    assert fb.crank_turns_fully() == _turns_by_diagonal(fb), fb.lengths


@pytest.mark.parametrize("fb", [CHANGE_POINT, FourBar(0.3, 0.1, 0.3, 0.1)],
                         ids=["change-point", "parallelogram"])
def test_change_point_crank_closes_at_every_angle(fb):
    # the crank turns fully: the closed form gives a pose at every crank angle, the flat
    # pose included (exact multiples of 1 deg hit 180 deg)
    assert fb.grashof_class() == "change-point" and fb.crank_turns_fully()
    for k in range(360):
        fb.pose(math.radians(k))


def test_change_point_scene_warns_of_its_flat_pose_not_of_a_limited_crank():
    scene = load_scene(SCENES_DIR / "change_point.toml")
    warnings = pose_warnings(scene.four_bar, scene.rigid_pose())
    assert not any("cannot turn fully" in w for w in warnings), warnings
    assert any("change-point" in w and "180 deg" in w and "flat pose" in w for w in warnings)


def test_non_grashof_still_warns_that_the_crank_cannot_turn():
    triple = FourBar.from_ratios(0.6, 0.7, 0.8, 0.3)
    pose = triple.pose(0.0)
    assert not triple.crank_turns_fully()
    warnings = pose_warnings(triple, RigidPose(0.0, pose.joints, {"coupler/rocker": pose.mu},
                                               "open"))
    assert any("cannot turn fully" in w for w in warnings)


def _folded_limit(fb: FourBar) -> float:
    """Crank angle [rad] where the diagonal O4-A equals |coupler - rocker| (law of cosines)."""
    L1, L2, L3, L4 = fb.lengths
    return math.acos((L1**2 + L2**2 - (L3 - L4) ** 2) / (2 * L1 * L2))


@pytest.mark.parametrize("fb,theta,mu", [(FOLDED, _folded_limit(FOLDED), 0.0),
                                          (CHANGE_POINT, math.pi, math.pi)],
                         ids=["folded dead centre", "change-point flat pose"])
def test_exact_toggle_is_a_pose(fb, theta, mu):
    pose = fb.pose(theta)
    L1, _, L3, L4 = fb.lengths
    A, B = pose.joints["A"], pose.joints["B"]
    # the loop closes: link lengths to round-off of metre-sized coordinates
    assert math.dist(A, B) == pytest.approx(L3, abs=1e-12)
    assert math.dist((L1, 0.0), B) == pytest.approx(L4, abs=1e-12)
    # mu = 0 or 180 deg: sqrt of the round-off in cos mu, about 1e-8 rad
    assert pose.mu == pytest.approx(mu, abs=1e-6)


def test_beyond_a_folded_toggle_the_error_names_the_bound_that_fails():
    with pytest.raises(KinematicsError) as info:
        FOLDED.pose(_folded_limit(FOLDED) - 1e-3)
    message = str(info.value)
    assert "shorter than |coupler - rocker|" in message and "0.15 m" in message
    assert "tolerance" in message and "coupler + rocker must span" not in message


def test_beyond_an_extended_toggle_the_error_names_the_bound_that_fails():
    triple = FourBar.from_ratios(0.6, 0.7, 0.8, 0.3)
    with pytest.raises(KinematicsError, match=r"longer than coupler \+ rocker"):
        triple.pose(math.pi)


@pytest.mark.parametrize("fb,count", [(CHANGE_POINT, 1), (FOLDED, 4),
                                      (FourBar(0.3, 0.08, 0.24, 0.2), 0)],
                         ids=["change-point", "double-rocker", "crank-rocker"])
def test_dead_centres_are_where_coupler_and_rocker_line_up(fb, count):
    found = fb.dead_centres()
    assert len(found) == count
    for theta in found:
        pose = fb.pose(theta)
        # coupler and rocker collinear: B, A and O4 on one line. The cross product is
        # L3 L4 sin(mu); acos near +-1 loses half the digits, so theta and mu are good to a
        # few sqrt(eps) ~ 1e-8 rad: sin(mu) < 1e-7
        (ax, ay), (bx, by), (ox, oy) = pose.joints["A"], pose.joints["B"], pose.joints["O4"]
        cross = abs((ax - bx) * (oy - by) - (ay - by) * (ox - bx))
        assert cross < 1e-7 * fb.coupler * fb.rocker
