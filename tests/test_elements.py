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


def test_rotation_is_orthogonal():
    R = node_rotation(1.234)
    np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-15)


def test_paper_printed_matrices_fail_the_checks():
    """FACTS.md: the printed K has EI/l^3 in every bending entry and +12EI/l^3 at (v1, v2); the
    printed M has -13 l b at (theta1, v2). The same checks reject them, so they can fail."""
    l, EA, EI, rhoA = 0.5, 1e6, 2.0, 0.1
    k, m = closed_form(l, EA, EI, rhoA)
    printed_k = k.copy()
    c = EI / l**3
    printed_k[np.ix_([1, 2, 4, 5], [1, 2, 4, 5])] = c * np.array(
        [[12, 6, 12, 6], [6, 4, -6, 2], [12, -6, 12, -6], [6, 2, -6, 4]])
    R = rigid_motions(np.array([0.0, l]))
    # a rigid translation in y loads the printed bending block with 24 EI/l^3, not 0
    assert np.abs(printed_k @ R).max() >= 24 * c * (1 - 1e-12)
    printed_m = m.copy()
    printed_m[2, 4] = -13 * l * rhoA * l / 420
    assert np.abs(printed_m - printed_m.T).max() > 0
    assert np.abs(k @ R).max() <= 1e-12 * np.abs(k).max()
    assert math.isclose(m[2, 4], m[4, 2])
