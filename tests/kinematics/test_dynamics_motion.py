"""Rigid-body motion at speed: against finite differences of positions over the crank angle
and against the four-bar's closed-form velocity and acceleration analysis."""

import math

import numpy as np
import pytest
from conftest import CASES_DIR, SCENES_DIR

from flexlink.errors import InputError
from flexlink.kinematics import FourBar
from flexlink.kinematics.dynamics import rigid_motion
from flexlink.kinematics.linkage import four_bar_linkage
from flexlink.scene import load_scene

H = 1e-4  # crank-angle step [rad] of the central differences


def body_point(linkage, state, body, local):
    """Global position [m] of the point at ``local`` (x, y) [m] in ``body``'s frame."""
    b = linkage.body(body)
    p0, p1 = (np.asarray(state.points[j]) for j in b.joints[:2])
    e = (p1 - p0) / np.linalg.norm(p1 - p0)
    return p0 + local[0] * e + local[1] * np.array([-e[1], e[0]])


def states_around(linkage, q, guess):
    s0 = linkage.solve(q, guess)
    assert np.allclose(np.array(list(s0.points.values())), np.array(list(guess.values())),
                       atol=1e-12 * linkage.size), "rigid_state is not a converged pose"
    return s0, linkage.solve(q - H, s0.points), linkage.solve(q + H, s0.points)


@pytest.mark.parametrize("scene_path", [CASES_DIR / "case3.toml", SCENES_DIR / "wiper.toml"],
                         ids=lambda p: p.stem)
@pytest.mark.parametrize("q", [0.3, 2.0, 4.4])
def test_point_motion_matches_finite_differences(scene_path, q):
    scene = load_scene(scene_path)
    linkage = scene.linkage
    s0, sm, sp = states_around(linkage, q, scene.rigid_state(q).points)
    speed, qddot = 7.3, -2.1  # arbitrary, both nonzero so both terms are exercised
    motion = rigid_motion(linkage, s0, speed, qddot)
    size = linkage.size
    for b in linkage.bodies:
        local = (0.37 * b.length, -0.21 * b.length)  # a point off the body's axis
        x0, xm, xp = (body_point(linkage, s, b.name, local) for s in (s0, sm, sp))
        d1 = (xp - xm) / (2 * H)
        d2 = (xp - 2 * x0 + xm) / H**2
        v = motion.point_velocity(b.name, x0)
        a = motion.point_acceleration(b.name, x0)
        # central differences: truncation ~ H^2 |p'''| ~ 1e-8 size; second difference also
        # round-off ~ 1e-16 size / H^2 ~ 1e-8 size
        assert np.allclose(v, d1 * speed, rtol=0, atol=1e-7 * size * speed)
        assert np.allclose(a, d2 * speed**2 + d1 * qddot, rtol=0, atol=1e-6 * size * speed**2)
        i = linkage.bodies.index(b)
        dtheta = (np.unwrap([sm.angles[i], sp.angles[i]]) @ [-1, 1]) / (2 * H)
        assert motion.omega[i] == pytest.approx(dtheta * speed, abs=1e-7 * speed)


def closed_form(L1, L2, L3, L4, t2, w2, a2, t3, t4):
    """Four-bar velocity and acceleration in closed form (loop R2 + R3 - R4 - R1 = 0, angles
    of O2->A, A->B, O4->B; Norton, Design of Machinery, sections 6.7 and 7.3)."""
    w3 = L2 * w2 / L3 * math.sin(t4 - t2) / math.sin(t3 - t4)
    w4 = L2 * w2 / L4 * math.sin(t2 - t3) / math.sin(t4 - t3)
    A, B, D, E = L4 * math.sin(t4), L3 * math.sin(t3), L4 * math.cos(t4), L3 * math.cos(t3)
    C = (L2 * a2 * math.sin(t2) + L2 * w2**2 * math.cos(t2) + L3 * w3**2 * math.cos(t3)
         - L4 * w4**2 * math.cos(t4))
    F = (L2 * a2 * math.cos(t2) - L2 * w2**2 * math.sin(t2) - L3 * w3**2 * math.sin(t3)
         + L4 * w4**2 * math.sin(t4))
    a3 = (C * D - A * F) / (A * E - B * D)
    a4 = (C * E - B * F) / (A * E - B * D)
    return w3, w4, a3, a4


@pytest.mark.parametrize("q", np.linspace(0.1, 6.2, 7))
def test_four_bar_closed_form(q):
    L1, L2, L3, L4 = 0.1524, 0.0508, 0.1778, 0.1016  # a Grashof crank-rocker
    linkage = four_bar_linkage(L1, L2, L3, L4)
    pose = FourBar(L1, L2, L3, L4).pose(q, "open")
    state = linkage.solve(q, {k: pose.joints[k] for k in ("A", "B")})
    w2, a2 = 25.0, 40.0
    m = rigid_motion(linkage, state, w2, a2)
    w3, w4, a3, a4 = closed_form(L1, L2, L3, L4, q, w2, a2, pose.theta3, pose.theta4)
    # both exact up to round-off of O(1e-13) relative in the coefficients
    assert m.omega == pytest.approx([w2, w3, w4], rel=1e-10, abs=1e-10 * w2)
    assert m.alpha == pytest.approx([a2, a3, a4], rel=1e-10, abs=1e-10 * w2**2)
    # the crank pin: a_A = L2 (alpha2 k x e - w2^2 e)
    e = np.array([math.cos(q), math.sin(q)])
    a_A = L2 * (a2 * np.array([-e[1], e[0]]) - w2**2 * e)
    assert m.accelerations["A"] == pytest.approx(a_A, abs=1e-10 * L2 * w2**2)
    assert m.point_acceleration("coupler", m.points["B"]) == pytest.approx(
        m.point_acceleration("rocker", m.points["B"]), abs=1e-10 * L2 * w2**2)


def test_rejects_non_finite_speed():
    linkage = four_bar_linkage(1.0, 0.3, 0.9, 0.8)
    state = linkage.solve(0.5, {"A": (0.26, 0.14), "B": (0.9, 0.8)})
    for bad in (math.nan, math.inf):
        with pytest.raises(InputError, match="speed"):
            rigid_motion(linkage, state, bad)
    with pytest.raises(InputError, match="crank_acceleration"):
        rigid_motion(linkage, state, 1.0, math.nan)
