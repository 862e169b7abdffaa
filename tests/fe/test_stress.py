"""Stress recovery (``fe.stress``) against closed forms: a cantilever under a tip load
(sigma = 6 P (L - x) / (b t^2) at its fibres, any beam theory, any angle of the link) and a
uniform bar turning about one end (sigma = rho Omega^2 (L^2 - x^2) / 2), the latter exact at
the element ends only with the elements' own inertia loads subtracted."""

import math

import numpy as np
import pytest

from flexlink.fe.assembly import assemble, rigid_elimination
from flexlink.fe.model import JointSpec, LinkSpec, Section, Topology, build_model
from flexlink.fe.preload import element_inertia_loads, inertia_loads, static_displacement
from flexlink.fe.stress import end_positions, link_stresses

RIGID = math.inf
B, T = 0.02, 0.004  # section width and in-plane depth [m]


def _section(beam):
    return Section.rectangle(E=210e9, G=81e9, density=7850.0, width=T, thickness=B,
                             bending="edgewise", beam=beam)


def _clamped_link(section, length, angle, elements):
    """A link clamped at joint O (the origin) and free at E, at ``angle`` [rad]."""
    topology = Topology(
        links=(LinkSpec("bar", "O", "E", section, elements),),
        joints=(JointSpec("O", ground=True, Kt=RIGID, Kr=RIGID),
                JointSpec("E", ground=False, Kt=RIGID, Kr=0.0)))
    end = (length * math.cos(angle), length * math.sin(angle))
    return build_model(topology, {"O": (0.0, 0.0), "E": end})


def _solve(model, f):
    K, _ = assemble(model)
    Tr = rigid_elimination(model)
    return static_displacement((Tr.T @ K @ Tr).toarray(), Tr, f)


@pytest.mark.parametrize("beam", ["euler-bernoulli", "timoshenko"])
@pytest.mark.parametrize("angle", [0.0, 0.7])
def test_cantilever_tip_load_gives_6PL_over_bt2(beam, angle):
    """The root stress is 6 P L / (b t^2), compressive on the +y fibre for a load along +y
    (the link's own normal), and falls linearly to 0 at the tip. Nodal loads only, so the
    element end forces are exact in both theories: the tolerance is round-off (the stiffness
    spans 12 EI / h^3 to EA / h, about 1e6 here)."""
    L, P = 0.3, 40.0
    model = _clamped_link(_section(beam), L, angle, 6)
    f = np.zeros(model.n_dofs)
    tip = model.links[0].nodes[-1]
    f[3 * tip:3 * tip + 2] = P * np.array([-math.sin(angle), math.cos(angle)])
    sigma = link_stresses(model, _solve(model, f))[0]  # (e, 2 ends, 2 fibres)
    x = end_positions(model.links[0])
    expected = 6.0 * P * (L - x) / (B * T**2)
    np.testing.assert_allclose(sigma[..., 0], -expected, rtol=1e-9, atol=1e-9 * expected.max())
    np.testing.assert_allclose(sigma[..., 1], expected, rtol=1e-9, atol=1e-9 * expected.max())
    assert 6 * P * L / (B * T**2) == pytest.approx(-sigma[0, 0, 0], rel=1e-9)


@pytest.mark.parametrize("beam", ["euler-bernoulli", "timoshenko"])
@pytest.mark.parametrize("elements", [1, 3])
def test_rotating_bar_axial_stress_is_exact_at_element_ends(beam, elements):
    """A bar clamped at the axis and turning at Omega: its d'Alembert load rho A Omega^2 x
    pulls it outwards and the axial stress is rho Omega^2 (L^2 - x^2) / 2. The linear axial
    element's nodal displacements are exact (1D), so with each element's own load vector
    subtracted its end forces are exact too, even with one element; the fibres carry the same
    stress (no bending). Without the elements' own loads each element would show its mean
    force (an error of rho Omega^2 L^2 / 2 at the root of a one-element bar)."""
    L, omega, angle = 0.25, 300.0, 0.4
    model = _clamped_link(_section(beam), L, angle, elements)
    acc = -omega**2 * model.nodes  # centripetal, about the origin
    alpha = np.zeros(1)
    u = _solve(model, inertia_loads(model, acc, alpha))
    sigma = link_stresses(model, u, element_inertia_loads(model, acc, alpha))[0]
    x = end_positions(model.links[0])
    rho = model.links[0].section.density
    expected = rho * omega**2 * (L**2 - x**2) / 2.0
    for fibre in (0, 1):
        np.testing.assert_allclose(sigma[..., fibre], expected, rtol=1e-9,
                                   atol=1e-9 * expected.max())


def test_trailing_axes_are_load_cases():
    """Two load cases at once give each its own stresses (the modal rows use this)."""
    model = _clamped_link(_section("euler-bernoulli"), 0.3, 0.2, 4)
    rng = np.random.default_rng(3)
    u = rng.normal(size=(model.n_dofs, 2))
    both = link_stresses(model, u)[0]
    for k in range(2):
        np.testing.assert_allclose(both[:, :, k], link_stresses(model, u[:, k])[0], rtol=1e-13)
