"""The general loop-closure solver against the closed-form four-bar, finite differences,
virtual work, and its own error paths."""

import math

import numpy as np
import pytest

from flexlink.errors import InputError, KinematicsError
from flexlink.kinematics.fourbar import FourBar
from flexlink.kinematics.linkage import Body, Linkage, crank_angles, four_bar_linkage

FOUR_BARS = {  # (ratios R2, R3, R4) with L1 = 0.3 m: Table II case 1 and case 2
    "case1": (0.267, 0.800, 0.667),
    "case2": (0.417, 1.000, 0.792),
}


@pytest.mark.parametrize("branch", ["open", "crossed"])
@pytest.mark.parametrize("case", FOUR_BARS)
def test_agrees_with_closed_form_four_bar_over_the_cycle(case, branch):
    fb = FourBar.from_ratios(*FOUR_BARS[case], ground=0.3)
    linkage = four_bar_linkage(*fb.lengths)
    q = crank_angles(360)
    cycle = linkage.cycle(q, fb.pose(q[0], branch).joints)
    worst = 0.0
    for state in cycle.states:
        exact = fb.pose(state.q, branch)
        worst = max(worst, *(np.abs(np.subtract(exact.joints[j], state.points[j])).max()
                             for j in exact.joints))
        for body, theta in (("coupler", exact.theta3), ("rocker", exact.theta4)):
            diff = state.angles[cycle.column(body)] - theta
            assert abs(math.remainder(diff, 2 * math.pi)) < 1e-10
    assert worst < 1e-10  # metres, on a 0.3 m linkage: the branch is kept all the way round


def test_velocity_coefficients_match_finite_differences_and_closed_form():
    fb = FourBar.from_ratios(*FOUR_BARS["case1"], ground=0.3)
    L1, L2, L3, L4 = fb.lengths
    linkage = four_bar_linkage(*fb.lengths)
    h = 1e-5  # central differences: error ~ h^2 * third derivative ~ 1e-10
    for q in np.radians([0.0, 37.0, 140.0, 251.0]):
        guess = fb.pose(q).joints
        s = linkage.solve(q, guess)
        plus, minus = linkage.solve(q + h, guess), linkage.solve(q - h, guess)
        dA = np.remainder(plus.angles - minus.angles + math.pi, 2 * math.pi) - math.pi
        np.testing.assert_allclose(s.K, dA / (2 * h), atol=1e-8)
        np.testing.assert_allclose(s.L, (plus.K - minus.K) / (2 * h), atol=1e-7)
        # closed form from the loop equations: K4 = L2 sin(q - t3) / (L4 sin(t4 - t3))
        t3, t4 = s.angles[1], s.angles[2]
        assert s.K[2] == pytest.approx(L2 * math.sin(q - t3) / (L4 * math.sin(t4 - t3)), abs=1e-12)
        assert s.K[1] == pytest.approx(L2 * math.sin(q - t4) / (L3 * math.sin(t4 - t3)), abs=1e-12)


def test_static_torque_ratio_is_one_over_K_by_virtual_work():
    # A rocker torque T4 balanced by crank torque T2: T2 dq + T4 dtheta4 = 0, so the ratio of
    # the output torque the crank can hold is |T4/T2| = 1/|K4|; checked with finite virtual work
    fb = FourBar.from_ratios(*FOUR_BARS["case2"], ground=0.3)
    linkage = four_bar_linkage(*fb.lengths)
    q, h = math.radians(75.0), 1e-6
    s = linkage.solve(q, fb.pose(q).joints)
    work_ratio = (2 * h) / (linkage.solve(q + h, s.points).angles[2]
                            - linkage.solve(q - h, s.points).angles[2])
    assert 1.0 / s.K[2] == pytest.approx(work_ratio, rel=1e-8)


def test_triangle_body_keeps_its_shape_and_side():
    # two four-bars in series through a rigid triangle (a crank-double-rocker)
    tri = Body.polar("rocker1", ("O2", "b", "c"), (0.052, 0.049), (0.0, math.radians(20)))
    linkage = Linkage(
        ground={"O1": (0.0, 0.0), "O2": (0.458, 0.0), "O3": (-0.0579, 0.0725)},
        bodies=(Body.bar("crank", "O1", "a", 0.041), Body.bar("link1", "a", "b", 0.450), tri,
                Body.bar("link2", "c", "d", 0.517), Body.bar("rocker2", "O3", "d", 0.053)),
        driver="crank")
    guess = {"a": (0.041, 0.0), "b": (0.46, 0.052), "c": (0.44, 0.045), "d": (-0.07, 0.12)}
    cycle = linkage.cycle(crank_angles(360), guess)
    for s in cycle.states:
        p = {k: np.array(v) for k, v in s.points.items()}
        assert np.linalg.norm(p["b"] - p["c"]) == pytest.approx(
            math.sqrt(0.052**2 + 0.049**2 - 2 * 0.052 * 0.049 * math.cos(math.radians(20))), abs=1e-12)
        u, v = p["b"] - p["O2"], p["c"] - p["O2"]
        assert math.atan2(u[0] * v[1] - u[1] * v[0], u @ v) == pytest.approx(math.radians(20), abs=1e-12)
        assert np.linalg.norm(p["d"] - p["c"]) == pytest.approx(0.517, abs=1e-12)
    # after one revolution the linkage is back where it started (same branch)
    last = linkage.solve(2 * math.pi, cycle.states[-1].points)
    for j in guess:
        np.testing.assert_allclose(last.points[j], cycle.states[0].points[j], atol=1e-12)


def test_loop_that_cannot_close_and_dead_centre_are_refused():
    fb = FourBar(ground=1.0, crank=0.6, coupler=0.5, rocker=0.6)  # non-Grashof: crank cannot turn
    linkage = four_bar_linkage(*fb.lengths)
    with pytest.raises(KinematicsError, match="cannot turn fully: at q = .* the loop does not close"):
        linkage.cycle(crank_angles(72), fb.pose(0.0).joints)
    # at q = 0, |O4 A| = 0.8 = coupler + rocker: coupler and rocker in line (mu = 180 deg)
    dead = four_bar_linkage(1.0, 0.2, 0.5, 0.3)
    with pytest.raises(KinematicsError, match="dead centre"):
        dead.solve(0.0, {"A": (0.2, 0.0), "B": (0.7, 0.0)})


def test_mobility_other_than_one_is_an_input_error():
    with pytest.raises(InputError, match="one degree of freedom"):
        Linkage(ground={"O": (0.0, 0.0)}, bodies=(Body.bar("crank", "O", "A", 1.0),
                                                  Body.bar("free", "A", "B", 1.0)), driver="crank")


def test_two_loop_velocity_coefficients_match_finite_differences():
    # the wiper's two loops and rigid triangle: K and L of every body against central
    # differences of the solved angles and K (h = 1e-5: truncation ~ 1e-10)
    from pathlib import Path

    from flexlink.scene import load_scene

    scene = load_scene(Path(__file__).resolve().parents[2] / "scenes" / "wiper.toml")
    cycle = scene.linkage.cycle(crank_angles(36), scene.guess)
    h = 1e-5
    for state in cycle.states[::5]:
        plus = scene.linkage.solve(state.q + h, state.points)
        minus = scene.linkage.solve(state.q - h, state.points)
        dA = np.remainder(plus.angles - minus.angles + math.pi, 2 * math.pi) - math.pi
        np.testing.assert_allclose(state.K, dA / (2 * h), atol=1e-8)
        np.testing.assert_allclose(state.L, (plus.K - minus.K) / (2 * h), atol=1e-7)


@pytest.mark.parametrize("scene_file", ["cases/case2.toml", "scenes/wiper.toml"])
def test_the_driver_turns_at_exactly_the_crank_rate(scene_file):
    # the driver's angle is the input angle q itself, so its coefficients are K = 1 and L = 0
    # by construction, not by solving the loop: equality is exact (a driver alpha of 1e-13
    # at constant speed would add a spurious circulatory term on one CPU and not another);
    # the other bodies' coefficients are solved, and their K vary over the cycle
    from pathlib import Path

    from flexlink.scene import load_scene

    scene = load_scene(Path(__file__).resolve().parents[2] / scene_file)
    cycle = scene.linkage.cycle(crank_angles(72), scene.guess)
    driver = [b.name for b in scene.linkage.bodies].index(scene.linkage.driver)
    assert np.all(cycle.K[:, driver] == 1.0) and np.all(cycle.L[:, driver] == 0.0)
    others = np.delete(cycle.K, driver, axis=1)
    assert np.all(np.ptp(others, axis=0) > 1e-3)
