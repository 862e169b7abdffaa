"""Four-bar kinematics against FACTS.md and against independent computations."""

import math

import numpy as np
import pytest

from flexlink.errors import KinematicsError
from flexlink.kinematics.fourbar import FourBar

TABLE2 = {1: (0.267, 0.800, 0.667), 2: (0.417, 1.000, 0.792), 3: (0.141, 0.900, 0.457),
          4: (0.209, 0.914, 0.457)}
# paper's stated mu limits [deg]: cases 1, 2 as printed; cases 3, 4 are designed as 90 -+ delta
PAPER_MU = {1: (59.17, 119.18), 2: (35.7, 103.9), 3: (70.0, 110.0), 4: (60.0, 120.0)}
# Table II prints R to 3 decimals; that rounding alone moves mu by up to 0.29 deg
# (first order, computed per case in test_design_mu_limits_within_what_rounding_of_r_explains)
ROUNDING_DEG = 0.3


def fourbar(case, ground=1.0):
    return FourBar.from_ratios(*TABLE2[case], ground=ground)


@pytest.mark.parametrize("case", [1, 2, 3, 4])
def test_mu_limits_match_the_paper(case):
    mu_min, mu_max = np.degrees(fourbar(case).transmission_limits())
    lo, hi = PAPER_MU[case]
    tol = 0.1 if case in (1, 2) else ROUNDING_DEG
    assert abs(mu_min - lo) < tol and abs(mu_max - hi) < tol, (mu_min, mu_max)


def _rounding_envelope(case):
    """Largest change of mu_min or mu_max [deg] that moving each printed ratio by half its last
    digit (0.0005) can cause, summed over the three ratios (first order)."""
    base = np.array(TABLE2[case])
    nominal = np.array(fourbar(case).transmission_limits())
    total = 0.0
    for i in range(3):
        worst = 0.0
        for sign in (-1, 1):
            r = base.copy()
            r[i] += sign * 0.0005
            moved = np.array(FourBar.from_ratios(*r, ground=1.0).transmission_limits())
            worst = max(worst, np.degrees(np.abs(moved - nominal)).max())
        total += worst
    return total


@pytest.mark.parametrize("case", [3, 4])
def test_design_mu_limits_within_what_rounding_of_r_explains(case):
    """Cases 3, 4 are designed as 90 -+ delta; the computed limits may miss the design values
    only by what the 3-decimal rounding of R can cause (not by a fixed allowance)."""
    envelope = _rounding_envelope(case)
    mu_min, mu_max = np.degrees(fourbar(case).transmission_limits())
    lo, hi = PAPER_MU[case]
    assert abs(mu_min - lo) <= envelope and abs(mu_max - hi) <= envelope, (mu_min, mu_max, envelope)


def _mu_from_triangle(L1, L2, L3, L4, theta2):
    """Transmission angle [rad] by hand: the diagonal A-O4 from triangle O2-A-O4, then the angle
    at B of triangle A-B-O4 (law of cosines twice)."""
    diag2 = L1**2 + L2**2 - 2 * L1 * L2 * math.cos(theta2)
    return math.acos((L3**2 + L4**2 - diag2) / (2 * L3 * L4))


@pytest.mark.parametrize("case", [1, 2, 3, 4])
@pytest.mark.parametrize("theta_deg", [0.0, 37.0, 90.0, 151.0, 180.0, 290.0])
def test_transmission_angle_equals_the_law_of_cosines(case, theta_deg):
    fb = fourbar(case, ground=0.3)
    theta = math.radians(theta_deg)
    expected = _mu_from_triangle(*fb.lengths, theta)
    assert math.isclose(float(fb.transmission_angle(theta)), expected, abs_tol=1e-12)
    # and the angle between B->A and B->O4 in the solved pose (a third path: coordinates)
    j = {k: np.array(v) for k, v in fb.pose(theta).joints.items()}
    u, v = j["A"] - j["B"], j["O4"] - j["B"]
    angle = math.acos(np.dot(u, v) / (np.linalg.norm(u) * np.linalg.norm(v)))
    assert math.isclose(angle, expected, abs_tol=1e-9)


@pytest.mark.parametrize("case", [1, 2, 3, 4])
def test_mu_min_at_theta_0_and_mu_max_at_180_deg(case):
    """mu_min has the diagonal L1 - L2, mu_max the diagonal L1 + L2 (hand calculation)."""
    L1, L2, L3, L4 = fourbar(case).lengths
    mu_min, mu_max = fourbar(case).transmission_limits()
    assert math.isclose(math.cos(mu_min), (L3**2 + L4**2 - (L1 - L2) ** 2) / (2 * L3 * L4),
                        abs_tol=1e-12)
    assert math.isclose(math.cos(mu_max), (L3**2 + L4**2 - (L1 + L2) ** 2) / (2 * L3 * L4),
                        abs_tol=1e-12)
    assert mu_min < mu_max


@pytest.mark.parametrize("mu_deg", [75.0, 90.0, 105.0])
def test_crank_angles_for_mu_invert_the_triangle(mu_deg):
    """Away from 90 deg the cos(mu) term matters: the crank angle by hand is
    cos theta2 = (L1^2 + L2^2 - d^2) / (2 L1 L2), d^2 = L3^2 + L4^2 - 2 L3 L4 cos mu."""
    fb = fourbar(1, ground=0.3)
    L1, L2, L3, L4 = fb.lengths
    mu = math.radians(mu_deg)
    d2 = L3**2 + L4**2 - 2 * L3 * L4 * math.cos(mu)
    theta = math.acos((L1**2 + L2**2 - d2) / (2 * L1 * L2))
    a, b = fb.crank_angles_for_mu(mu)
    assert math.isclose(a, theta, abs_tol=1e-12)
    assert math.isclose(b, 2 * math.pi - theta, abs_tol=1e-12)
    assert math.isclose(_mu_from_triangle(L1, L2, L3, L4, a), mu, abs_tol=1e-12)


@pytest.mark.parametrize("case", [1, 2, 3, 4])
def test_swing_angle_closed_form_equals_sampled_cycle(case):
    fb = fourbar(case, ground=0.3)
    theta = np.linspace(0, 2 * math.pi, 20001)
    theta4 = np.unwrap([fb.pose(t).theta4 for t in theta])
    sampled = np.degrees(theta4.max() - theta4.min())
    assert abs(np.degrees(fb.rocker_swing()) - sampled) < 0.1 * 1e-2


def test_swing_angles_differ_from_the_paper_as_reported():
    """The paper prints 46.8, 66.9, 33.9, 50.7 deg; the geometry of Table II gives 47.20, 68.27,
    35.94, 54.43 deg (checked two ways above). Kept here so docs/table2.md's statement is tested."""
    ours = [round(math.degrees(fourbar(c).rocker_swing()), 2) for c in (1, 2, 3, 4)]
    assert ours == [47.20, 68.27, 35.94, 54.43]


@pytest.mark.parametrize("case", [1, 2, 3, 4])
@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_pose_at_mu_90_closes_the_loop(case, branch):
    fb = fourbar(case, ground=0.3)
    pose = fb.pose_at_mu(math.pi / 2, branch)
    j = {k: np.array(v) for k, v in pose.joints.items()}
    assert math.isclose(np.linalg.norm(j["A"] - j["O2"]), fb.crank, rel_tol=1e-12)
    assert math.isclose(np.linalg.norm(j["B"] - j["A"]), fb.coupler, rel_tol=1e-12)
    assert math.isclose(np.linalg.norm(j["B"] - j["O4"]), fb.rocker, rel_tol=1e-12)
    u, v = j["A"] - j["B"], j["O4"] - j["B"]
    assert abs(np.dot(u, v)) < 1e-12  # coupler perpendicular to rocker
    # open branch: B on the clockwise side of the diagonal O4 -> A
    d = j["A"] - j["O4"]
    cross = d[0] * (j["B"] - j["O4"])[1] - d[1] * (j["B"] - j["O4"])[0]
    assert (cross < 0) == (branch == "open")


def test_grashof_classes():
    assert fourbar(1).grashof_class() == "crank-rocker"
    assert FourBar(2.0, 3.0, 1.0, 2.5).grashof_class() == "double-rocker"
    assert FourBar(0.2, 1.0, 1.0, 1.0).grashof_class() == "double-crank"
    assert FourBar(1.0, 0.9, 0.8, 0.85).grashof_class() == "non-Grashof"
    assert FourBar(1.0, 0.5, 1.0, 0.5).grashof_class() == "change-point"


def test_unreachable_mu_and_unclosable_linkage_are_clear_errors():
    with pytest.raises(KinematicsError, match="not reachable"):
        fourbar(3).pose_at_mu(math.radians(45))
    with pytest.raises(KinematicsError, match="cannot close"):
        FourBar(1.0, 0.1, 0.2, 0.3)
    with pytest.raises(KinematicsError, match="crank"):
        FourBar(1.0, 0.9, 0.8, 0.85).transmission_limits()
