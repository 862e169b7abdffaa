"""The co-rotational frame element against closed forms: rigid motions carry no force, the
tangent is the derivative of the internal force, at zero displacement it is the linear
Euler-Bernoulli element, and cantilevers follow the circular arc (end moment) and the elastica
(end force, elliptic integrals) at large rotation; Howell's PRB constants then reproduce the tip
path to the accuracy he states."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.special import ellipeinc, ellipkinc

from flexlink.analysis.large_deflection import CorotationalFrame, solve_static
from flexlink.fe.corotational import (Chords, chord_end_forces, element_state, internal_forces,
                                      tangent_stiffness)

EI, EA, LENGTH = 2.0, 4.0e6, 1.0  # [N m^2], [N], [m]: slender (EA L^2 / EI = 2e6)


def _random_elements(rng, e=5):
    X = rng.normal(size=(e, 2, 2))
    return X, Chords.of(X, rng.uniform(1, 3, e) * 1e3, rng.uniform(1, 3, e))


def test_rigid_motion_carries_no_force():
    """A large rotation plus a translation of every element: no stretch, no end rotation from
    the chord, so no force (to round-off of the chord's length, 1e-12 of EA)."""
    rng = np.random.default_rng(1)
    X, chords = _random_elements(rng)
    angle, shift = 2.4, np.array([0.3, -1.1])
    c, s = math.cos(angle), math.sin(angle)
    moved = X @ np.array([[c, s], [-s, c]]) + shift  # rows: rotated by +angle
    u = np.concatenate([moved[:, 0] - X[:, 0], np.full((len(X), 1), angle),
                        moved[:, 1] - X[:, 1], np.full((len(X), 1), angle)], axis=1)
    f = internal_forces(element_state(chords, X, u))
    assert np.abs(f).max() < 1e-12 * chords.EA.max()


def test_tangent_is_the_derivative_of_the_internal_force():
    """K_t against central differences of f at a large, arbitrary displacement: every term of
    K_t (material, N z z^T / L, (m1 + m2)(r z^T + z r^T) / L^2) shows here; central
    differences with h = 1e-6 are good to ~1e-9 of K's scale."""
    rng = np.random.default_rng(2)
    X, chords = _random_elements(rng)
    u = rng.normal(scale=0.2, size=(len(X), 6))
    K = tangent_stiffness(chords, element_state(chords, X, u))
    h = 1e-6
    numeric = np.empty_like(K)
    for j in range(6):
        du = np.zeros_like(u)
        du[:, j] = h
        numeric[:, :, j] = (internal_forces(element_state(chords, X, u + du))
                            - internal_forces(element_state(chords, X, u - du))) / (2 * h)
    assert np.abs(K - numeric).max() < 1e-7 * np.abs(K).max()


def test_chord_end_forces_are_the_internal_forces_in_the_chord_frame():
    """The end forces handed to stress recovery, turned from the chord frame to the global one,
    are the internal forces B^T f_l (a wrong shear sign or a moment at the wrong end shows)."""
    rng = np.random.default_rng(4)
    X, chords = _random_elements(rng)
    state = element_state(chords, X, rng.normal(scale=0.2, size=(len(X), 6)))
    c, s = np.cos(state.beta), np.sin(state.beta)
    local = chord_end_forces(state)
    turned = np.empty_like(local)
    for node in (0, 3):
        fx, fy = local[:, node], local[:, node + 1]
        turned[:, node], turned[:, node + 1] = c * fx - s * fy, s * fx + c * fy
        turned[:, node + 2] = local[:, node + 2]
    f = internal_forces(state)
    assert np.abs(turned - f).max() < 1e-12 * np.abs(f).max()


def test_internal_force_is_the_gradient_of_the_energy():
    rng = np.random.default_rng(3)
    X, chords = _random_elements(rng)
    u = rng.normal(scale=0.2, size=(len(X), 6))
    f = internal_forces(element_state(chords, X, u))
    h = 1e-6
    for j in range(6):
        du = np.zeros_like(u)
        du[:, j] = h
        dU = (element_state(chords, X, u + du).energy
              - element_state(chords, X, u - du).energy) / (2 * h)
        assert np.abs(dU - f[:, j]).max() < 1e-7 * np.abs(f).max()


def test_tangent_at_rest_is_the_linear_euler_bernoulli_element():
    """At u = 0 the tangent is the textbook element T^T k T (independent code: fe.beams)."""
    from flexlink.fe.assembly import node_rotation
    from flexlink.fe.beams import link_entries
    from flexlink.fe.model import Section

    section = Section.rectangle(210e9, 80e9, 7850, 0.02, 0.006)
    h, angle = 0.05, 0.7
    X = np.array([[[0.0, 0.0], [h * math.cos(angle), h * math.sin(angle)]]])
    chords = Chords.of(X, section.EA, section.EI)
    K = tangent_stiffness(chords, element_state(chords, X, np.zeros((1, 6))))[0]
    R = np.zeros((6, 6))
    R[:3, :3] = R[3:, 3:] = node_rotation(angle)
    rows, cols, k, _ = link_entries(h, 1, section)
    local = np.zeros((6, 6))
    np.add.at(local, (rows, cols), k)
    linear = R.T @ local @ R
    assert np.abs(K - linear).max() < 1e-12 * np.abs(linear).max()


def _cantilever(n):
    """A straight cantilever along x of n elements, clamped at node 0: (frame, T)."""
    x = np.linspace(0.0, LENGTH, n + 1)
    X = np.stack([np.stack([x[:-1], 0 * x[:-1]], 1), np.stack([x[1:], 0 * x[1:]], 1)], 1)
    dofs = 3 * np.arange(n)[:, None] + np.arange(6)
    frame = CorotationalFrame(X, dofs, Chords.of(X, EA, EI), 3 * (n + 1), np.zeros(n, int))
    T = np.eye(3 * (n + 1))[:, 3:]  # the clamp: node 0's DOFs have no unknown
    return frame.eliminated(T), T


def _loaded(frame, T, load_at_tip, steps):
    """Load continuation: the tip load ramped in ``steps`` equal steps; the last solution."""
    q = np.zeros(T.shape[1])
    for k in range(1, steps + 1):
        p = np.zeros(frame.n_dofs)
        p[-3:] = np.asarray(load_at_tip) * k / steps
        q = solve_static(frame, np.array([], int), q, load=p, where="cantilever").q
    return T @ q


@pytest.mark.parametrize("turn", [1.0, 2 * math.pi])
def test_end_moment_bends_a_circular_arc(turn):
    """M = EI turn / L: every node turns by M s / EI exactly (to the solver's tolerance) and the
    nodes lie on one circle; a chord of the co-rotational element spans an arc's turn
    phi = h M / EI, so the circle's radius is h / (2 sin(phi / 2)) against EI / M in the
    continuum, a relative O(phi^2 / 24) difference; at turn = 2 pi (a full circle) the
    polygon closes: the tip comes back to the root."""
    n = 40
    frame, T = _cantilever(n)
    M = EI * turn / LENGTH
    u = _loaded(frame, T, (0.0, 0.0, M), 16).reshape(-1, 3)
    s = np.linspace(0, LENGTH, n + 1)
    assert np.abs(u[:, 2] - M * s / EI).max() < 1e-9 * turn
    xy = np.stack([s, np.zeros_like(s)], 1) + u[:, :2]
    phi = turn / n
    radius = (LENGTH / n) / (2 * math.sin(phi / 2))
    centre = np.array([0.0, radius])  # the arc leaves the root along x, curving to +y
    assert np.abs(np.hypot(*(xy - centre).T) - radius).max() < 1e-9 * LENGTH
    assert abs(radius * M / EI - 1) < phi**2 / 24 * 1.01
    if turn > 6:
        assert np.hypot(*xy[-1]) < 1e-9 * LENGTH


def elastica_tip(alpha):
    """Tip of a cantilever (length 1, clamped horizontal) under a dead end force normal to it,
    alpha = P L^2 / EI: (x, y deflection, tip slope theta0) from the elastica in elliptic
    integrals (Bisshopp and Drucker; Howell's "Compliant Mechanisms" 5.1): with
    k = sqrt((1 + sin theta0) / 2) and sin(phi1) = 1 / (k sqrt 2),
        sqrt(alpha) = F(pi/2, k) - F(phi1, k),
        x / L = sqrt(2 sin(theta0) / alpha),
        y / L = 1 - 2 (E(pi/2, k) - E(phi1, k)) / sqrt(alpha).
    scipy's ellipkinc/ellipeinc take m = k^2."""

    def parts(theta0):
        m = (1 + math.sin(theta0)) / 2
        phi1 = math.asin(1 / math.sqrt(2 * m))
        return m, phi1

    def mismatch(theta0):
        m, phi1 = parts(theta0)
        return ellipkinc(math.pi / 2, m) - ellipkinc(phi1, m) - math.sqrt(alpha)

    theta0 = brentq(mismatch, 1e-9, math.pi / 2 - 1e-9, xtol=1e-15)
    m, phi1 = parts(theta0)
    x = math.sqrt(2 * math.sin(theta0) / alpha)
    y = 1 - 2 * (ellipeinc(math.pi / 2, m) - ellipeinc(phi1, m)) / math.sqrt(alpha)
    return x, y, theta0


def test_elastica_closed_form_small_load_is_the_linear_cantilever():
    """The oracle itself: for small alpha the elastica tip is alpha / 3 down, slope alpha / 2."""
    x, y, theta0 = elastica_tip(1e-4)
    assert abs(y / (1e-4 / 3) - 1) < 1e-4 and abs(theta0 / 5e-5 - 1) < 1e-4


@pytest.mark.parametrize("alpha", [1.0, 3.0, 10.0])
def test_end_force_follows_the_elastica(alpha):
    """Tip deflections of 40 elements against the elliptic-integral elastica. The element is
    second order in h (the arc's chord): measured at alpha = 10, 7.5e-5 L and 9.5e-5 rad with
    40 elements, 2.2e-5 L and 2.5e-5 rad with 80 (1e-5 or less at alpha = 1, 3); 2e-4 is
    tight for that and far below a wrong geometric term's miss (or the linear model's
    y = alpha / 3, off by 2.5 L at alpha = 10)."""
    frame, T = _cantilever(40)
    u = _loaded(frame, T, (0.0, alpha * EI / LENGTH**2, 0.0), 10)
    x_ref, y_ref, theta_ref = elastica_tip(alpha)
    assert abs(LENGTH + u[-3] - x_ref * LENGTH) < 2e-4 * LENGTH
    assert abs(u[-2] - y_ref * LENGTH) < 2e-4 * LENGTH
    assert abs(u[-1] - theta_ref) < 2e-4


def _prb_path_error(x, y, gamma):
    """Distance of the tip (x, y) (length 1, root at the origin) from the PRB tip path, a circle
    of radius gamma about (1 - gamma, 0); relative to the tip deflection."""
    return abs(math.hypot(x - (1 - gamma), y) - gamma) / math.hypot(1 - x, y)


@pytest.mark.parametrize("gamma, reach_deg", [(0.8517, 64.3), (0.85, 63.0)])
def test_howell_prb_constants_reproduce_the_tip_path(gamma, reach_deg):
    """Howell (Compliant Mechanisms, 5.1; Howell and Midha 1995), vertical end force (n = 0):
    gamma = 0.8517 keeps the tip within 0.5 % of its deflection of the PRB's circle for
    pseudo-rigid-body angles up to Theta = 64.3 deg; the rounded gamma = 0.85 does so to
    Theta = 63.2 deg (the elastica here: 0.5 % is crossed at 64.27 and 63.25 deg). Both the
    elastica and the co-rotational FE tip paths stay inside."""
    frame, T = _cantilever(40)
    q = np.zeros(T.shape[1])
    worst_fe, worst_ref, Theta = 0.0, 0.0, 0.0
    for alpha in np.linspace(0.25, 8.0, 32):
        x, y, _ = elastica_tip(alpha)
        Theta = math.atan2(y, x - (1 - gamma))
        if Theta > math.radians(reach_deg):
            break
        p = np.zeros(frame.n_dofs)
        p[-2] = alpha * EI / LENGTH**2
        q = solve_static(frame, np.array([], int), q, load=p, where="howell").q
        u = T @ q
        worst_fe = max(worst_fe, _prb_path_error(LENGTH + u[-3], u[-2], gamma))
        worst_ref = max(worst_ref, _prb_path_error(x, y, gamma))
    assert Theta > math.radians(reach_deg)  # the sweep went past Howell's range
    assert worst_ref < 0.005 and worst_fe < 0.005


def test_howell_spring_constant_gives_the_load():
    """K_Theta = 2.65 (Howell's average over load angles; 2.676 for n = 0): the PRB spring
    K = gamma K_Theta EI / L carries the force's moment about the characteristic pivot,
    gamma K_Theta EI Theta / L = P gamma L cos(Theta). A constant spring is a fit: over
    Theta <= 64.3 deg the load it implies straddles the elastica's (too stiff below 43 deg,
    too soft above), measured within 4.5 %; Howell states no tighter bound for it."""
    K_theta = 2.65
    errors = []
    for alpha in np.linspace(0.1, 8.0, 40):
        x, y, _ = elastica_tip(alpha)
        Theta = math.atan2(y, x - (1 - 0.85))
        if Theta > math.radians(64.3):
            break
        errors.append(K_theta * Theta / math.cos(Theta) / alpha - 1)
    assert max(np.abs(errors)) < 0.05 and min(errors) < 0 < max(errors)
