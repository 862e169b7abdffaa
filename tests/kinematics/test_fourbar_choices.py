"""The four-bar's choices are enums converted at the edge (``kinematics.fourbar``): a branch
given as text is the same pose as its member, the Grashof class is a member whose JSON is the
text it always had, and a word that is no branch names the field and every choice."""

import json
import math

import pytest

from flexlink.errors import InputError
from flexlink.kinematics import Branch, FourBar, GrashofClass

CRANK_ROCKER = FourBar(0.3, 0.08, 0.24, 0.2)  # s + l = 0.38 < p + q = 0.44, crank shortest


@pytest.mark.parametrize("branch", list(Branch))
def test_a_branch_as_text_is_the_pose_of_its_member(branch):
    by_text = CRANK_ROCKER.pose(math.radians(40), branch.value)
    by_member = CRANK_ROCKER.pose(math.radians(40), branch)
    assert by_text.branch is branch and by_member.branch is branch
    assert by_text.joints == by_member.joints  # the same closed form, bit for bit


def test_the_two_branches_mirror_b_about_the_diagonal():
    """B of the open and crossed poses are mirror images about the diagonal O4-A: the same
    distances to O4 and A, on either side (cross products of opposite sign)."""
    q = math.radians(40)
    a, b_open = (CRANK_ROCKER.pose(q, Branch.OPEN).joints[k] for k in ("A", "B"))
    b_crossed = CRANK_ROCKER.pose(q, Branch.CROSSED).joints["B"]
    o4 = (CRANK_ROCKER.ground, 0.0)

    def side(b):
        return (a[0] - o4[0]) * (b[1] - o4[1]) - (a[1] - o4[1]) * (b[0] - o4[0])
    assert side(b_open) < 0 < side(b_crossed)
    for p in (a, o4):
        assert math.dist(b_open, p) == pytest.approx(math.dist(b_crossed, p), rel=1e-12)


def test_a_word_that_is_no_branch_names_the_field_and_the_choices():
    with pytest.raises(InputError) as info:
        CRANK_ROCKER.pose(0.3, "sideways")
    assert info.value.field == "branch" and info.value.expected == "open or crossed"
    assert "'sideways'" in str(info.value)


@pytest.mark.parametrize("lengths, kind, text", [
    ((0.3, 0.08, 0.24, 0.2), GrashofClass.CRANK_ROCKER, "crank-rocker"),
    ((0.2, 1.0, 1.0, 1.0), GrashofClass.DOUBLE_CRANK, "double-crank"),
    ((2.0, 3.0, 1.0, 2.5), GrashofClass.DOUBLE_ROCKER, "double-rocker"),
    ((1.0, 0.5, 1.0, 0.5), GrashofClass.CHANGE_POINT, "change-point"),
    ((1.0, 0.9, 0.8, 0.85), GrashofClass.NON_GRASHOF, "non-Grashof"),
])
def test_the_grashof_class_is_a_member_with_its_text_in_json(lengths, kind, text):
    """Grashof's sums decide: s + l against p + q, then which link is shortest."""
    found = FourBar(*lengths).grashof_class()
    assert found is kind
    assert json.dumps({"grashof": found}) == json.dumps({"grashof": text})
    assert f"{found}" == text  # messages and the text report show the word
