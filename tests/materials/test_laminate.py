"""Ply stresses and strength ratios of the woven strip (``materials.laminate``) against
closed forms: the layers' mean stress is the beam stress, and Tsai-Wu and maximum stress both
give the uniaxial strength back for a stress along or across the fibres alone."""

import numpy as np
import pytest

from flexlink.materials.laminate import (PlyStrength, layer_stresses, max_stress_ratio,
                                         tsai_wu_ratio)
from flexlink.materials.mixtures import (load_constituent, rule_of_mixtures,
                                         woven_beam_modulus)

PLY = rule_of_mixtures(load_constituent("carbon_fiber"), load_constituent("polyester"), 0.5)
STRENGTH = PlyStrength(Xt=1800e6, Xc=1000e6, Yt=55e6, Yc=120e6, S=45e6)


@pytest.mark.parametrize("eps", [1e-3, -2e-4])
def test_layers_carry_the_beam_stress(eps):
    """The 0 and 90 degree layers' mean stress along the strip is E_beam eps (the narrow
    strip's modulus, ``woven_beam_modulus``), and across it nothing (free contraction)."""
    s = layer_stresses(PLY, eps)
    along = 0.5 * (s[0, 0] + s[1, 1])  # sigma1 of the 0 layer, sigma2 of the 90 layer
    across = 0.5 * (s[0, 1] + s[1, 0])
    assert along == pytest.approx(woven_beam_modulus(PLY) * eps, rel=1e-12)
    assert abs(across) < 1e-12 * abs(along)


@pytest.mark.parametrize("stress, strength", [((900e6, 0.0), 1800e6), ((-500e6, 0.0), 1000e6),
                                              ((0.0, 11e6), 55e6), ((0.0, -30e6), 120e6)])
def test_uniaxial_stress_gives_its_strength(stress, strength):
    """A stress along (or across) the fibres alone fails at Xt, Xc (Yt, Yc) by both criteria:
    R = strength / |sigma|."""
    expected = strength / max(abs(x) for x in stress)
    assert max_stress_ratio(np.array(stress), STRENGTH) == pytest.approx(expected, rel=1e-12)
    assert tsai_wu_ratio(np.array(stress), STRENGTH) == pytest.approx(expected, rel=1e-12)


def test_biaxial_tsai_wu_is_on_its_surface():
    """R sigma lies on the Tsai-Wu surface F1 s1 + F2 s2 + F11 s1^2 + F22 s2^2 + 2 F12 s1 s2
    = 1, written out here."""
    s1, s2 = 400e6, 20e6
    R = float(tsai_wu_ratio(np.array([s1, s2]), STRENGTH))
    p = STRENGTH
    F1, F2 = 1 / p.Xt - 1 / p.Xc, 1 / p.Yt - 1 / p.Yc
    F11, F22 = 1 / (p.Xt * p.Xc), 1 / (p.Yt * p.Yc)
    F12 = -0.5 * np.sqrt(F11 * F22)
    a, b = R * s1, R * s2
    assert F1 * a + F2 * b + F11 * a * a + F22 * b * b + 2 * F12 * a * b == pytest.approx(1.0,
                                                                                         rel=1e-12)
