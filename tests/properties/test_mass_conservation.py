"""Every mass model keeps the linkage's mass: a rigid translation's kinetic energy,
r^T M r, is the total mass of links (rho A L) and joint masses, computed here from the drawn
scene's inputs, in the consistent and in the lumped (HRZ) matrix alike.

For the consistent matrices a rigid rotation is also exact, since the elements interpolate a
rigid motion exactly (linear axial, cubic Hermite or the Timoshenko element's static shapes):
r^T M r = sum over links of rho A int |p - c|^2 ds (+ rho I L for Timoshenko's rotary inertia)
+ sum over joint masses of m |p_j - c|^2, about any centre c."""

import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from strategies import linkages, load

from flexlink.analysis.identity import total_mass
from flexlink.analysis.modal import analyze
from flexlink.fe.assembly import assemble
from flexlink.fe.energy import lumped_mass

# Sums of a few dozen positive entries: round-off of a few eps.
RTOL = 1e-12


def _model(spec):
    return analyze(load(spec), 1).model


def _rigid(model, cx=0.0, cy=0.0):
    """(n, 3): translation in x, in y, and rotation about (cx, cy) [m] of every DOF."""
    x, y = model.nodes[:, 0], model.nodes[:, 1]
    r = np.zeros((model.n_dofs, 3))
    r[0::3, 0], r[1::3, 1] = 1.0, 1.0
    r[0::3, 2], r[1::3, 2], r[2::3, 2] = -(y - cy), x - cx, 1.0
    return r


@given(linkages(), st.sampled_from(("consistent", "lumped")))
def test_a_rigid_translation_carries_the_whole_mass(spec, mass):
    model = _model(spec)
    M = assemble(model)[1] if mass == "consistent" else lumped_mass(model)
    r = _rigid(model)
    energy = r[:, :2].T @ (M @ r[:, :2])
    np.testing.assert_allclose(np.diag(energy), spec.total_mass, rtol=RTOL)
    assert abs(energy[0, 1]) <= RTOL * spec.total_mass  # x and y motions do not couple
    assert math.isclose(total_mass(model), spec.total_mass, rel_tol=RTOL)  # the printed total


def _rotational_inertia(spec, model, cx, cy):
    """sum rho A int |p - c|^2 ds (+ rho I L, Timoshenko) + sum m_j |p_j - c|^2 [kg m^2], from
    the spec's inputs and the joint positions of the model."""
    placed = {j: np.array(model.nodes[nodes[0]]) for j, nodes in model.joint_nodes.items()}
    c = np.array([cx, cy])
    total = 0.0
    for name, a, b in (("crank", "O2", "A"), ("coupler", "A", "B"), ("rocker", "O4", "B")):
        p, d = placed[a] - c, placed[b] - placed[a]
        length = float(np.linalg.norm(d))
        section = spec.sections[name]
        total += spec.density * section.A * length * (p @ p + p @ d + d @ d / 3)
        if spec.beam == "timoshenko":
            total += spec.density * section.I * length
    for name, joint in spec.joints.items():
        q = placed[name] - c
        total += joint.mass * (q @ q)
    return total


@given(linkages(), st.floats(-1.0, 1.0), st.floats(-1.0, 1.0))
def test_a_rigid_rotation_has_the_linkages_moment_of_inertia(spec, cx, cy):
    model = _model(spec)
    M = assemble(model)[1]
    r = _rigid(model, cx, cy)[:, 2]
    expected = _rotational_inertia(spec, model, cx, cy)
    assert math.isclose(r @ (M @ r), expected, rel_tol=1e-10), (r @ (M @ r), expected)
