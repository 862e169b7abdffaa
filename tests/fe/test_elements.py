"""Element matrices: scikit-fem chain against an independent closed form; symmetry; zero strain
energy in rigid-body motion; the paper's printed misprints fail these checks."""

import math

import numpy as np
import pytest

from flexlink.fe.assembly import assemble, node_rotation
from flexlink.fe.link import link_matrices

from helpers import single_beam


def closed_form(l, EA, EI, rhoA):
    """Textbook 2D Euler-Bernoulli frame element, DOF order (u1, v1, rz1, u2, v2, rz2).
    Przemieniecki / Cook: consistent mass a = rhoA l/6, b = rhoA l/420."""
    k = np.zeros((6, 6))
    k[np.ix_([0, 3], [0, 3])] = EA / l * np.array([[1, -1], [-1, 1]])
    kb = EI / l**3 * np.array([[12, 6 * l, -12, 6 * l], [6 * l, 4 * l * l, -6 * l, 2 * l * l],
                               [-12, -6 * l, 12, -6 * l], [6 * l, 2 * l * l, -6 * l, 4 * l * l]])
    k[np.ix_([1, 2, 4, 5], [1, 2, 4, 5])] = kb
    a, b = rhoA * l / 6, rhoA * l / 420
    m = np.zeros((6, 6))
    m[np.ix_([0, 3], [0, 3])] = a * np.array([[2, 1], [1, 2]])
    m[np.ix_([1, 2, 4, 5], [1, 2, 4, 5])] = b * np.array(
        [[156, 22 * l, 54, -13 * l], [22 * l, 4 * l * l, 13 * l, -3 * l * l],
         [54, 13 * l, 156, -22 * l], [-13 * l, -3 * l * l, -22 * l, 4 * l * l]])
    return k, m


def rigid_motions(x):
    """Columns: translation x, translation y, rotation about the origin, for nodes at x (local)."""
    n = len(x)
    R = np.zeros((3 * n, 3))
    R[0::3, 0] = 1.0
    R[1::3, 1] = 1.0
    R[1::3, 2] = x
    R[2::3, 2] = 1.0
    return R


@pytest.mark.parametrize("l, EA, EI, rhoA", [(0.37, 3.1e6, 7.3, 0.045), (2.0, 1.0, 1.0, 1.0)])
def test_single_element_matches_closed_form(l, EA, EI, rhoA):
    K, M = link_matrices(l, 1, EA, EI, rhoA)
    k, m = closed_form(l, EA, EI, rhoA)
    # assembly by quadrature is exact for these polynomial integrands: round-off level only
    np.testing.assert_allclose(K.toarray(), k, rtol=1e-12, atol=1e-12 * np.abs(k).max())
    np.testing.assert_allclose(M.toarray(), m, rtol=1e-12, atol=1e-12 * np.abs(m).max())


def test_chain_is_assembly_of_closed_form_elements():
    n, L, EA, EI, rhoA = 5, 1.3, 2e5, 3.0, 0.2
    K, M = link_matrices(L, n, EA, EI, rhoA)
    k, m = closed_form(L / n, EA, EI, rhoA)
    Kc, Mc = np.zeros((3 * n + 3,) * 2), np.zeros((3 * n + 3,) * 2)
    for e in range(n):
        sl = slice(3 * e, 3 * e + 6)
        Kc[sl, sl] += k
        Mc[sl, sl] += m
    np.testing.assert_allclose(K.toarray(), Kc, atol=1e-10 * np.abs(Kc).max())
    np.testing.assert_allclose(M.toarray(), Mc, atol=1e-12 * np.abs(Mc).max())


def test_symmetric_and_rigid_body_strain_free():
    n, L = 7, 0.8
    K, M = link_matrices(L, n, 5e6, 12.0, 0.3)
    K, M = K.toarray(), M.toarray()
    assert np.abs(K - K.T).max() <= 1e-14 * np.abs(K).max()
    assert np.abs(M - M.T).max() <= 1e-14 * np.abs(M).max()
    R = rigid_motions(np.linspace(0, L, n + 1))
    # strain energy of rigid motions vanishes relative to the element scale
    assert np.abs(K @ R).max() <= 1e-10 * np.abs(K).max()
    # mass is positive definite
    assert np.linalg.eigvalsh(M).min() > 0


def test_rotated_global_matrices_keep_rigid_body_modes():
    angle = 0.7321
    model = single_beam("free-free", 6, angle=angle)
    K, M = assemble(model)
    K = K.toarray()
    x, y = model.nodes[:, 0], model.nodes[:, 1]
    n = len(x)
    R = np.zeros((3 * n, 3))
    R[0::3, 0] = 1
    R[1::3, 1] = 1
    R[0::3, 2], R[1::3, 2], R[2::3, 2] = -y, x, 1.0
    assert np.abs(K @ R).max() <= 1e-9 * np.abs(K).max()
    assert np.abs(K - K.T).max() <= 1e-12 * np.abs(K).max()


@pytest.mark.parametrize("angle", [0.3, 1.234, 2.9])
def test_rotation_takes_the_link_axis_to_local_x(angle):
    """local = R @ global: the link's own direction (cos a, sin a) is local (1, 0) and its
    normal (-sin a, cos a) is local (0, 1). The transpose would give (cos 2a, sin 2a) instead."""
    R = node_rotation(angle)
    c, s = math.cos(angle), math.sin(angle)
    np.testing.assert_allclose(R @ [c, s, 0.0], [1.0, 0.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(R @ [-s, c, 0.0], [0.0, 1.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(R @ [0.0, 0.0, 1.0], [0.0, 0.0, 1.0], atol=0)  # rotations stay


def test_entries_the_paper_misprints_are_the_textbook_ones():
    """FACTS.md: the paper prints +12 EI/l^3 at (v1, v2), EI/l^3 in every bending entry and
    -13 l rhoA l / 420 at (theta1, v2). flexlink's element has the textbook values (Przemieniecki,
    DOF order u1 v1 theta1 u2 v2 theta2): -12 EI/l^3, 4 EI/l, 6 EI/l^2 and +13 rhoA l^2 / 420."""
    l, EA, EI, rhoA = 0.5, 1e6, 2.0, 0.1
    K, M = (A.toarray() for A in link_matrices(l, 1, EA, EI, rhoA))
    assert K[1, 4] == pytest.approx(-12 * EI / l**3, rel=1e-12)  # -192 N/m
    assert K[2, 2] == pytest.approx(4 * EI / l, rel=1e-12)  # 16 N m
    assert K[1, 2] == pytest.approx(6 * EI / l**2, rel=1e-12)  # 48 N
    assert K[0, 3] == pytest.approx(-EA / l, rel=1e-12)
    assert M[2, 4] == pytest.approx(13 * rhoA * l**2 / 420, rel=1e-12)
    assert M[4, 2] == M[2, 4]
    assert M[1, 1] == pytest.approx(156 * rhoA * l / 420, rel=1e-12)
