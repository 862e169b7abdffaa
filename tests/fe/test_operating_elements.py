"""The operating-point element terms against physics: Euler's buckling load (K_g), the
consistent mass (Mt), rigid-body resultants of the d'Alembert loads, the rotating-frame
stiffness as the derivative of those loads, and the Coriolis torque of a stretching bar
(angular momentum: a spinning bar that lengthens slows down)."""

import dataclasses
import math

import numpy as np
import pytest
import scipy.linalg as la
import scipy.sparse as sp

from conftest import SCENES_DIR
from flexlink.fe.beams import beam_matrices, shear_parameter
from flexlink.fe.geometric import GeometricForm, geometric_stiffness, unit_geometric_stiffness
from flexlink.fe.link import chain_entries
from flexlink.fe.model import Section
from flexlink.fe.model_at_pose import pose_model
from flexlink.fe.preload import inertia_loads
from flexlink.fe.rotating import coupling, rotating_entries, translational_mass
from flexlink.fe.timoshenko import WEIGHTS, XI, shape_functions
from flexlink.scene import load_scene

STEEL = Section.rectangle(200e9, 80e9, 7800.0, 0.02, 0.01)
J = np.array([[0.0, -1.0], [1.0, 0.0]])


def rotor_model(angle_deg=30.0, elements=8, tip_mass=0.0, beam="euler-bernoulli"):
    """The rotor bar (scenes/rotor.toml) meshed at a crank angle: one link from the origin,
    optionally with a joint mass [kg] at its tip T, in beam theory ``beam``."""
    scene = load_scene(SCENES_DIR / "rotor.toml")
    state = scene.rigid_state(math.radians(angle_deg))
    topology = scene.topology(elements)
    joints = tuple(dataclasses.replace(j, mass=tip_mass) if j.name == "T" else j
                   for j in topology.joints)
    section = dataclasses.replace(topology.links[0].section, beam=beam)
    links = (dataclasses.replace(topology.links[0], section=section),)
    topology = dataclasses.replace(topology, joints=joints, links=links)
    return pose_model(topology, state.points), section


def full(model, rows, cols, values):
    return sp.coo_matrix((values, (rows, cols)), shape=(model.n_dofs,) * 2).toarray()


def test_consistent_kg_is_the_integral_of_the_hermite_slopes():
    h = 0.137
    _, dNv, _, _ = shape_functions(XI, h, 0.0)
    exact = (dNv * (WEIGHTS * h)) @ dNv.T
    kg = unit_geometric_stiffness(h, GeometricForm.CONSISTENT)
    # the closed form against the 4-point quadrature (exact for a quartic): round-off only
    np.testing.assert_allclose(kg[np.ix_([1, 2, 4, 5], [1, 2, 4, 5])], exact, rtol=1e-13,
                               atol=1e-15)
    # the Timoshenko form tends to it as the shear parameter vanishes (linearly in phi)
    tim = unit_geometric_stiffness(h, GeometricForm.CONSISTENT, 1e-9)
    np.testing.assert_allclose(tim, kg, atol=1e-8)
    assert np.all(kg[[0, 3]] == 0) and np.allclose(kg, kg.T)


def buckling_error(form, elements, L=0.8):
    """Relative error of the lowest P of (K - P K_g1) v = 0 of a pinned-pinned column against
    Euler's pi^2 EI / L^2."""
    K, _ = beam_matrices(L, elements, STEEL)
    kg1 = geometric_stiffness(L / elements, -np.ones(elements), form)  # unit compression
    Kg = np.zeros(K.shape)
    for e in range(elements):
        Kg[3 * e:3 * e + 6, 3 * e:3 * e + 6] += kg1[e]
    keep = np.setdiff1d(np.arange(K.shape[0]), [0, 1, 3 * elements + 1])
    # K_g is only semi-definite (no axial rows): solve -K_g v = (1 / P) K v, K definite
    mu = la.eigh(-Kg[np.ix_(keep, keep)], K.toarray()[np.ix_(keep, keep)], eigvals_only=True)
    assert mu.max() > 0  # compression softens: a positive buckling load
    return 1 / mu.max() / (math.pi**2 * STEEL.EI / L**2) - 1


@pytest.mark.parametrize("form, order, fine_error", [
    # consistent K_g: order h^4 (measured 3.3e-5 at 8 elements, 2.1e-6 at 16)
    (GeometricForm.CONSISTENT, 4, 3e-6),
    # string K_g misses the bending part of v': order h^2 (measured 1.3e-2 at 8, 3.2e-3 at 16)
    (GeometricForm.STRING, 2, 4e-3),
])
def test_kg_converges_to_euler_buckling_load(form, order, fine_error):
    coarse, fine = buckling_error(form, 8), buckling_error(form, 16)
    assert 0 < fine < fine_error
    # halving h divides the error by 2^order (10 % for the pre-asymptotic part)
    assert coarse / fine == pytest.approx(2.0**order, rel=0.1)


def test_timoshenko_kg_converges_to_engessers_buckling_load():
    """A stubby Timoshenko column (L/h = 5, P_E / kGA = 0.099): minimising
    (1/2) int EI psi'^2 + kGA (v' - psi)^2 - P v'^2 over v = A sin(pi x / L),
    psi = B cos(pi x / L) gives Engesser's P = P_E / (1 + P_E / kGA), 9 % under Euler's P_E.
    K_g with the element's own v (shear parameter phi of each element) converges to it at
    order h^2 (measured 2.6e-4 at 16 elements, 6.6e-5 at 32); Hermite slopes in place of
    the Timoshenko v miss it by 1.6e-3 whatever the mesh."""
    section = dataclasses.replace(STEEL, beam="timoshenko")
    L = 5 * section.depth
    euler = math.pi**2 * section.EI / L**2
    engesser = euler / (1 + euler / section.kGA)

    def error(elements):
        h = L / elements
        K, _ = beam_matrices(L, elements, section)
        kg1 = geometric_stiffness(h, -np.ones(elements), GeometricForm.CONSISTENT,
                                  shear_parameter(section, h))
        Kg = np.zeros(K.shape)
        for e in range(elements):
            Kg[3 * e:3 * e + 6, 3 * e:3 * e + 6] += kg1[e]
        keep = np.setdiff1d(np.arange(K.shape[0]), [0, 1, 3 * elements + 1])
        mu = la.eigh(-Kg[np.ix_(keep, keep)], K.toarray()[np.ix_(keep, keep)],
                     eigvals_only=True)
        return 1 / mu.max() / engesser - 1

    coarse, fine = error(16), error(32)
    assert 0 < fine < 1e-4
    assert coarse / fine == pytest.approx(4.0, rel=0.1)  # order h^2, 10 % pre-asymptotic


def test_translational_mass_is_the_euler_bernoulli_consistent_mass():
    h, rhoA = 0.05, 3.7
    rows, cols, _, m = chain_entries(h, 1, 1.0, 1.0, rhoA)
    M = sp.coo_matrix((m, (rows, cols)), shape=(6, 6)).toarray()
    np.testing.assert_allclose(translational_mass(h, rhoA), M, rtol=1e-13, atol=1e-18)
    S = coupling(h, rhoA)
    np.testing.assert_allclose(S, -S.T, atol=1e-18)
    # S couples axial to transverse only: int rhoA (N_v N_u - N_u N_v)
    assert np.all(S[np.ix_([0, 3], [0, 3])] == 0)


def rigid_acceleration(points, origin, a0, omega, alpha):
    r = points - origin
    return a0 + alpha * r @ J.T - omega**2 * r


@pytest.mark.parametrize("beam", ["euler-bernoulli", "timoshenko"])
def test_inertia_loads_have_the_rigid_body_resultants(beam):
    """Sum of the consistent d'Alembert loads = -m a_G, their moment about G = -I_G alpha
    (I_G = m L^2 / 12 of the bar's line of mass, plus rhoI L of a Timoshenko section's rotary
    inertia); the shape functions reproduce rigid motions exactly."""
    model, s = rotor_model(angle_deg=37.0, beam=beam)
    a0, omega, alpha = np.array([3.0, -2.0]), 11.0, -250.0
    origin = model.nodes[0]
    acc = rigid_acceleration(model.nodes, origin, a0, omega, alpha)
    f = inertia_loads(model, acc, [alpha])
    L, m = model.links[0].length, s.mass_per_length * model.links[0].length
    G = (model.nodes[0] + model.nodes[-1]) / 2
    a_G = rigid_acceleration(G[None], origin, a0, omega, alpha)[0]
    fx, fy, mz = f[0::3], f[1::3], f[2::3]
    np.testing.assert_allclose([fx.sum(), fy.sum()], -m * a_G, rtol=1e-12)
    r = model.nodes - G
    moment = (r[:, 0] * fy - r[:, 1] * fx).sum() + mz.sum()
    rotary = s.rotary_inertia * L if beam == "timoshenko" else 0.0
    assert moment == pytest.approx(-(m * L * L / 12 + rotary) * alpha, rel=1e-12)


@pytest.mark.parametrize("beam", ["euler-bernoulli", "timoshenko"])
def test_rotating_stiffness_is_the_derivative_of_the_inertia_loads(beam):
    """Move every point of the bar by a body-fixed linear field w (which the elements carry
    exactly): the d'Alembert loads change by -(-omega^2 Mt + alpha S) q, the centrifugal and
    angular-acceleration stiffness acting on the nodal values q of w. The loads come from
    ``kinematics`` accelerations, so this checks both terms' sign and size independently; in
    each beam theory, whose shape functions (shear parameter phi) weight both sides."""
    model, _ = rotor_model(angle_deg=25.0, beam=beam)
    omega, alpha = 17.0, 900.0
    origin = model.nodes[0]
    B, c = np.array([[2e-3, -1e-3], [4e-3, 3e-3]]), np.array([1e-3, -2e-3])
    w = (model.nodes - origin) @ B.T + c
    angle = model.links[0].angle
    e, n = np.array([math.cos(angle), math.sin(angle)]), np.array([-math.sin(angle), math.cos(angle)])
    q = np.zeros(model.n_dofs)
    q[0::3], q[1::3], q[2::3] = w[:, 0], w[:, 1], n @ B @ e
    before = inertia_loads(model, rigid_acceleration(model.nodes, origin, 0.0, omega, alpha), [alpha])
    after = inertia_loads(model, rigid_acceleration(model.nodes + w, origin, 0.0, omega, alpha),
                          [alpha])
    rows, cols, values = rotating_entries(model, [omega], [alpha])
    K_rot = full(model, rows, cols, values[0] + values[2])
    np.testing.assert_allclose(after - before, -K_rot @ q, rtol=1e-11,
                               atol=1e-12 * np.abs(after - before).max())


def test_coriolis_torque_of_a_stretching_bar():
    """A bar spinning at Omega whose points move outward at u' = cdot x (x from the pivot)
    feels the Coriolis force -2 Omega k x u' per unit mass; its torque about the pivot is
    -2 Omega cdot (int rhoA x^2 dx + m L^2) = -2 Omega cdot (rhoA L^3 / 3 + m L^2) with a tip
    mass m (the angular momentum of a lengthening bar): the virtual work of -G qdot on a rigid
    rotation about the pivot."""
    tip = 0.4
    model, s = rotor_model(angle_deg=60.0, tip_mass=tip)
    assert model.point_masses
    Omega, cdot = 40.0, 0.3
    origin = model.nodes[0]
    r = model.nodes - origin
    qdot = np.zeros(model.n_dofs)
    qdot[0::3], qdot[1::3] = cdot * r[:, 0], cdot * r[:, 1]
    turn = np.zeros(model.n_dofs)  # a unit rigid rotation about the pivot
    turn[0::3], turn[1::3], turn[2::3] = -r[:, 1], r[:, 0], 1.0
    rows, cols, values = rotating_entries(model, [Omega], [0.0])
    G = full(model, rows, cols, values[1])
    L = model.links[0].length
    torque = turn @ (-G @ qdot)
    inertia = s.mass_per_length * L**3 / 3 + tip * L**2
    assert torque == pytest.approx(-2 * Omega * cdot * inertia, rel=1e-12)
    np.testing.assert_allclose(G, -G.T, atol=1e-14 * np.abs(G).max())


def test_joint_masses_turn_with_the_link_that_carries_them():
    """The derivative check on a three-link frame with joint masses (the aluminium four-bar):
    every link its own turning rate, acceleration and body-fixed linear field; a joint mass
    sits on a node of one link and turns with that link's frame."""
    scene = load_scene(SCENES_DIR / "kineto_aluminium.toml")
    model = pose_model(scene.topology(4), scene.rigid_state().points)
    assert model.point_masses  # the test needs them
    rng = np.random.default_rng(1)
    omega, alpha = rng.uniform(-30, 30, 3), rng.uniform(-2000, 2000, 3)
    before, after = np.zeros((len(model.nodes), 2)), np.zeros((len(model.nodes), 2))
    q = np.zeros(model.n_dofs)
    for link, w_, a_ in zip(model.links, omega, alpha):
        nodes = model.nodes[link.nodes]
        origin, a0 = nodes[0], rng.uniform(-5, 5, 2)
        B, c = rng.uniform(-3e-3, 3e-3, (2, 2)), rng.uniform(-1e-3, 1e-3, 2)
        w = (nodes - origin) @ B.T + c
        e = np.array([math.cos(link.angle), math.sin(link.angle)])
        n = np.array([-e[1], e[0]])
        q[3 * link.nodes], q[3 * link.nodes + 1], q[3 * link.nodes + 2] = w[:, 0], w[:, 1], n @ B @ e
        before[link.nodes] = rigid_acceleration(nodes, origin, a0, w_, a_)
        after[link.nodes] = rigid_acceleration(nodes + w, origin, a0, w_, a_)
    change = inertia_loads(model, after, alpha) - inertia_loads(model, before, alpha)
    rows, cols, values = rotating_entries(model, omega, alpha)
    K_rot = full(model, rows, cols, values[0] + values[2])
    np.testing.assert_allclose(change, -K_rot @ q, rtol=1e-10, atol=1e-12 * np.abs(change).max())
