"""The Timoshenko link element against closed forms: the element stiffness, the pinned-pinned
frequencies (shear and rotary inertia), no shear locking on slender links, and the energy
written without cancellation."""

import dataclasses
import math

import numpy as np
import pytest

from flexlink.fe.energy import bending_energy
from flexlink.fe.model import Section
from flexlink.fe.timoshenko import element_matrices
from flexlink.fe.beams import pinned_bending_frequencies as beam_frequencies
from flexlink.fe.beams import euler_bernoulli_pinned, timoshenko_pinned

# a steel strip; E/G = 2.6 (nu = 0.3), depth 10 mm
STEEL = Section.rectangle(E=210e9, G=210e9 / 2.6, density=7850.0, width=0.01, thickness=0.002,
                          beam="timoshenko")


def test_element_stiffness_is_the_closed_form():
    """Przemieniecki's Timoshenko beam stiffness: EI / (h^3 (1 + Phi)) x
    [12, 6h, -12, 6h; ., (4 + Phi) h^2, -6h, (2 - Phi) h^2; ...]."""
    h, EI, kGA = 0.05, 3.0, 2e4
    phi = 12 * EI / (kGA * h * h)
    K, _ = element_matrices(h, 1.0, EI, kGA, 1.0, 0.0)
    expected = EI / (h**3 * (1 + phi)) * np.array([
        [12, 6 * h, -12, 6 * h], [6 * h, (4 + phi) * h * h, -6 * h, (2 - phi) * h * h],
        [-12, -6 * h, 12, -6 * h], [6 * h, (2 - phi) * h * h, -6 * h, (4 + phi) * h * h]])
    b = [1, 2, 4, 5]
    np.testing.assert_allclose(K[np.ix_(b, b)], expected, rtol=1e-12, atol=1e-12 * expected.max())


def test_energy_without_cancellation_equals_u_k_u():
    h, EI, kGA = 0.05, 3.0, 2e4
    K, _ = element_matrices(h, 1.0, EI, kGA, 1.0, 0.0)
    rng = np.random.default_rng(1)
    v1, r1, v2, r2 = rng.normal(size=4)
    u = np.array([0.0, v1, r1, 0.0, v2, r2])
    chord = (v2 - v1) / h
    s = dataclasses.replace(STEEL, E=EI / STEEL.second_moment, G=kGA / (STEEL.shear_factor * STEEL.area))
    assert bending_energy(s, h, r1 - chord, r2 - chord) == pytest.approx(u @ K @ u, rel=1e-12)


@pytest.mark.parametrize("slenderness", [5.0, 20.0])
def test_pinned_pinned_matches_closed_form_to_1e_6(slenderness):
    """Mode 1 at 512 elements. The element holds a constant shear strain per element, so the
    frequency error falls as h^2 (measured 5.6e-7 at 256 elements for L/h = 5); 512 elements
    leave a factor 4 below the 1e-6 target."""
    L = slenderness * STEEL.depth
    exact = timoshenko_pinned(STEEL, L)
    computed = beam_frequencies(STEEL, L, 512)[0]
    assert abs(computed / exact - 1) < 1e-6
    # and shear and rotary inertia matter here: Euler-Bernoulli is far off at L/h = 5
    if slenderness == 5.0:
        assert euler_bernoulli_pinned(STEEL, L) / exact - 1 > 0.05


def test_convergence_order_is_two():
    L = 5 * STEEL.depth
    exact = timoshenko_pinned(STEEL, L)
    errors = [beam_frequencies(STEEL, L, n)[0] / exact - 1 for n in (16, 32, 64)]
    orders = [math.log2(errors[i] / errors[i + 1]) for i in range(2)]
    assert all(1.95 < p < 2.05 for p in orders), orders
    assert all(e > 0 for e in errors)  # consistent mass: upper bounds


@pytest.mark.parametrize("elements", [2, 8])
def test_no_shear_locking_on_a_slender_link(elements):
    """L/h = 1e3: the shear parameter of an element is ~1e-5, and a locking element would be
    stiff by a factor ~1/Phi there. The Timoshenko and Euler-Bernoulli elements of the same
    (coarse) mesh agree to 1e-6, the physical difference being 1.7e-6 by the closed forms;
    so the two FE results must differ by that closed-form difference, to 1e-6."""
    L = 1e3 * STEEL.depth
    eb = dataclasses.replace(STEEL, beam="euler-bernoulli")
    fe_ratio = beam_frequencies(STEEL, L, elements)[0] / beam_frequencies(eb, L, elements)[0]
    exact_ratio = timoshenko_pinned(STEEL, L) / euler_bernoulli_pinned(eb, L)
    assert abs(fe_ratio - 1) < 1e-5
    assert abs(fe_ratio - exact_ratio) < 1e-6


def test_range_warning_quotes_the_exact_timoshenko_drop():
    """The Euler-Bernoulli range warning gives the exact drop of Timoshenko theory, which is
    what flexlink's own elements give on that link (not the cruder estimate that picks the
    links)."""
    from flexlink.fe.model import LinkSpec, Topology, build_model, JointSpec
    from flexlink.scene.plausibility import exact_timoshenko_drop, model_warnings, timoshenko_drop

    length = 3 * STEEL.depth  # L/h = 3: far outside Euler-Bernoulli theory
    eb = dataclasses.replace(STEEL, beam="euler-bernoulli")
    elements = 1 - beam_frequencies(STEEL, length, 64)[0] / beam_frequencies(eb, length, 64)[0]
    exact = exact_timoshenko_drop(STEEL, length)
    assert exact == pytest.approx(elements, rel=1e-3)  # 64 elements, O(h^2)
    assert abs(timoshenko_drop(STEEL, length) - exact) > 10 * abs(elements - exact)
    joints = (JointSpec("P", True, math.inf, 0.0), JointSpec("Q", True, math.inf, 0.0))
    points = {"P": (0.0, 0.0), "Q": (length, 0.0)}
    topology = Topology(links=(LinkSpec("bar", "P", "Q", eb, 4),), joints=joints)
    [warning] = model_warnings(build_model(topology, points))
    assert f"{100 * exact:.3g} % lower (exact solution" in warning
    # the same link with Timoshenko elements is not told to use them
    topology = Topology(links=(LinkSpec("bar", "P", "Q", STEEL, 4),), joints=joints)
    assert model_warnings(build_model(topology, points)) == []
