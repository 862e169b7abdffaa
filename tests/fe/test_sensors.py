"""Sensors on a frame model (fe/sensors.py): placement on the nearest link and the readings
of the element's own interpolation, checked against motions the interpolation must reproduce
exactly (rigid rotations, a cubic deflection) and against the nodes themselves."""

from __future__ import annotations

import math

import numpy as np
import pytest

from flexlink.errors import InputError
from flexlink.fe.model_at_pose import pose_model
from flexlink.fe.motions import Part
from flexlink.fe.sensors import channel_operator, place_points
from flexlink.scene import load_scene

EXACT = 1e-12  # round-off of a few products of order-1 numbers


def _model(beam="euler-bernoulli", elements=5):
    scene = load_scene("cases/case3.toml", overrides={"model.beam": beam})
    return pose_model(scene.topology(elements), scene.rigid_pose().joints, warn=False)


def _points_near_links(model, rng, count=40, off=2e-3, beyond=0.0):
    """Points at random places along random links, pushed ``off`` [m] at most sideways and
    up to ``beyond`` (a fraction of the length) past the ends."""
    out = []
    for _ in range(count):
        link = model.links[rng.integers(len(model.links))]
        a = model.nodes[link.first_node]
        t = rng.uniform(0.02 - beyond, 0.98 + beyond)
        normal = np.array([-math.sin(link.angle), math.cos(link.angle)])
        out.append(a + t * link.length * np.array([math.cos(link.angle), math.sin(link.angle)])
                   + rng.uniform(-off, off) * normal)
    return np.array(out)


@pytest.mark.parametrize("beam", ["euler-bernoulli", "timoshenko"])
def test_a_rigid_rotation_is_read_exactly_at_any_point(beam):
    """A rigid rotation theta about the origin: ux = -theta y, uy = theta x, rz = theta at
    every node. Both interpolations hold rigid motions exactly, and a point off the axis moves
    with its section, so every channel reads d . theta e_z x p (p the sensor's own position)."""
    model = _model(beam)
    rng = np.random.default_rng(3)
    points = _points_near_links(model, rng, count=60, beyond=0.05)
    placement = place_points(model, points, [str(i) for i in range(len(points))], 0.01)
    direction = rng.normal(size=(len(points), 3))
    direction /= np.linalg.norm(direction, axis=1)[:, None]
    theta = 1e-3
    shape = np.zeros(model.n_dofs)
    shape[0::3], shape[1::3], shape[2::3] = -theta * model.nodes[:, 1], theta * model.nodes[:, 0], theta
    S = channel_operator(Part.IN_PLANE, model, placement, np.arange(len(points)), direction)
    expected = direction[:, 0] * -theta * points[:, 1] + direction[:, 1] * theta * points[:, 0]
    np.testing.assert_allclose(S @ shape, expected, rtol=0, atol=EXACT * theta)


def test_an_out_of_plane_rigid_tilt_is_read_exactly():
    """A rigid rotation (ax, ay, 0) about in-plane axes: w = ax y - ay x, rx = ax, ry = ay at
    every node; a sensor reads dz (ax py - ay px) at its own position p."""
    model = _model()
    rng = np.random.default_rng(4)
    points = _points_near_links(model, rng, count=60, beyond=0.05)
    # past the free ends at the ground pivots: the nearest place is the end itself, and the
    # point sits off it along the link's axis
    crank, rocker = model.links[0], model.links[-1]
    points = np.vstack([points, model.nodes[0] - 3e-3 * np.array([math.cos(crank.angle), math.sin(crank.angle)]),
                        model.nodes[-1] + 3e-3 * np.array([math.cos(rocker.angle), math.sin(rocker.angle)])])
    placement = place_points(model, points, [str(i) for i in range(len(points))], 0.01)
    direction = np.column_stack([np.zeros(len(points)), np.zeros(len(points)),
                                 rng.choice([-1.0, 1.0], len(points))])
    ax, ay = 2e-3, -1e-3
    shape = np.zeros(model.n_dofs)
    shape[0::3] = ax * model.nodes[:, 1] - ay * model.nodes[:, 0]
    shape[1::3], shape[2::3] = ax, ay
    S = channel_operator(Part.OUT_OF_PLANE, model, placement, np.arange(len(points)), direction)
    expected = direction[:, 2] * (ax * points[:, 1] - ay * points[:, 0])
    np.testing.assert_allclose(S @ shape, expected, rtol=0, atol=EXACT * 1e-3)


def test_a_cubic_deflection_and_linear_stretch_are_reproduced_between_nodes():
    """Nodal values of v(x) = c3 x^3 + c2 x^2 + c1 x (with rz = v') and u(x) = a x along one
    link: Hermite cubics and linear axial interpolation hold them exactly, so a point on the
    axis at any x reads u and v of the closed form."""
    model = _model(elements=4)
    link = model.links[1]
    c, s = math.cos(link.angle), math.sin(link.angle)
    x_nodes = np.linspace(0.0, link.length, link.elements + 1)
    c3, c2, c1, a = 0.7, -0.3, 0.02, 1e-3
    v = lambda x: c3 * x**3 + c2 * x**2 + c1 * x  # noqa: E731
    shape = np.zeros(model.n_dofs)
    nodes = link.nodes
    u_n, v_n = a * x_nodes, v(x_nodes)
    shape[3 * nodes], shape[3 * nodes + 1] = c * u_n - s * v_n, s * u_n + c * v_n
    shape[3 * nodes + 2] = 3 * c3 * x_nodes**2 + 2 * c2 * x_nodes + c1
    x = np.array([0.013, 0.07, 0.131, 0.2, 0.2649]) * link.length / 0.27
    start = model.nodes[link.first_node]
    points = start + x[:, None] * [c, s]
    placement = place_points(model, points, list("abcde"), 1e-6)
    assert set(placement.link) == {1}
    axial = np.tile([c, s, 0.0], (len(x), 1))
    transverse = np.tile([-s, c, 0.0], (len(x), 1))
    S_u = channel_operator(Part.IN_PLANE, model, placement, np.arange(len(x)), axial)
    S_v = channel_operator(Part.IN_PLANE, model, placement, np.arange(len(x)), transverse)
    np.testing.assert_allclose(S_u @ shape, a * x, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(S_v @ shape, v(x), rtol=1e-12, atol=1e-15)


def test_timoshenko_links_read_a_shear_deflection_by_their_own_interpolation():
    """A uniform shear force P along a Timoshenko link: v = P/EI (L x^2/2 - x^3/6) + P x/kGA
    and psi = P/EI (L x - x^2/2) (the static solution the interdependent element holds
    exactly). Nodal (v, psi) from it are read back between the nodes as v(x) and as the
    section rotation psi(x) (a point off the axis moves by -psi offset along the axis);
    Hermite cubics on (v, psi) would miss the shear part."""
    model = _model("timoshenko", elements=3)
    link = model.links[1]
    sec = link.section
    c, s = math.cos(link.angle), math.sin(link.angle)
    L, P = link.length, 1.0
    v = lambda x: P / sec.EI * (L * x**2 / 2 - x**3 / 6) + P * x / sec.kGA  # noqa: E731
    psi = lambda x: P / sec.EI * (L * x - x**2 / 2)  # noqa: E731
    xn = np.linspace(0.0, L, link.elements + 1)
    shape = np.zeros(model.n_dofs)
    shape[3 * link.nodes], shape[3 * link.nodes + 1] = -s * v(xn), c * v(xn)
    shape[3 * link.nodes + 2] = psi(xn)
    x = np.array([0.11, 0.37, 0.52, 0.93]) * L
    side = 1e-3  # [m] off the axis, towards local +y
    normal = np.array([-s, c])
    points = model.nodes[link.first_node] + x[:, None] * [c, s] + side * normal
    placement = place_points(model, points, list("abcd"), 0.01)
    S_v = channel_operator(Part.IN_PLANE, model, placement, np.arange(4), np.tile([-s, c, 0], (4, 1)))
    S_u = channel_operator(Part.IN_PLANE, model, placement, np.arange(4), np.tile([c, s, 0], (4, 1)))
    scale = np.abs(v(xn)).max()
    np.testing.assert_allclose(S_v @ shape, v(x), rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(S_u @ shape, -side * psi(x), rtol=0, atol=1e-12 * scale)


def test_a_point_on_a_node_reads_that_nodes_displacement():
    """At an inner node the operator is the node's own (ux, uy) and nothing else."""
    model = _model()
    link = model.links[2]
    node = link.first_node + 2
    placement = place_points(model, model.nodes[[node]], ["n"], 1e-9)
    S = channel_operator(Part.IN_PLANE, model, placement, [0, 0], [[1, 0, 0], [0, 1, 0]])
    expected = np.zeros((2, model.n_dofs))
    expected[0, 3 * node], expected[1, 3 * node + 1] = 1.0, 1.0
    np.testing.assert_allclose(S, expected, atol=EXACT)


def test_a_sensor_off_every_link_is_named():
    model = _model()
    far = model.nodes.mean(axis=0) + [0.0, 0.5]
    with pytest.raises(InputError, match=r"test.uff: sensor 17: at .* mm from the nearest link \(coupler\): off every"):
        place_points(model, np.array([model.nodes[3], far]), ["3", "17"], 0.01, source="test.uff")
