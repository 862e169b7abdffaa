"""A published four-bar dynamic-force problem, all of whose inputs are stated, solved by
flexlink's Newton-Euler inverse dynamics and by an independent Lagrange closed form.

The problem (as set in Indian "Theory of Machines" courses, e.g. the T.E. Mechanical "Theory
of Machines II, Sheet No. 5: Dynamic force analysis", problem 1): four-link mechanism ABCD,
AB = 500 mm (crank), BC = 660 mm, CD = 560 mm, AD = 1000 mm (fixed). AB turns at 10.5 rad/s
counter-clockwise with an angular retardation of 26 rad/s^2 when it makes 60 deg with AD.
BC and CD have 4.2 kg per metre of length; AB has 3.54 kg with its centre 200 mm from A and
a moment of inertia of 88 500 kg mm^2. Gravity and friction neglected; find the drive torque
on AB.

The printed answer of the textbook this problem comes from could not be reached (see
docs/dynamics.md, "Published four-bar examples"), and the textbook solves it graphically
(two to three digits). So this is not a comparison with a printed number: the reference is
the Lagrange closed form below, written from the stated inputs without flexlink's kinematics,
and its value is pinned so that a printed answer, once found, can be set beside it.
Assumptions where the statement is silent: the open assembly (C above AD), BC and CD uniform
bars (centre at mid-length, I_G = m l^2 / 12), the centre of AB on the line AB.
"""

import math

import numpy as np
import pytest

from flexlink.kinematics import FourBar
from flexlink.kinematics.dynamics import rigid_motion
from flexlink.kinematics.inverse import BodyMass, inverse_dynamics
from flexlink.kinematics.linkage import four_bar_linkage
from flexlink.units import parse_quantity

AD, AB, BC, CD = (parse_quantity(t, "length") for t in ("1000 mm", "500 mm", "660 mm", "560 mm"))
THETA = parse_quantity("60 deg", "angle")
OMEGA = parse_quantity("10.5 rad/s", "angular speed")
ALPHA = parse_quantity("-26 rad/s^2", "angular acceleration")  # a retardation of the ccw crank
M_AB = parse_quantity("3.54 kg", "mass")
G_AB = parse_quantity("200 mm", "length")  # A to the centre of AB
I_AB = parse_quantity("885000 g*cm^2", "rotary inertia")  # = 88 500 kg mm^2
MU = 4.2  # kg per metre of BC and CD
M_BC, M_CD = MU * BC, MU * CD

# 8th-order central difference: error ~ h^8 f^(9) / 630
D8 = (1 / 280, -4 / 105, 1 / 5, -4 / 5, 0.0, 4 / 5, -1 / 5, 4 / 105, -1 / 280)


def joint_c(q):
    """C from the crank angle q: the upper intersection of the circles about B (radius BC)
    and D (radius CD), with A at the origin and D on +x."""
    b = np.array([AB * math.cos(q), AB * math.sin(q)])
    d = np.array([AD, 0.0]) - b
    r = math.hypot(*d)
    along = (BC**2 - CD**2 + r**2) / (2 * r)
    e = d / r
    return b, b + along * e + math.sqrt(BC**2 - along**2) * np.array([-e[1], e[0]])


def mass_function(q):
    """M(q) = 2 T / qdot^2 [kg m^2], velocities from the loop equation's derivative."""
    b, c = joint_c(q)
    t3 = math.atan2(c[1] - b[1], c[0] - b[0])
    t4 = math.atan2(c[1], c[0] - AD)
    w3 = AB * math.sin(t4 - q) / (BC * math.sin(t3 - t4))
    w4 = AB * math.sin(q - t3) / (CD * math.sin(t4 - t3))
    v_g3 = AB * np.array([-math.sin(q), math.cos(q)]) + w3 * BC / 2 * np.array(
        [-math.sin(t3), math.cos(t3)])
    return (I_AB + M_AB * G_AB**2 + M_BC * v_g3 @ v_g3 + M_BC * BC**2 / 12 * w3**2
            + M_CD * CD**2 / 3 * w4**2)


def lagrange_torque(q, w, qdd, h=1e-2):
    """tau = M qdd + M' w^2 / 2 (no loads, no gravity)."""
    dm = sum(c * mass_function(q + k * h) for k, c in zip(range(-4, 5), D8) if c) / h
    return mass_function(q) * qdd + 0.5 * dm * w * w


def flexlink_solution():
    linkage = four_bar_linkage(AD, AB, BC, CD)
    pose = FourBar(AD, AB, BC, CD).pose(THETA, "open")
    state = linkage.solve(THETA, {j: pose.joints[j] for j in ("A", "B")})
    masses = (BodyMass("crank", M_AB, (G_AB, 0.0), I_AB),
              BodyMass("coupler", M_BC, (BC / 2, 0.0), M_BC * BC**2 / 12),
              BodyMass("rocker", M_CD, (CD / 2, 0.0), M_CD * CD**2 / 12))
    return state, inverse_dynamics(linkage, rigid_motion(linkage, state, OMEGA, ALPHA), masses)


# The closed form's value [N m], counter-clockwise on AB: drive torque needed at this instant.
REFERENCE_TORQUE = 24.0735857


def test_drive_torque_of_the_published_problem():
    state, result = flexlink_solution()
    # flexlink's joints A (= the book's B) and B (= the book's C) are the closed form's
    b, c = joint_c(THETA)
    assert np.allclose(state.points["A"], b, atol=1e-12) and np.allclose(state.points["B"], c,
                                                                          atol=1e-12)
    ref = lagrange_torque(THETA, OMEGA, ALPHA)
    assert ref == pytest.approx(REFERENCE_TORQUE, abs=1e-7)  # pinned to its 9th digit
    # Newton-Euler against Lagrange, apart by the difference's truncation (~1e-13 relative)
    assert result.torque == pytest.approx(ref, rel=1e-9)

