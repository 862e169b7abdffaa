"""Inverse dynamics against independent references: the power balance
tau Omega = dT/dt - P_loads with T(q) written in closed form (four-bar) or from finite
differences of positions (general linkage), a balanced crank, a parallelogram, Lagrange's
equation on a stated four-bar, and the kinetic energy of the FE model's consistent mass."""

import dataclasses
import math

import numpy as np
import pytest
from conftest import SCENES_DIR

from flexlink.errors import InputError
from flexlink.fe.assembly import assemble
from flexlink.fe.model import build_model
from flexlink.kinematics import Body, FourBar, Linkage
from flexlink.kinematics.dynamics import rigid_motion
from flexlink.kinematics.inverse import Bar, Wrench, body_masses, inverse_dynamics
from flexlink.kinematics.linkage import four_bar_linkage
from flexlink.scene import load_scene

# A steel crank-rocker (lengths [m], uniform bars [kg/m], pin masses [kg]); the numbers are
# this test's own, chosen so that every term is of the same order.
L1, L2, L3, L4 = 0.30, 0.08, 0.28, 0.20
MU = {"crank": 1.2, "coupler": 0.8, "rocker": 1.0}
PINS = {"A": 0.05, "B": 0.03}
TL, FP, P_LOCAL = -0.7, (3.0, -5.0), (0.12, 0.04)  # rocker torque [N m]; coupler force [N] at P

# 8th-order central difference of f at x with step h: error ~ h^8 f^(9) / 630
D8 = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])


def d8(f, x, h):
    return sum(c * f(x + k * h) for c, k in zip(D8, range(-4, 5)) if c) / h


def four_bar_velocities(q, w2):
    """Angles, angular velocities and pin positions/velocities in closed form: the pose from
    ``FourBar.pose``, the velocities from the loop equation's derivative (Norton 6.7)."""
    pose = FourBar(L1, L2, L3, L4).pose(q, "open")
    t3, t4 = pose.theta3, pose.theta4
    w3 = L2 * w2 / L3 * math.sin(t4 - q) / math.sin(t3 - t4)
    w4 = L2 * w2 / L4 * math.sin(q - t3) / math.sin(t4 - t3)
    def e(t):  # unit vector at angle t
        return np.array([math.cos(t), math.sin(t)])

    def k(t):  # e(t) turned by +90 deg
        return np.array([-math.sin(t), math.cos(t)])

    A, vA = L2 * e(q), L2 * w2 * k(q)
    vB = L4 * w4 * k(t4)
    return {"t3": t3, "t4": t4, "w3": w3, "w4": w4, "A": A, "vA": vA, "vB": vB, "e": e, "k": k}


def four_bar_mass_function(q):
    """M(q) = 2 T / Omega^2 of the four-bar with bars MU and pins PINS, in closed form."""
    s = four_bar_velocities(q, 1.0)
    m2, m3, m4 = MU["crank"] * L2, MU["coupler"] * L3, MU["rocker"] * L4
    vG3 = s["vA"] + s["w3"] * L3 / 2 * s["k"](s["t3"])
    return (m2 * L2**2 / 3 + m3 * vG3 @ vG3 + m3 * L3**2 / 12 * s["w3"] ** 2
            + m4 * L4**2 / 3 * s["w4"] ** 2 + PINS["A"] * s["vA"] @ s["vA"]
            + PINS["B"] * s["vB"] @ s["vB"])


def four_bar_load_power(q, w2):
    """Power [W] of TL on the rocker and FP at the coupler point P_LOCAL (coupler frame)."""
    s = four_bar_velocities(q, w2)
    r = P_LOCAL[0] * s["e"](s["t3"]) + P_LOCAL[1] * s["k"](s["t3"])
    vP = s["vA"] + s["w3"] * np.array([-r[1], r[0]])
    return TL * s["w4"] + np.dot(FP, vP)


def flexlink_four_bar(q, w2, qdd, loads=True):
    linkage = four_bar_linkage(L1, L2, L3, L4)
    pose = FourBar(L1, L2, L3, L4).pose(q, "open")
    state = linkage.solve(q, {j: pose.joints[j] for j in ("A", "B")})
    motion = rigid_motion(linkage, state, w2, qdd)
    bars = [Bar(n, *ends, MU[n]) for n, ends in
            (("crank", ("O2", "A")), ("coupler", ("A", "B")), ("rocker", ("O4", "B")))]
    masses = body_masses(linkage, bars, PINS)
    A, B = motion.points["A"], motion.points["B"]
    e3 = (B - A) / np.linalg.norm(B - A)
    P = A + P_LOCAL[0] * e3 + P_LOCAL[1] * np.array([-e3[1], e3[0]])
    wrenches = [Wrench("rocker", torque=TL), Wrench("coupler", force=FP, point=tuple(P))]
    return inverse_dynamics(linkage, motion, masses, wrenches if loads else [])


@pytest.mark.parametrize("qdd", [0.0, 37.0])
def test_power_balance_four_bar(qdd):
    """tau Omega = dT/dt - P_loads at every sampled angle, with dT/dt = Omega (M qdd +
    M' Omega^2 / 2) from the closed-form M(q) and its 8th-order difference."""
    w2 = 3.27 * 20
    residuals, scale = [], 0.0
    for q in np.linspace(0.0, 2 * math.pi, 73)[:-1]:
        res = flexlink_four_bar(q, w2, qdd)
        dT = w2 * (four_bar_mass_function(q) * qdd + 0.5 * d8(four_bar_mass_function, q, 1e-2) * w2**2)
        residuals.append(res.torque * w2 - (dT - four_bar_load_power(q, w2)))
        scale = max(scale, abs(res.torque * w2))
        assert res.kinetic_energy == pytest.approx(0.5 * four_bar_mass_function(q) * w2**2,
                                                   rel=1e-12)
    # relative to the peak drive power; the difference's truncation is ~1e-13 of it
    assert max(map(abs, residuals)) <= 1e-9 * scale


def test_power_balance_general_linkage():
    """The wiper (five bodies, a three-joint rocker, pin masses): T(q) = sum m v_G^2 / 2 +
    I omega^2 / 2 written here from the joints' first-order coefficients dp/dq alone (no
    accelerations, no pin forces), dT/dq by an 8th-order difference of the solved poses."""
    scene = load_scene(SCENES_DIR / "wiper.toml")
    linkage = scene.linkage
    rng = np.random.default_rng(1)
    bars = [Bar(b.name, b.joints[0], b.joints[-1], float(rng.uniform(0.5, 2.0)),
                float(rng.uniform(0, 1e-4))) for b in linkage.bodies]
    masses = body_masses(linkage, bars, {"a": 0.02, "c": 0.01})

    def mass_function(q, guess):
        """2 T / Omega^2 at crank angle q."""
        s = linkage.solve(q, guess)
        total = 0.0
        for b, m in zip(linkage.bodies, masses):
            p0, p1 = (np.array(s.points[j]) for j in b.joints[:2])
            d0, d1 = (s.dpoints[j] for j in b.joints[:2])
            d, dd = p1 - p0, d1 - d0
            w = (d[0] * dd[1] - d[1] * dd[0]) / (d @ d)  # dtheta/dq of the body's axis
            e = d / np.linalg.norm(d)
            r = m.centroid[0] * e + m.centroid[1] * np.array([-e[1], e[0]])
            v = d0 + w * np.array([-r[1], r[0]])
            total += m.mass * v @ v + m.inertia * w**2
        return total

    w, qdd = 12.0, -4.0
    worst, scale = 0.0, 0.0
    state = scene.rigid_state(0.0)
    for q in np.linspace(0.0, 2 * math.pi, 37)[:-1]:
        state = linkage.solve(q, state.points)
        res = inverse_dynamics(linkage, rigid_motion(linkage, state, w, qdd), masses)
        M = mass_function(q, state.points)
        dM = d8(lambda x, guess=state.points: mass_function(x, guess), q, 5e-3)
        worst = max(worst, abs(res.torque * w - w * (M * qdd + 0.5 * dM * w**2)))
        scale = max(scale, abs(res.torque * w))
    # truncation h^8 M^(9) / 630 and round-off 1e-16 / h: both below 1e-11 of the peak power
    assert worst <= 1e-9 * scale


def test_balanced_crank_needs_no_torque_at_constant_speed():
    """A crank whose mass centre is on its pivot: two equal arms at 180 deg (and a pin mass
    balanced by the other arm's). tau = 0 at constant speed, tau = I_O qdd when accelerating."""
    crank = Body.polar("crank", ("O", "A", "C"), (0.1, 0.1), (0.0, math.pi))
    linkage = Linkage(ground={"O": (0.0, 0.0)}, bodies=(crank,), driver="crank")
    masses = body_masses(linkage, [Bar("arm1", "O", "A", 2.0), Bar("arm2", "O", "C", 2.0)],
                         {"A": 0.1, "C": 0.1})
    I_O = 2 * (0.2 * 0.1**2 / 3) + 2 * 0.1 * 0.1**2
    for q in np.linspace(0, 2 * math.pi, 9):
        state = linkage.solve(q, {"A": (0.1 * math.cos(q), 0.1 * math.sin(q)),
                                  "C": (-0.1 * math.cos(q), -0.1 * math.sin(q))})
        res = inverse_dynamics(linkage, rigid_motion(linkage, state, 300.0), masses)
        assert abs(res.torque) <= 1e-12 * I_O * 300.0**2  # round-off of centroid ~ 1e-17 m
        assert np.allclose(res.forces[("O", "crank")], 0.0, atol=1e-12 * 0.4 * 0.1 * 300**2)
        res = inverse_dynamics(linkage, rigid_motion(linkage, state, 300.0, 50.0), masses)
        assert res.torque == pytest.approx(I_O * 50.0, rel=1e-12)


def test_unbalanced_crank_bearing_force_is_centripetal():
    """A single bar crank at constant speed: the bearing pulls m Omega^2 l/2 towards the pivot."""
    linkage = Linkage(ground={"O": (0.0, 0.0)}, bodies=(Body.bar("crank", "O", "A", 0.2),),
                      driver="crank")
    masses = body_masses(linkage, [Bar("crank", "O", "A", 1.5)])
    q, w = 0.7, 40.0
    state = linkage.solve(q, {"A": (0.2 * math.cos(q), 0.2 * math.sin(q))})
    res = inverse_dynamics(linkage, rigid_motion(linkage, state, w), masses)
    expected = -0.3 * w**2 * 0.1 * np.array([math.cos(q), math.sin(q)])
    assert res.forces[("O", "crank")] == pytest.approx(expected, rel=1e-13)
    assert abs(res.torque) <= 1e-13 * 0.3 * w**2 * 0.1 * 0.2


def test_parallelogram_needs_no_torque_at_constant_speed():
    """Crank and rocker equal, coupler equal to the ground: the coupler translates and the
    kinetic energy (I_O2 + I_O4 + m3 L2^2) Omega^2 / 2 is constant, so tau = 0."""
    L = 0.1
    linkage = Linkage(ground={"O2": (0.0, 0.0), "O4": (0.3, 0.0)},
                      bodies=(Body.bar("crank", "O2", "A", L), Body.bar("coupler", "A", "B", 0.3),
                              Body.bar("rocker", "O4", "B", L)), driver="crank")
    masses = body_masses(linkage, [Bar("crank", "O2", "A", 1.0), Bar("coupler", "A", "B", 2.0),
                                   Bar("rocker", "O4", "B", 1.0)])
    w = 50.0
    for q in (0.4, 1.3, 2.5, 4.0, 5.5):
        A = L * np.array([math.cos(q), math.sin(q)])
        state = linkage.solve(q, {"A": A, "B": A + (0.3, 0.0)})
        res = inverse_dynamics(linkage, rigid_motion(linkage, state, w), masses)
        assert abs(res.torque) <= 1e-11 * 0.6 * w**2 * L**2  # round-off of the pin forces


# Lagrange's equation tau = M(q) qdd + M'(q) qdot^2 / 2 - Q(q, qdot), Q = P_loads / qdot,
# on the crank-rocker above (L1..L4, MU, PINS, TL, FP, P_LOCAL), at Omega = 10 rad/s and
# qdd = 5 rad/s^2; M(q) and Q by the closed forms of this file, M' by an 8th-order difference.
# No textbook's printed solution is used: the reference below was computed here from those
# closed forms (independent of flexlink's Newton-Euler system) and is pinned to 4 digits.
LAGRANGE_TABLE = [  # crank angle [deg], tau [N m] from lagrange_torque below
    (0, -0.2259617), (60, 0.5451144), (135, 0.1732497), (210, -0.2576779), (300, -0.1678446)]


def lagrange_torque(q, w, qdd):
    M = four_bar_mass_function(q)
    dM = d8(four_bar_mass_function, q, 1e-2)
    return M * qdd + 0.5 * dM * w**2 - four_bar_load_power(q, w) / w


@pytest.mark.parametrize("deg, tau", LAGRANGE_TABLE)
def test_lagrange_reference(deg, tau):
    q, w, qdd = math.radians(deg), 10.0, 5.0
    ref = lagrange_torque(q, w, qdd)
    assert ref == pytest.approx(tau, abs=5e-8)  # the pinned table: this file's closed form
    # Newton-Euler against Lagrange: the same physics by two routes, apart by the
    # difference's truncation (~1e-13 relative)
    assert flexlink_four_bar(q, w, qdd).torque == pytest.approx(ref, rel=1e-9, abs=1e-12)


def test_kinetic_energy_matches_the_consistent_mass_matrix():
    """1/2 v^T M v of the FE model's consistent mass (Timoshenko: with rotary inertia) under
    the rigid nodal velocities equals the bodies' m v^2 / 2 + I omega^2 / 2: the mass
    properties are those of the beams the scene states."""
    scene = load_scene(SCENES_DIR / "kineto_aluminium.toml")
    links = tuple(dataclasses.replace(l, section=dataclasses.replace(l.section, beam="timoshenko"),
                                      elements=4) for l in scene.links)
    topology = dataclasses.replace(scene.topology(4), links=links)
    state = scene.rigid_state(1.1)
    motion = rigid_motion(scene.linkage, state, 25.0)
    model = build_model(topology, state.points)
    _, M = assemble(model)
    v = np.zeros(model.n_dofs)
    body_of = {l.name: next(b for b in scene.linkage.bodies if l.start in b.joints
                            and l.end in b.joints) for l in scene.links}
    for link in model.links:
        b = body_of[link.name]
        nodes = link.nodes
        v.reshape(-1, 3)[nodes, :2] = motion.point_velocity(b.name, model.nodes[nodes])
        v.reshape(-1, 3)[nodes, 2] = motion.omega[scene.linkage.bodies.index(b)]
    fe = 0.5 * v @ (M @ v)
    bars = [Bar(l.name, l.start, l.end, l.section.mass_per_length,
                l.section.density * l.section.second_moment) for l in scene.links]
    masses = body_masses(scene.linkage, bars, {j.name: j.mass for j in scene.joints})
    ours = inverse_dynamics(scene.linkage, motion, masses).kinetic_energy
    assert ours == pytest.approx(fe, rel=1e-12)  # both exact for rigid motion


def test_load_on_unknown_body_is_refused():
    linkage = four_bar_linkage(L1, L2, L3, L4)
    state = linkage.solve(1.0, {j: FourBar(L1, L2, L3, L4).pose(1.0).joints[j] for j in "AB"})
    masses = body_masses(linkage, [])
    with pytest.raises(InputError, match="'rocker2'"):
        inverse_dynamics(linkage, rigid_motion(linkage, state, 1.0), masses,
                         [Wrench("rocker2", torque=1.0)])
