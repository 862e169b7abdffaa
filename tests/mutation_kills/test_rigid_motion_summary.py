"""Rigid kinematics against closed forms and the schema of its refusals: what mutants of
flexlink/kinematics/ showed the suite did not check (docs/testing.md, mutation testing).

The four-bar of Table II case 1 (L1 = 1 m) is the reference: its closed-form pose
(``FourBar.pose``, law of cosines) is independent of the general linkage's Newton solver."""

import math

import numpy as np
import pytest

from flexlink.errors import InputError
from flexlink.kinematics import FourBar
from flexlink.kinematics.linkage import crank_angles, crossings, four_bar_linkage
from flexlink.kinematics.motion import body_summary, limit_positions
from flexlink.output.cycle.rigid_motion import motion_csv
from flexlink.kinematics.synthesis import brodell_soni, minimax

CASE1 = FourBar.from_ratios(0.267, 0.800, 0.667, ground=1.0)


@pytest.fixture(scope="module")
def cycle():
    linkage = four_bar_linkage(*CASE1.lengths)
    q = crank_angles(72)
    return linkage, linkage.cycle(q, CASE1.pose(q[0]).joints)


def rocker_velocity_ratio(fb: FourBar, theta2: float) -> float:
    """omega4 / omega2 of a four-bar from its closed-form pose: the loop equation's derivative
    gives omega4 / omega2 = L2 sin(theta3 - theta2) / (L4 sin(theta3 - theta4))."""
    p = fb.pose(theta2)
    return fb.crank * math.sin(p.theta3 - p.theta2) / (fb.rocker * math.sin(p.theta3 - p.theta4))


def test_a_crank_has_no_angle_extremes_and_a_rocker_swings_its_closed_form_angle(cycle):
    """A body turning fully has no extreme angle; the rocker's sampled extremes span at most
    the closed-form swing, and within the sampling step's second-order error of it."""
    _, cyc = cycle
    assert body_summary(cyc, "crank", None).angle is None
    rocker = body_summary(cyc, "rocker", None, output=True).angle
    swing = math.degrees(CASE1.rocker_swing())
    sampled = rocker.max - rocker.min
    # a sampled extreme misses the true one by O(h^2): with 5 deg steps well under 1 deg
    assert swing - 1.0 < sampled <= swing + 1e-9


def test_angular_speed_and_acceleration_scale_as_w_and_w_squared(cycle):
    """At a constant crank speed w: omega = K w and alpha = L w^2, so doubling w doubles every
    omega and multiplies every alpha by 4 (CSV rows and summary alike)."""
    _, cyc = cycle
    one, two = (body_summary(cyc, "rocker", w, output=True) for w in (1.5, 3.0))
    for key in ("min", "max"):
        assert getattr(two.omega, key) == pytest.approx(2 * getattr(one.omega, key), rel=1e-12)
        assert getattr(two.alpha, key) == pytest.approx(4 * getattr(one.alpha, key), rel=1e-12)
    assert two.peak_alpha.value == pytest.approx(4 * one.peak_alpha.value, rel=1e-12)
    assert two.peak_alpha.value == pytest.approx(
        max(abs(two.alpha.min), abs(two.alpha.max)), rel=1e-12)

    def columns(w):
        lines = motion_csv(cyc, w).splitlines()
        head = lines[0].split(",")
        rows = np.array([[float(v) for v in line.split(",")] for line in lines[1:]])
        return rows[:, head.index("rocker_omega_rad_s")], rows[:, head.index("rocker_alpha_rad_s2")]

    (om1, al1), (om2, al2) = columns(1.5), columns(3.0)
    assert np.allclose(om2, 2 * om1, rtol=1e-9, atol=0)  # 10 significant digits in the CSV
    assert np.allclose(al2, 4 * al1, rtol=1e-9, atol=0)


def test_least_torque_ratio_is_one_over_the_largest_velocity_ratio(cycle):
    """Virtual work, T2 w2 + T4 w4 = 0: |T4 / T2| = 1 / |w4 / w2|, smallest where the rocker
    is fastest. The velocity ratio comes from the closed-form pose at the same samples."""
    _, cyc = cycle
    ratios = np.abs([rocker_velocity_ratio(CASE1, q) for q in cyc.q])
    summary = body_summary(cyc, "rocker", None, output=True).torque_ratio
    # the Newton solve meets the closed form to ~1e-12; 1e-9 leaves room for its tolerance
    assert summary.value == pytest.approx(1 / ratios.max(), rel=1e-9)
    assert summary.at_deg == pytest.approx(math.degrees(cyc.q[np.argmax(ratios)]) % 360)


def test_limit_positions_are_the_closed_form_toggles(cycle):
    """The rocker stops where crank and coupler are collinear: |O2 B| = L3 + L2 (extended) or
    L3 - L2 (folded); the triangle O2 O4 B then fixes the crank angle."""
    linkage, cyc = cycle
    L1, L2, L3, L4 = CASE1.lengths
    expected = []
    for d, turn in ((L3 + L2, 0.0), (L3 - L2, math.pi)):
        phi = math.acos((L1**2 + d**2 - L4**2) / (2 * L1 * d))  # angle of O2->B above O2->O4
        expected.append(math.degrees(phi + turn) % 360)
    found = sorted(p.crank_deg for p in limit_positions(linkage, cyc, "rocker"))
    assert found == pytest.approx(sorted(expected), abs=1e-8)  # Newton on K to |K| < 1e-13
    assert all(0.0 <= a < 360.0 for a in found)


def test_a_crossing_between_the_last_sample_and_the_first_is_found_where_it_is():
    """crossings() treats the samples as periodic: a zero of sin(q - q0) with q0 after the
    last sample lies on the segment that wraps round to the first one."""
    q = crank_angles(36)
    q0 = 2 * math.pi - 0.05  # between q[-1] = 350 deg and 360 deg
    found = np.sort(crossings(q, np.sin(q - q0), 0.0))
    # linear interpolation of sin across a 10 deg step: error O(h^3), under 1e-3 rad
    assert found == pytest.approx(np.sort([q0 - math.pi, q0]), abs=1e-3)


def test_a_double_crank_has_transmission_limits_at_0_and_180_deg():
    """Shortest link the ground (Grashof): both side links turn fully, so mu_min and mu_max
    exist and lie at theta2 = 0 and 180 deg (law of cosines)."""
    fb = FourBar(0.2, 1.0, 1.0, 1.0)
    mu0 = math.acos((1.0 + 1.0 - (1.0 - 0.2) ** 2) / 2.0)  # coupler-rocker angle, A on O2O4
    mu180 = math.acos((1.0 + 1.0 - (1.0 + 0.2) ** 2) / 2.0)
    assert fb.transmission_limits() == pytest.approx((mu0, mu180), rel=1e-14)


def test_an_unknown_branch_names_the_field():
    with pytest.raises(InputError) as info:
        CASE1.pose(0.3, "upside-down")
    assert info.value.field == "branch"


@pytest.mark.parametrize("delta_deg", [0.0, 90.0, 95.0])
def test_minimax_band_half_width_outside_0_to_90_deg_is_refused(delta_deg):
    """delta = 90 deg would put mu_min at 0 (a dead centre, sin mu_min = 0 in a divisor)."""
    with pytest.raises(InputError) as info:
        minimax(math.radians(40.0), math.radians(delta_deg))
    assert info.value.field == "delta"


def test_minimax_with_m2_plus_n2_equal_to_1_is_refused():
    """theta4i = mu_min gives M = 1, N = 0, so M^2 + N^2 = 1 exactly: R2 = 0/0 (a crank of
    zero length), no crank-rocker."""
    delta = math.radians(30.0)
    with pytest.raises(InputError) as info:
        minimax(math.pi / 2 - delta, delta)
    assert info.value.field == "theta4i"


@pytest.mark.parametrize("swing_deg", [0.0, 180.0, 200.0])
def test_brodell_soni_swing_outside_0_to_180_deg_is_refused_naming_it(swing_deg):
    with pytest.raises(InputError) as info:
        brodell_soni(math.radians(40.0), math.radians(swing_deg))
    assert "swing" in info.value.field
