"""Root kinds and instability causes (flexlink/analysis/instability.py) on two-DOF systems whose
roots are known in closed form: a negative stiffness diverges (s = +-sqrt(k)), a circulatory
(skew) stiffness flutters with a positive-definite symmetric part (s^2 = -k +- i c), and a
gyroscopic coupling alone, K positive definite, keeps every root on the imaginary axis."""

import math

import numpy as np
import pytest

from flexlink.analysis.instability import (Cause, RootKind, instability_causes, root_kinds)
from flexlink.analysis.quadratic import quadratic_modes

I2 = np.eye(2)
ZERO = np.zeros((2, 2))


def test_real_roots_have_a_kind_of_their_own():
    # s^2 - 4 = 0 (a negative stiffness): +-2, real; s^2 + 4 = 0: +-2i
    kinds = root_kinds(np.array([2.0 + 1e-20j, -2.0, 2.0j, 1.0 + 3.0j]))
    assert kinds == (RootKind.DIVERGING, RootKind.DECAYING, RootKind.VIBRATING,
                     RootKind.VIBRATING)


def test_a_negative_stiffness_is_named_by_the_part_that_makes_it():
    """K = diag(1, 1) elastic; a 'preload' part diag(0, -2) makes it indefinite alone, the
    'centrifugal' part diag(-0.5, 0) does not: the preload is the cause. Roots: +-1 (real)
    and +-i/sqrt(2)."""
    elastic, preload, centrifugal = I2, np.diag([0.0, -2.0]), np.diag([-0.5, 0.0])
    K = elastic + preload + centrifugal
    modes = quadratic_modes(I2, ZERO, K, 2)
    kinds = root_kinds(modes.eigenvalues)
    assert sorted(kinds) == sorted((RootKind.DIVERGING, RootKind.VIBRATING))
    diverging = modes.eigenvalues[kinds.index(RootKind.DIVERGING)]
    assert diverging.real == pytest.approx(1.0, rel=1e-12)  # s^2 = 1
    causes = instability_causes(elastic, {Cause.PRELOAD: preload, Cause.CENTRIFUGAL: centrifugal},
                                None, modes.negative_stiffness, modes.growing, kinds)
    assert causes == (Cause.PRELOAD,)
    # both parts needed: each alone keeps K positive definite
    half = np.diag([0.0, -0.7])
    causes = instability_causes(elastic, {Cause.PRELOAD: half, Cause.CENTRIFUGAL: half},
                                None, 1, np.array([True]), (RootKind.DIVERGING,))
    assert causes == (Cause.COMBINED,)


def test_a_circulatory_term_alone_makes_a_positive_stiffness_flutter():
    """K = [[k, c], [-c, k]]: symmetric part k I (positive definite), skew part c. The roots
    satisfy s^2 = -k +- i c: with k = 4, c = 3, s^2 = -4 + 3i gives s = 0.7416 + 2.0226i,
    growing although nothing is negative. Without the skew part the roots are +-2i."""
    k, c = 4.0, 3.0
    skew = np.array([[0.0, c], [-c, 0.0]])
    modes = quadratic_modes(I2, ZERO, k * I2 + skew, 2)
    kinds = root_kinds(modes.eigenvalues)
    assert kinds == (RootKind.VIBRATING, RootKind.VIBRATING)
    expected = np.sqrt(complex(-k, c))
    assert max(modes.eigenvalues.real) == pytest.approx(abs(expected.real), rel=1e-10)
    assert modes.negative_stiffness == 0
    causes = instability_causes(k * I2, {}, skew, 0, modes.growing, kinds)
    assert causes == (Cause.CIRCULATORY,)
    # the same growth with no skew part given is not blamed on one
    assert instability_causes(k * I2, {}, None, 0, modes.growing, kinds) == ()
    assert instability_causes(k * I2, {}, np.zeros((2, 2)), 0, modes.growing, kinds) == ()


def test_a_gyroscopic_coupling_with_positive_stiffness_never_grows():
    """G = g [[0, 1], [-1, 0]] with K = diag(1, 4): a conservative system; every root on the
    imaginary axis (Kelvin-Tait-Chetaev), so nothing to blame."""
    g = 5.0
    G = g * np.array([[0.0, 1.0], [-1.0, 0.0]])
    modes = quadratic_modes(I2, G, np.diag([1.0, 4.0]), 2)
    assert not modes.growing.any()
    # s^4 + (1 + 4 + g^2) s^2 + 4 = 0: |s|^2 are the roots of w^2 - 30 w + 4 = 0
    w = np.sort(np.roots([1.0, -(5.0 + g * g), 4.0]))
    assert np.sort(np.abs(modes.eigenvalues) ** 2) == pytest.approx(w, rel=1e-10)
    assert instability_causes(np.diag([1.0, 4.0]), {}, None, 0, modes.growing,
                              root_kinds(modes.eigenvalues)) == ()
    assert math.isfinite(float(np.abs(modes.eigenvalues).max()))
