"""The modal assurance criterion and its samplers, from their definitions: MAC's closed form,
the link-frame turn as a rotation, the kinetic energy kept by the link-frame mass, and the
in-plane stations sampling the element fields exactly (linear u, cubic v)."""

import math

import numpy as np
import pytest

from flexlink.analysis.mac import (compare_models, link_frame, link_frame_mass, mac_matrix,
                                   pair_modes, stations)
from flexlink.errors import InputError
from flexlink.fe.assembly import assemble
from flexlink.fe.model import JointSpec, LinkSpec, Topology, build_model
from flexlink.fe.motions import Part

from helpers import SECTION, single_beam


def test_mac_matrix_is_its_closed_form():
    rng = np.random.default_rng(3)
    A, B = rng.normal(size=(6, 3)), rng.normal(size=(6, 2))
    G = rng.normal(size=(6, 6))
    W = G @ G.T  # symmetric positive definite
    for weight in (None, W):
        Wm = np.eye(6) if weight is None else weight
        expected = np.array([[(a @ Wm @ b) ** 2 / ((a @ Wm @ a) * (b @ Wm @ b)) for b in B.T]
                             for a in A.T])
        # a handful of flops on O(1) numbers: round-off only
        np.testing.assert_allclose(mac_matrix(A, B, weight), expected, rtol=1e-13)
    # blind to scale and sign; 1 for a multiple of itself, 0 for a W-orthogonal pair
    np.testing.assert_allclose(mac_matrix(A, -3.0 * A[:, :1], W)[0, 0], 1.0, rtol=1e-14)
    b = B[:, 0] - (A[:, 0] @ W @ B[:, 0]) / (A[:, 0] @ W @ A[:, 0]) * A[:, 0]
    assert mac_matrix(A[:, :1], b[:, None], W)[0, 0] < 1e-28


def test_pair_modes_takes_the_largest_total():
    # greedy row-by-row would take (0, 0) = 0.9 and then (1, 1) = 0.1; the best total is the swap
    mac = np.array([[0.9, 0.8], [0.85, 0.1]])
    pairing = pair_modes(mac)
    assert list(pairing.a) == [0, 1] and list(pairing.b) == [1, 0]
    np.testing.assert_array_equal(pairing.mac, [0.8, 0.85])  # entries picked, not computed


def test_link_frame_turns_each_node_into_its_link_axes():
    angle = 0.7
    model = single_beam("free-free", 3, angle=angle)
    # a rigid translation along the link axis plus one across it, and a rotation field
    c, s = math.cos(angle), math.sin(angle)
    along, across = np.array([c, s]), np.array([-s, c])
    shape = np.zeros((len(model.nodes), 3))
    shape[:, :2] = 2.0 * along + 5.0 * across
    shape[:, 2] = np.arange(len(model.nodes))
    U = link_frame(model, shape.ravel()[:, None]).reshape(-1, 3)
    np.testing.assert_allclose(U[:, 0], 2.0, rtol=1e-14)
    np.testing.assert_allclose(U[:, 1], 5.0, rtol=1e-14)
    np.testing.assert_array_equal(U[:, 2], shape[:, 2])  # rz is the same in every frame


def _bent_pair_with_mass():
    """Two links at 90 deg through a finite joint carrying a 0.3 kg mass."""
    joints = (JointSpec("A", ground=True, Kt=1e7, Kr=0.0), JointSpec("B", ground=False,
              Kt=1e6, Kr=10.0, mass=0.3), JointSpec("C", ground=False, Kt=0.0, Kr=0.0))
    links = (LinkSpec("first", "A", "B", SECTION, 3), LinkSpec("second", "B", "C", SECTION, 2))
    return build_model(Topology(links=links, joints=joints),
                       {"A": (0.0, 0.0), "B": (0.4, 0.3), "C": (0.1, 0.7)})


def test_link_frame_mass_keeps_the_kinetic_energy():
    # the same velocities in global and in link frames: s^T M s is a scalar, frame-free
    model = _bent_pair_with_mass()
    _, M = assemble(model)
    S = np.random.default_rng(5).normal(size=(model.n_dofs, 4))
    U = link_frame(model, S)
    # round-off of a sum of ~100 terms of size ~1
    np.testing.assert_allclose(U.T @ link_frame_mass(model) @ U, S.T @ M @ S, rtol=1e-12)


def test_stations_sample_linear_u_and_cubic_v_exactly():
    angle, L, per_link = -0.4, 1.0, 10
    model = single_beam("free-free", 4, angle=angle)
    x = np.linspace(0.0, L, 5)
    u = lambda t: 1e-3 + 2e-3 * t  # noqa: E731  the element's axial field is linear
    v = lambda t: -1e-3 + 4e-3 * t - 3e-3 * t**2 + 5e-3 * t**3  # noqa: E731  Hermite: cubic
    dv = lambda t: 4e-3 - 6e-3 * t + 15e-3 * t**2  # noqa: E731
    c, s = math.cos(angle), math.sin(angle)
    shape = np.column_stack([c * u(x) - s * v(x), s * u(x) + c * v(x), dv(x)]).ravel()[:, None]
    values, weights, names = stations(model, shape, per_link)
    where = np.linspace(0.0, L, per_link + 1)
    # exact up to round-off of fields of size 1e-2
    np.testing.assert_allclose(values[: per_link + 1, 0], u(where), rtol=0, atol=1e-17)
    np.testing.assert_allclose(values[per_link + 1:, 0], v(where), rtol=0, atol=1e-17)
    # trapezoid weights: half at the ends, summing to the link's mass, once for u and once for v
    mass = SECTION.mass_per_length * L
    np.testing.assert_allclose(weights[: per_link + 1].sum(), mass, rtol=1e-14)
    np.testing.assert_allclose(weights[[0, per_link]], mass / per_link / 2, rtol=1e-14)
    np.testing.assert_array_equal(weights[: per_link + 1], weights[per_link + 1:])
    assert names == ("beam",)


def test_compare_models_matches_one_field_on_two_meshes():
    # the same cubic field, nodal values on 2 and on 5 elements: MAC 1 between the meshes,
    # and a shape without v against one without u: MAC 0
    angle = 0.3
    c, s = math.cos(angle), math.sin(angle)

    def field(model, u, v, dv):
        x = np.linspace(0.0, 1.0, len(model.nodes))
        return np.column_stack([c * u(x) - s * v(x), s * u(x) + c * v(x), dv(x)]).ravel()

    coarse, fine = single_beam("free-free", 2, angle=angle), single_beam("free-free", 5, angle=angle)
    fields = [(lambda t: 0 * t, lambda t: t**3 - t, lambda t: 3 * t**2 - 1),
              (lambda t: 1 + t, lambda t: 0 * t, lambda t: 0 * t)]
    A = np.column_stack([field(coarse, *f) for f in fields])
    B = np.column_stack([field(fine, *f) for f in fields])
    mac = compare_models(coarse, A, fine, B)
    # exact sampling on both meshes: round-off only
    np.testing.assert_allclose(mac, np.eye(2), atol=1e-13)


def test_compare_models_refuses_different_links():
    first = single_beam("free-free", 2)
    joints = (JointSpec("S", ground=False, Kt=0.0, Kr=0.0), JointSpec("E", ground=False,
              Kt=0.0, Kr=0.0))
    other = build_model(Topology(links=(LinkSpec("rod", "S", "E", SECTION, 2),), joints=joints),
                        {"S": (0.0, 0.0), "E": (1.0, 0.0)})
    shapes = np.ones((first.n_dofs, 1))
    with pytest.raises(InputError, match="different links") as err:
        compare_models(first, shapes, other, shapes)
    assert err.value.field == "links"
    assert "same link names" in err.value.expected


def test_out_of_plane_comparison_matches_one_field_on_two_meshes():
    # deflection w cubic (w' = -ty in the link frame) and twist tx linear: both meshes hold
    # them exactly, so each field has MAC 1 with itself across the meshes and 0 with the other
    # (w and twist sit in separate rows of the sampled values)
    angle = 0.5
    c, s = math.cos(angle), math.sin(angle)

    def field(model, w, dw, tx):
        x = np.linspace(0.0, 1.0, len(model.nodes))
        ty = -dw(x)
        return np.column_stack([w(x), c * tx(x) - s * ty, s * tx(x) + c * ty]).ravel()

    coarse, fine = single_beam("free-free", 2, angle=angle), single_beam("free-free", 5, angle=angle)
    fields = [(lambda t: t**3 - 2 * t, lambda t: 3 * t**2 - 2, lambda t: 0 * t),
              (lambda t: 0 * t, lambda t: 0 * t, lambda t: 1 - 3 * t)]
    A = np.column_stack([field(coarse, *f) for f in fields])
    B = np.column_stack([field(fine, *f) for f in fields])
    # exact sampling on both meshes: round-off only
    np.testing.assert_allclose(compare_models(coarse, A, fine, B, part=Part.OUT_OF_PLANE),
                               np.eye(2), atol=1e-13)
